#include "gl/render_geometry.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace clothlab {

sphere_mesh make_unit_sphere(int slices, int stacks) {
  sphere_mesh mesh;
  const float pi = std::numbers::pi_v<float>;
  // Vertex (slice, stack): longitude 2 pi slice / slices, colatitude pi stack / stacks.
  for (int stack = 0; stack <= stacks; ++stack) {
    const float colatitude = pi * static_cast<float>(stack) / static_cast<float>(stacks);
    for (int slice = 0; slice <= slices; ++slice) {
      const float longitude = 2.0f * pi * static_cast<float>(slice) / static_cast<float>(slices);
      mesh.vertices.push_back(std::sin(colatitude) * std::cos(longitude));
      mesh.vertices.push_back(std::sin(colatitude) * std::sin(longitude));
      mesh.vertices.push_back(std::cos(colatitude));
    }
  }
  const auto vertex = [slices](int slice, int stack) {
    return static_cast<std::uint32_t>(slice + (slices + 1) * stack);
  };
  for (int stack = 0; stack < stacks; ++stack) {
    for (int slice = 0; slice < slices; ++slice) {
      // Going down in colatitude then east in longitude is counter-clockwise from outside.
      const std::uint32_t quad[4] = {vertex(slice, stack), vertex(slice, stack + 1),
                                     vertex(slice + 1, stack + 1), vertex(slice + 1, stack)};
      mesh.indices.insert(mesh.indices.end(), {quad[0], quad[1], quad[2]});
      mesh.indices.insert(mesh.indices.end(), {quad[0], quad[2], quad[3]});
    }
  }
  return mesh;
}

void append_coil(const glm::vec3& a, const glm::vec3& b, const coil_shape& coil,
                 std::vector<float>& points) {
  const auto add = [&points](const glm::vec3& p) { points.insert(points.end(), {p.x, p.y, p.z}); };
  const glm::vec3 axis = b - a;
  const float length = glm::length(axis);
  const glm::vec3 along = length > 0.0f ? axis / length : glm::vec3(0.0f, 0.0f, -1.0f);
  // Two unit vectors perpendicular to the spring, for the helix.
  const glm::vec3 helper =
      std::abs(along.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 side = glm::normalize(glm::cross(along, helper));
  const glm::vec3 other_side = glm::cross(along, side);

  const glm::vec3 coil_start = a + coil.lead_fraction * axis;
  const glm::vec3 coil_axis = (1.0f - 2.0f * coil.lead_fraction) * axis;
  const int segments = coil.turns * coil.segments_per_turn;
  add(a);
  for (int i = 0; i <= segments; ++i) {
    const float s = static_cast<float>(i) / static_cast<float>(segments);
    const float angle = 2.0f * std::numbers::pi_v<float> * static_cast<float>(coil.turns) * s;
    // The radius opens from 0 at both ends of the helix so that it joins the straight leads.
    const float taper = std::min(1.0f, 8.0f * std::min(s, 1.0f - s));
    add(coil_start + s * coil_axis +
        coil.radius * taper * (std::cos(angle) * side + std::sin(angle) * other_side));
  }
  add(b);
}

cloth_indices make_cloth_indices(const spring_mesh& cloth) {
  const int n = cloth.grid_size();
  cloth_indices result;
  auto& indices = result.indices;
  const auto k = [n](int ku, int kv) {
    return static_cast<std::uint32_t>(spring_mesh::index(ku, kv, n));
  };
  const auto range_since = [&indices](std::size_t first) {
    return index_range{static_cast<std::uint32_t>(first),
                       static_cast<std::uint32_t>(indices.size() - first)};
  };

  // Cell (ku, kv) -> (ku+1, kv+1): triangles (00, 10, 11) and (00, 11, 01). Since
  // (p10 - p00) x (p11 - p00) points along d_u x d_v, they are counter-clockwise seen from
  // the side the vertex normals point to (the front face).
  std::size_t first = indices.size();
  for (int kv = 0; kv + 1 < n; ++kv) {
    for (int ku = 0; ku + 1 < n; ++ku) {
      // A torn cloth (tearing, an addition) leaves out the triangles that lost a spring.
      if (cloth.triangle_intact(ku, kv, false))
        indices.insert(indices.end(), {k(ku, kv), k(ku + 1, kv), k(ku + 1, kv + 1)});
      if (cloth.triangle_intact(ku, kv, true))
        indices.insert(indices.end(), {k(ku, kv), k(ku + 1, kv + 1), k(ku, kv + 1)});
    }
  }
  result.triangles = range_since(first);

  // Every triangle edge once: along u, along v, and the diagonal that splits each cell.
  first = indices.size();
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      if (ku + 1 < n && cloth.spring_intact(ku, kv, 1, 0))
        indices.insert(indices.end(), {k(ku, kv), k(ku + 1, kv)});
      if (kv + 1 < n && cloth.spring_intact(ku, kv, 0, 1))
        indices.insert(indices.end(), {k(ku, kv), k(ku, kv + 1)});
      if (ku + 1 < n && kv + 1 < n && cloth.spring_intact(ku, kv, 1, 1))
        indices.insert(indices.end(), {k(ku, kv), k(ku + 1, kv + 1)});
    }
  }
  result.edges = range_since(first);

  for (const spring_family family : all_spring_families) {
    first = indices.size();
    for (const spring& s : cloth.springs(family))
      indices.insert(indices.end(), {s.a, s.b});
    result.springs[static_cast<int>(family)] = range_since(first);
  }
  return result;
}

std::vector<float> make_grid_texture_coordinates(int n) {
  std::vector<float> uv;
  uv.reserve(2 * static_cast<std::size_t>(n) * n);
  const float last = static_cast<float>(std::max(n - 1, 1));
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      uv.push_back(static_cast<float>(ku) / last);
      uv.push_back(static_cast<float>(kv) / last);
    }
  }
  return uv;
}

std::vector<std::int32_t> make_grid_texels(int n) {
  std::vector<std::int32_t> texels;
  texels.reserve(2 * static_cast<std::size_t>(n) * n);
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku)
      texels.insert(texels.end(), {ku, kv});
  }
  return texels;
}

float drawn_mass_radius(float radius, float metres_per_pixel) {
  return std::max(radius, min_mass_pixels * metres_per_pixel);
}

float chain_floor_height(float top_z, std::span<const spring> springs, double mass, double gravity,
                         double stiffness) {
  double rest_lengths = 0.0;
  double static_stretch = 0.0;
  const auto count = static_cast<double>(springs.size());
  for (std::size_t i = 0; i < springs.size(); ++i) {
    const double masses_below = count - static_cast<double>(i);
    rest_lengths += springs[i].rest_length;
    if (stiffness > 0.0)
      static_stretch += masses_below * mass * gravity / stiffness;
  }
  const double margin = 0.3;  // m
  return top_z - static_cast<float>(rest_lengths + 2.0 * static_stretch + margin);
}

}  // namespace clothlab
