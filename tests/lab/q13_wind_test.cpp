// Question 13: the wind, F_w = K_w <n, u_w> n on every vertex (n its unit normal, u_w the unit
// wind direction), on the CPU (spring_mesh::compute_force) and on the GPU (shaders/gpu_step.frag).
// The springs are off (stiffness 0) or at rest, so the wind is the only force. Every case is
// checked on both paths: the flat cloth, the tilted cloth (<n, u_w> < 0), the wind opposite the
// normal, a curved cloth whose normals all differ, and no wind. Tolerances: float_rounding of the
// wind force K_w (lab_check.hpp), in single or double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gl_fixture.hpp"
#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::gpu_cloth;
using student::spring_mesh;

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

// "vertex 5 = s(1, 1)"
std::string vertex(std::size_t k, int n) {
  return format(tr("vertex %zu = s(%zu, %zu)"), k, k % std::size_t(n), k / std::size_t(n));
}

// The cloth of windy_cloth turned by 30 degrees about x: s(ku, kv) = (x, y cos 30, y sin 30),
// whose normal is n = (0, -sin 30, cos 30) = (0, -0.5, 0.866).
void tilt(spring_mesh& cloth) {
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    const glm::dvec3 p = cloth.particles().get_position(k);
    cloth.particles().set_position(k, {p.x, p.y * c, p.y * s});
  }
}

// A 4 x 4 cloth bent in both directions, z = 0.3 sin(3 x + 1) + 0.25 cos(4 y): every vertex has
// its own normal, and a wind along (1, 2, 0.5) meets some from the front (<n, u_w> > 0), some
// from the back (<n, u_w> < 0).
void curve(spring_mesh& cloth) {
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    const glm::dvec3 p = cloth.particles().get_position(k);
    cloth.particles().set_position(
        k, {p.x, p.y, 0.3 * std::sin(3 * p.x + 1) + 0.25 * std::cos(4 * p.y)});
  }
}

// The wind force on every vertex by hand: F_w = K_w <n, u_w> n, with n the normal of model.md
// (central differences, one-sided on the border: n = normalize(d_u x d_v)) and u_w = direction
// normalised.
std::vector<glm::dvec3> expected_wind(const spring_mesh& cloth, double K_w,
                                      const glm::dvec3& direction) {
  const int n = cloth.grid_size();
  const auto p = [&](int ku, int kv) {
    return cloth.particles().get_position(spring_mesh::index(ku, kv, n));
  };
  const glm::dvec3 u_w = direction / glm::length(direction);
  std::vector<glm::dvec3> force;
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      const glm::dvec3 d_u = p(std::min(ku + 1, n - 1), kv) - p(std::max(ku - 1, 0), kv);
      const glm::dvec3 d_v = p(ku, std::min(kv + 1, n - 1)) - p(ku, std::max(kv - 1, 0));
      const glm::dvec3 normal = glm::normalize(glm::cross(d_u, d_v));
      force.push_back(K_w * glm::dot(normal, u_w) * normal);
    }
  }
  return force;
}

using lab::gpu_forces;  // one GPU step's force on each texel (gl_fixture.hpp)

// The rounding of a wind force of strength K_w, in single or double precision (the GPU's normals
// are single precision: a rounding of the same size).
double wind_tolerance(double K_w) {
  return lab::rounding(K_w);
}

// What a wind force of the wrong sign says.
// (A function: the catalogue is read once main has started.)
std::string reversed_wind() {
  return tr(
      "the wind force has the wrong sign: F_w = K_w <n, u_w> n pushes the cloth towards "
      "the side the wind blows to, along the normal; <n, u_w> is negative where the wind "
      "meets the other side of the cloth, and keeps its sign");
}

// Flat cloth: n = (0, 0, 1). Direction (0, 3, 4) -> u_w = (0, 0.6, 0.8), <n, u_w> = 0.8, and
// with K_w = 3 every vertex feels F_w = 3 * 0.8 * (0, 0, 1) = (0, 0, 2.4).
TEST(Q13Wind, AFlatClothFeelsTheWindAlongItsNormal) {
  spring_mesh cloth(windy_cloth(3.0, {0, 3, 4}));
  cloth.compute_force();
  LAB_EXPECT_EVERY_FORCE(
      k, cloth.particles().size(), cloth.particles().get_force(k), glm::dvec3(0, 0, 2.4),
      wind_tolerance(3.0),
      format(tr("Q13: on the flat cloth (n = (0, 0, 1)) a wind of strength K_w = 3 blowing along "
                "(0, 3, 4) (u_w = (0, 0.6, 0.8) once normalised) pushes every vertex with "
                "K_w <n, u_w> n = (0, 0, 2.4); vertex %zu"),
             std::size_t(k)),
      std::string("Q13") + colon() + reversed_wind());
}

