// What the cloth is made of beyond its state: the list of its springs (figure 6, each once, for
// the drawing, the energy, the implicit scheme's Jacobian and tearing) and its vertex normals
// (the wind, the drawing, the OBJ). None of it is a question of the lab.
#include <algorithm>

#include "core/grid_neighbours.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

std::array<spring_set, 3> spring_mesh::spring_sets() const {
  std::array<spring_set, 3> sets{};
  for (spring_family family : all_spring_families)
    sets[static_cast<int>(family)] = {springs(family), stiffness(family)};
  return sets;
}

// Every spring of figure 6 once, from its end of lower index, with its rest length, the
// distance of its ends in the flat cloth at rest (drawing, energy, the implicit scheme's
// Jacobian, tearing); every spring intact.
void spring_mesh::list_springs() {
  const int n = grid_size_;
  std::span<const glm::dvec3> x0 = as_vectors(rest_position_);
  for (spring_family family : all_spring_families) {
    std::vector<spring>& list = springs_[static_cast<int>(family)];
    list.clear();
    for (int kv = 0; kv < n; ++kv) {
      for (int ku = 0; ku < n; ++ku) {
        for (const grid_offset o : family_neighbours(family)) {
          const int ku2 = ku + o.du;
          const int kv2 = kv + o.dv;
          const std::size_t a = index(ku, kv, n);
          if (ku2 < 0 || ku2 >= n || kv2 < 0 || kv2 >= n || index(ku2, kv2, n) < a)
            continue;  // outside the grid, or already listed from the other end
          const std::size_t b = index(ku2, kv2, n);
          list.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                          glm::length(x0[a] - x0[b])});
        }
      }
    }
  }
  spring_torn_.assign(spring_slot(particles_.size(), -2, -2), 0);
}

void spring_mesh::compute_normals() {
  normals_.resize(particles_.position.size());
  compute_vertex_normals(grid_size_, particles_.position, normals_);
}

void compute_vertex_normals(int n, std::span<const double> position, std::span<double> normal) {
  auto p = [&](int ku, int kv) {
    const std::size_t k = 3 * spring_mesh::index(ku, kv, n);
    return glm::dvec3(position[k], position[k + 1], position[k + 2]);
  };
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      // Central differences, one-sided on the border.
      const glm::dvec3 du = p(std::min(ku + 1, n - 1), kv) - p(std::max(ku - 1, 0), kv);
      const glm::dvec3 dv = p(ku, std::min(kv + 1, n - 1)) - p(ku, std::max(kv - 1, 0));
      const glm::dvec3 c = glm::cross(du, dv);
      const glm::dvec3 unit = c / glm::length(c);
      const std::size_t k = 3 * spring_mesh::index(ku, kv, n);
      normal[k] = unit.x;
      normal[k + 1] = unit.y;
      normal[k + 2] = unit.z;
    }
  }
}

}  // namespace clothlab
