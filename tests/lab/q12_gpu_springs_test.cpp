// Question 12: the spring forces in the GPU step shader (shaders/gpu_step.frag). One GPU step,
// without gravity, damping, wind or ground, from a state set by hand: each particle's new
// velocity is dt F / m, F the sum of equation 2 over the springs of its up to 12 neighbours,
// computed here in double precision for the pairs named in each comment. The GPU computes in
// single precision: the tolerances allow for it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gl_fixture.hpp"
#include "gpu_cloth.hpp"
#include "lab_check.hpp"
#include "spring_mesh.hpp"

namespace clothlab {
namespace {

using Q12GpuSprings = lab::OffscreenGl;

constexpr double K_structural = 100.0, K_shear = 50.0, K_bending = 20.0;  // N/m
constexpr double dt = 0.01;                                               // s

// 5 x 5, S = 4 (h = 1): s(ku, kv) = (-2 + ku, -2 + kv, 0); no gravity, damping, pins, ground.
cloth_parameters still_cloth() {
  cloth_parameters p;
  p.grid_size = 5;
  p.side_length = 4.0;
  p.structural_stiffness = K_structural;
  p.shear_stiffness = K_shear;
  p.bending_stiffness = K_bending;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.dynamics = {.time_step = dt, .damping = 0.0, .mass = 1.0, .gravity = 0.0};
  return p;
}

glm::dvec3 rest_position(int ku, int kv) {
  return {-2.0 + ku, -2.0 + kv, 0.0};
}

// The force on s(ku, kv) at rest position, except s(2, 2) moved to c, by hand: its springs to
// the 12 neighbours of figure 6 that are inside the grid, each by equation 2.
glm::dvec3 expected_force(int ku, int kv, const glm::dvec3& c) {
  struct neighbour {
    int du, dv;
    double K, L0;
  };
  const double r2 = std::sqrt(2.0);
  const neighbour neighbours[] = {
      {1, 0, K_structural, 1},  {-1, 0, K_structural, 1}, {0, 1, K_structural, 1},
      {0, -1, K_structural, 1}, {1, 1, K_shear, r2},      {-1, -1, K_shear, r2},
      {1, -1, K_shear, r2},     {-1, 1, K_shear, r2},     {2, 0, K_bending, 2},
      {-2, 0, K_bending, 2},    {0, 2, K_bending, 2},     {0, -2, K_bending, 2}};
  const auto at = [&](int u, int v) { return u == 2 && v == 2 ? c : rest_position(u, v); };
  glm::dvec3 f(0.0);
  for (const neighbour& n : neighbours) {
    const int u = ku + n.du, v = kv + n.dv;
    if (u >= 0 && u < 5 && v >= 0 && v < 5)
      f += spring_force(at(ku, kv), at(u, v), n.K, n.L0);
  }
  return f;
}

// Moves s(2, 2) to c, runs one GPU step and reads the state back into `cloth`.
spring_mesh one_gpu_step(const glm::dvec3& c) {
  const cloth_parameters p = still_cloth();
  spring_mesh cloth(p);
  cloth.particles().set_position(spring_mesh::index(2, 2, 5), c);
  gpu_cloth gpu;
  std::string error;
  EXPECT_TRUE(gpu.load(cloth, error)) << error;
  gpu.step(p);
  gpu.read_state(cloth);
  return cloth;
}

glm::dvec3 velocity_of(const spring_mesh& cloth, int ku, int kv) {
  return cloth.particles().get_velocity(spring_mesh::index(ku, kv, 5));
}

TEST_F(Q12GpuSprings, TheDisplacedCentreFeelsAllTwelveSprings) {
  const glm::dvec3 c = {0.3, -0.2, 0.5};
  const spring_mesh cloth = one_gpu_step(c);
  LAB_EXPECT_VEC(velocity_of(cloth, 2, 2), dt * expected_force(2, 2, c), 1e-4,
                 "Q12: the centre texel (2, 2), moved off its rest place, should be pulled back "
                 "by the springs to its 12 neighbours (4 structural, 4 shear, 4 bending): its new "
                 "velocity is dt F / m. Does the velocity shader add the spring forces?");
}

TEST_F(Q12GpuSprings, EachNeighbourFeelsItsSpringToTheCentre) {
  const glm::dvec3 c = {0.3, -0.2, 0.5};
  const spring_mesh cloth = one_gpu_step(c);
  const struct {
    int ku, kv;
    const char* family;
  } neighbours[] = {{3, 2, "structural"}, {2, 1, "structural"}, {3, 3, "shear"},
                    {1, 3, "shear"},      {4, 2, "bending"},    {2, 0, "bending"}};
  for (const auto& n : neighbours) {
    LAB_EXPECT_VEC(velocity_of(cloth, n.ku, n.kv), dt * expected_force(n.ku, n.kv, c), 1e-4,
                   "Q12: texel (" + std::to_string(n.ku) + ", " + std::to_string(n.kv) +
                       ") should feel its " + n.family +
                       " spring to the displaced centre (2, 2), and nothing else");
  }
}

TEST_F(Q12GpuSprings, ACornerTexelReadsNoNeighbourOutsideTheGrid) {
  const cloth_parameters p = still_cloth();
  spring_mesh cloth(p);
  const glm::dvec3 corner = {-2.4, -2.3, 0.2};
  cloth.particles().set_position(0, corner);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  gpu.step(p);
  gpu.read_state(cloth);
  const glm::dvec3 f = spring_force(corner, rest_position(1, 0), K_structural, 1) +
                       spring_force(corner, rest_position(0, 1), K_structural, 1) +
                       spring_force(corner, rest_position(1, 1), K_shear, std::sqrt(2.0)) +
                       spring_force(corner, rest_position(2, 0), K_bending, 2) +
                       spring_force(corner, rest_position(0, 2), K_bending, 2);
  LAB_EXPECT_VEC(cloth.particles().get_velocity(0), dt * f, 1e-4,
                 "Q12: the corner texel (0, 0) has springs to (1, 0), (0, 1), (1, 1), (2, 0) "
                 "and (0, 2) only: texels outside the N x N grid must be skipped");
}

}  // namespace
}  // namespace clothlab