// The cloth turned by 30 degrees about x: s(ku, kv) = (x, y cos 30, y sin 30), whose normal is
// n = (0, -sin 30, cos 30) = (0, -0.5, 0.866). Wind along y, K_w = 5: <n, u_w> = -0.5,
// F_w = 5 (-0.5) n = (0, 1.25, -2.165): the wind pushes along the normal, not along itself.
TEST(Q13Wind, ATiltedClothIsPushedAlongItsNormalNotAlongTheWind) {
  spring_mesh cloth(windy_cloth(5.0, {0, 1, 0}));
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  tilt(cloth);
  cloth.compute_force();
  const glm::dvec3 n = {0, -s, c};
  LAB_EXPECT_EVERY_FORCE(
      k, cloth.particles().size(), cloth.particles().get_force(k), 5.0 * -s * n,
      wind_tolerance(5.0),
      format(tr("Q13: a cloth tilted by 30 degrees (n = (0, -0.5, 0.866)) in a wind of strength 5 "
                "along y should feel K_w <n, u_w> n = (0, 1.25, -2.165); vertex %zu"),
             std::size_t(k)),
      std::string("Q13") + colon() + reversed_wind());
}

// Flat cloth (n = (0, 0, 1)), wind of strength 4 blowing down along (0, 0, -2), against the
// normal: u_w = (0, 0, -1), <n, u_w> = -1, F_w = 4 (-1) (0, 0, 1) = (0, 0, -4): pushed down.
TEST(Q13Wind, AWindAgainstTheNormalPushesTheOtherWay) {
  spring_mesh cloth(windy_cloth(4.0, {0, 0, -2}));
  cloth.compute_force();
  LAB_EXPECT_EVERY_FORCE(
      k, cloth.particles().size(), cloth.particles().get_force(k), glm::dvec3(0, 0, -4),
      wind_tolerance(4.0),
      format(tr("Q13: a wind blowing down (u_w = (0, 0, -1)) on the flat cloth (n = (0, 0, 1)) "
                "has <n, u_w> = -1 and pushes every vertex DOWN with K_w <n, u_w> n = (0, 0, -4) "
                "(keep the sign of <n, u_w>); %s"),
             vertex(k, 4).c_str()),
      std::string("Q13") + colon() + reversed_wind());
}

// The curved cloth (see curve): every vertex feels K_w <n, u_w> n with its own normal.
TEST(Q13Wind, EveryVertexOfACurvedClothFeelsTheWindOnItsOwnNormal) {
  const glm::dvec3 direction = {1, 2, 0.5};
  spring_mesh cloth(windy_cloth(3.0, direction));
  curve(cloth);
  const std::vector<glm::dvec3> expected = expected_wind(cloth, 3.0, direction);
  cloth.compute_force();
  LAB_EXPECT_EVERY_VEC(k, cloth.particles().size(), cloth.particles().get_force(k), expected[k],
                       wind_tolerance(3.0),
                       format(tr("Q13: on a curved cloth each vertex has its own normal "
                                 "n(ku, kv); a wind of strength 3 along (1, 2, 0.5) pushes it "
                                 "with K_w <n, u_w> n, u_w the unit direction, along n, towards "
                                 "the side the wind blows (<n, u_w> may be negative); %s"),
                              vertex(k, 4).c_str()));
}

TEST(Q13Wind, NoWindNoForce) {
  spring_mesh cloth(windy_cloth(0.0, {0, 1, 0}));
  cloth.compute_force();
  LAB_EXPECT_EVERY_VEC(k, cloth.particles().size(), cloth.particles().get_force(k), glm::dvec3(0.0),
                       0.0, tr("Q13: with K_w = 0 there is no wind force"));
}

using Q13GpuWind = lab::OffscreenGl;

