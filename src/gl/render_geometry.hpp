// The geometry the renderer sends to the GPU, built on the CPU with no GL call, so that it can
// be tested without a context: the sphere mesh of the masses, the coils of the springs, the
// triangles, edges and springs of the cloth grid, and where the floor goes under a chain.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/spring.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

// A unit sphere centred on the origin: xyz per vertex (also its outward normal), triangles
// wound counter-clockwise when seen from outside.
struct sphere_mesh {
  std::vector<float> vertices;         // 3 floats per vertex
  std::vector<std::uint32_t> indices;  // 3 per triangle
};
sphere_mesh make_unit_sphere(int slices, int stacks);

// A spring drawn as a helix between its two ends: straight leads at both ends, `turns` turns of
// constant radius in between, so that a stretched spring shows wider-spaced coils.
struct coil_shape {
  float radius = 0.04f;  // m
  int turns = 10;
  int segments_per_turn = 12;
  float lead_fraction = 0.12f;  // of the length, straight at each end
  int vertex_count() const { return turns * segments_per_turn + 3; }  // a line strip
};
// Appends coil.vertex_count() points (xyz) of the line strip from a to b.
void append_coil(const glm::vec3& a, const glm::vec3& b, const coil_shape& coil,
                 std::vector<float>& points);

// A range of an index buffer, in indices.
struct index_range {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

// One index buffer for the N x N cloth (particle k = ku + N kv): the triangles (two per cell,
// counter-clockwise seen from the side its normal d_u x d_v points to), the triangle edges as
// line pairs (wireframe), then the springs of each family as line pairs.
struct cloth_indices {
  std::vector<std::uint32_t> indices;
  index_range triangles;
  index_range edges;
  std::array<index_range, 3> springs;  // indexed by spring_family
};
cloth_indices make_cloth_indices(const spring_mesh& cloth);

// Texture coordinates of the grid: (u, v) = (ku, kv) / (N - 1), 2 floats per particle.
std::vector<float> make_grid_texture_coordinates(int n);
// Texel of each particle in the N x N state textures: (ku, kv), 2 ints per particle.
std::vector<std::int32_t> make_grid_texels(int n);

// The radii of the spheres that draw stages 1 and 2 (the mouse picks a mass by them), m.
inline constexpr float chain_mass_radius = 0.085f;         // a moving mass
inline constexpr float chain_fixed_point_radius = 0.045f;  // the fixed p0

// The radius a mass (or the fixed p0) of stages 1 and 2 is drawn with, and picked by: its own
// (above), or min_mass_pixels pixels where the view is so far away that it would be smaller (a
// long chain framed whole: at n = 10 a 0.085 m mass is under a pixel). metres_per_pixel:
// camera::metres_per_pixel.
inline constexpr float min_mass_pixels = 3.0f;
float drawn_mass_radius(float radius, float metres_per_pixel);

// Height of the floor drawn under a chain hanging from a fixed point at height top_z (stages 1
// and 2). Spring i carries the weight of every mass below it, so at rest it is stretched by
// (masses below) m g / K beyond its rest length. The masses start at the springs' rest lengths,
// so (like an undamped oscillator released from rest) they swing down to about twice the static
// stretch below the start; the floor goes a little below that.
float chain_floor_height(float top_z, std::span<const spring> springs, double mass, double gravity,
                         double stiffness);

}  // namespace clothlab
