// Question 13: the wind, F_w = K_w <n, u_w> n on every vertex (n its unit normal, u_w the unit
// wind direction), on the CPU (spring_mesh::compute_force) and on the GPU (shaders/gpu_step.frag).
// The springs are off (stiffness 0) or at rest, so the wind is the only force.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gl_fixture.hpp"
#include "gpu_cloth.hpp"
#include "lab_check.hpp"
#include "spring_mesh.hpp"

namespace clothlab {
namespace {

cloth_parameters windy_cloth(double strength, const glm::dvec3& direction) {
  cloth_parameters p;
  p.grid_size = 4;
  p.structural_stiffness = 0.0;
  p.shear_stiffness = 0.0;
  p.bending_stiffness = 0.0;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.wind_strength = strength;
  p.wind_direction = direction;
  p.dynamics = {.time_step = 0.01, .damping = 0.0, .mass = 2.0, .gravity = 0.0};
  return p;
}

// Flat cloth: n = (0, 0, 1). Direction (0, 3, 4) -> u_w = (0, 0.6, 0.8), <n, u_w> = 0.8, and
// with K_w = 3 every vertex feels F_w = 3 * 0.8 * (0, 0, 1) = (0, 0, 2.4).
TEST(Q13Wind, AFlatClothFeelsTheWindAlongItsNormal) {
  spring_mesh cloth(windy_cloth(3.0, {0, 3, 4}));
  cloth.compute_force();
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    LAB_EXPECT_VEC(cloth.particles().get_force(k), glm::dvec3(0, 0, 2.4), 1e-12,
                   "Q13: on the flat cloth (n = (0, 0, 1)) a wind of strength K_w = 3 blowing "
                   "along (0, 3, 4) (u_w = (0, 0.6, 0.8) once normalised) pushes every vertex "
                   "with K_w <n, u_w> n = (0, 0, 2.4); vertex " +
                       std::to_string(k));
}

// The cloth turned by 30 degrees about x: s(ku, kv) = (x, y cos 30, y sin 30), whose normal is
// n = (0, -sin 30, cos 30) = (0, -0.5, 0.866). Wind along y, K_w = 5: <n, u_w> = -0.5,
// F_w = 5 (-0.5) n = (0, 1.25, -2.165): the wind pushes along the normal, not along itself.
TEST(Q13Wind, ATiltedClothIsPushedAlongItsNormalNotAlongTheWind) {
  spring_mesh cloth(windy_cloth(5.0, {0, 1, 0}));
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    const glm::dvec3 p = cloth.particles().get_position(k);
    cloth.particles().set_position(k, {p.x, p.y * c, p.y * s});
  }
  cloth.compute_force();
  const glm::dvec3 n = {0, -s, c};
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    LAB_EXPECT_VEC(cloth.particles().get_force(k), 5.0 * -s * n, 1e-9,
                   "Q13: a cloth tilted by 30 degrees (n = (0, -0.5, 0.866)) in a wind of "
                   "strength 5 along y should feel K_w <n, u_w> n = (0, 1.25, -2.165); vertex " +
                       std::to_string(k));
}

TEST(Q13Wind, NoWindNoForce) {
  spring_mesh cloth(windy_cloth(0.0, {0, 1, 0}));
  cloth.compute_force();
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    LAB_EXPECT_VEC(cloth.particles().get_force(k), glm::dvec3(0.0), 0.0,
                   "Q13: with K_w = 0 there is no wind force");
}

using Q13GpuWind = lab::OffscreenGl;

// The flat cloth again, on the GPU, one step without gravity: v = dt F_w / m
// = 0.01 (0, 0, 2.4) / 2 = (0, 0, 0.012), in single precision.
TEST_F(Q13GpuWind, TheGpuStepAddsTheWindAlongTheNormal) {
  const cloth_parameters p = windy_cloth(3.0, {0, 3, 4});
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  gpu.step(p);
  gpu.read_state(cloth);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    LAB_EXPECT_VEC(cloth.particles().get_velocity(k), glm::dvec3(0, 0, 0.012), 1e-7,
                   "Q13 (GPU): the velocity shader should add K_w <n, u_w> n to the force: after "
                   "one step of 0.01 s a 2 kg vertex of the flat cloth in a wind of strength 3 "
                   "along (0, 3, 4) moves at (0, 0, 0.012); texel " +
                       std::to_string(k));
}

}  // namespace
}  // namespace clothlab