// The flat cloth again, on the GPU, one step without gravity: v = dt F_w / m
// = 0.01 (0, 0, 2.4) / 2 = (0, 0, 0.012), in single precision.
TEST_F(Q13GpuWind, TheGpuStepAddsTheWindAlongTheNormal) {
  const cloth_parameters p = windy_cloth(3.0, {0, 3, 4});
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  const bool loaded = gpu.load(cloth, error);
  LAB_ASSERT_TRUE(loaded, error);
  gpu.step(p);
  gpu.read_state(cloth);
  LAB_EXPECT_EVERY_VEC(
      k, cloth.particles().size(), cloth.particles().get_velocity(k), glm::dvec3(0, 0, 0.012),
      0.01 / 2.0 * wind_tolerance(3.0),
      format(tr("Q13 (GPU): the velocity shader should add K_w <n, u_w> n to the force: after one "
                "step of 0.01 s a 2 kg vertex of the flat cloth in a wind of strength 3 along "
                "(0, 3, 4) moves at (0, 0, 0.012); texel %zu"),
             std::size_t(k)));
}

// The tilted cloth of the CPU test on the GPU: n = (0, -0.5, 0.866), wind of strength 5 along y,
// <n, u_w> = -0.5, F_w = (0, 1.25, -2.165).
TEST_F(Q13GpuWind, ATiltedClothIsPushedAlongItsNormalNotAlongTheWind) {
  const cloth_parameters p = windy_cloth(5.0, {0, 1, 0});
  spring_mesh cloth(p);
  tilt(cloth);
  const std::vector<glm::dvec3> force = gpu_forces(cloth, p);
  const glm::dvec3 n = {0, -0.5, std::cos(M_PI / 6)};
  LAB_EXPECT_EVERY_FORCE(
      k, force.size(), force[k], 5.0 * -0.5 * n, wind_tolerance(5.0),
      format(tr("Q13 (GPU): a cloth tilted by 30 degrees (n = (0, -0.5, 0.866)) in a wind of "
                "strength 5 along y has <n, u_w> = -0.5 (negative: keep its sign) and should feel "
                "K_w <n, u_w> n = (0, 1.25, -2.165), along n, not along the wind; %s"),
             vertex(k, 4).c_str()),
      std::string("Q13 (GPU)") + colon() + reversed_wind());
}

// The flat cloth on the GPU in a wind blowing down: F_w = (0, 0, -4).
TEST_F(Q13GpuWind, AWindAgainstTheNormalPushesTheOtherWay) {
  const cloth_parameters p = windy_cloth(4.0, {0, 0, -2});
  const spring_mesh cloth(p);
  const std::vector<glm::dvec3> force = gpu_forces(cloth, p);
  LAB_EXPECT_EVERY_FORCE(k, force.size(), force[k], glm::dvec3(0, 0, -4), wind_tolerance(4.0),
                         format(tr("Q13 (GPU): a wind blowing down (u_w = (0, 0, -1)) on the "
                                   "flat cloth (n = (0, 0, 1)) has <n, u_w> = -1 and pushes every "
                                   "texel DOWN with K_w <n, u_w> n = (0, 0, -4); %s"),
                                vertex(k, 4).c_str()),
                         std::string("Q13 (GPU)") + colon() + reversed_wind());
}

// The curved cloth on the GPU: each texel's own normal, read from normal_texture at that texel.
TEST_F(Q13GpuWind, EveryTexelOfACurvedClothFeelsTheWindOnItsOwnNormal) {
  const glm::dvec3 direction = {1, 2, 0.5};
  const cloth_parameters p = windy_cloth(3.0, direction);
  spring_mesh cloth(p);
  curve(cloth);
  const std::vector<glm::dvec3> expected = expected_wind(cloth, 3.0, direction);
  const std::vector<glm::dvec3> force = gpu_forces(cloth, p);
  LAB_EXPECT_EVERY_VEC(
      k, force.size(), force[k], expected[k], wind_tolerance(3.0),
      format(tr("Q13 (GPU): on a curved cloth each texel has its own normal n, read from "
                "normal_texture at this texel k; a wind of strength 3 along (1, 2, 0.5) pushes it "
                "with K_w <n, u_w> n (<n, u_w> may be negative); %s"),
             vertex(k, 4).c_str()));
}

TEST_F(Q13GpuWind, NoWindNoForce) {
  const cloth_parameters p = windy_cloth(0.0, {0, 1, 0});
  spring_mesh cloth(p);
  curve(cloth);
  const std::vector<glm::dvec3> force = gpu_forces(cloth, p);
  LAB_EXPECT_EVERY_VEC(
      k, force.size(), force[k], glm::dvec3(0.0), 0.0,
      format(tr("Q13 (GPU): with K_w = 0 there is no wind force; %s"), vertex(k, 4).c_str()));
}

}  // namespace
}  // namespace clothlab
