// The spring force (handout equation 2) and stages 1 and 2 (single spring, coupled springs):
// initial states from model.md and first steps computed by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "coupled_springs.hpp"
#include "particle_system.hpp"
#include "single_spring.hpp"
#include "spring.hpp"

namespace clothlab {
namespace {

void expect_vec_eq(const glm::dvec3& actual, const glm::dvec3& expected, const char* what) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(actual[c], expected[c]) << what << ", coordinate " << c;
  }
}

// p_a = (0, 0, 0), p_b = (3, 4, 0): |p_a - p_b| = 5, L0 = 4, K = 2:
// F_a = 2 (4 - 5) (-3, -4, 0) / 5 = (1.2, 1.6, 0), pulling a towards b; F_b = -F_a.
// The forces are added to what the array already holds.
TEST(SpringForce, StretchedSpringMatchesEquationTwoOnBothEnds) {
  const std::array<spring, 1> springs = {spring{0, 1, 4.0}};
  const std::vector<double> position = {0.0, 0.0, 0.0, 3.0, 4.0, 0.0};
  std::vector<double> force = {10.0, 0.0, 0.0, 0.0, 0.0, -1.0};
  accumulate_spring_forces(springs, 2.0, position, force);
  EXPECT_DOUBLE_EQ(force[0], 10.0 + 1.2);
  EXPECT_DOUBLE_EQ(force[1], 1.6);
  EXPECT_EQ(force[2], 0.0);
  EXPECT_DOUBLE_EQ(force[3], -1.2);
  EXPECT_DOUBLE_EQ(force[4], -1.6);
  EXPECT_EQ(force[5], -1.0);
}

// A compressed spring pushes its ends apart: p_a = (0,0,1), p_b = (0,0,0), L0 = 3, K = 5:
// F_a = 5 (3 - 1) (0, 0, 1) / 1 = (0, 0, 10).
TEST(SpringForce, CompressedSpringPushesTheEndsApart) {
  const std::array<spring, 1> springs = {spring{0, 1, 3.0}};
  const std::vector<double> position = {0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
  std::vector<double> force(6, 0.0);
  accumulate_spring_forces(springs, 5.0, position, force);
  EXPECT_DOUBLE_EQ(force[2], 10.0);
  EXPECT_DOUBLE_EQ(force[5], -10.0);
}

TEST(SingleSpring, InitialStateMatchesTheModel) {
  single_spring stage;
  stage.load_model();
  const particle_system& particles = stage.particles();
  ASSERT_EQ(particles.size(), 2u);
  expect_vec_eq(particles.get_position(0), {0.1, 0.0, 1.0}, "p0");
  expect_vec_eq(particles.get_position(1), {0.1, 0.0, 0.5}, "p1");
  EXPECT_EQ(particles.get_velocity(0), glm::dvec3(0.0));
  expect_vec_eq(particles.get_velocity(1), {1.0, -1.0, 0.0}, "v1");
  EXPECT_EQ(particles.is_fixed[0], 1);
  EXPECT_EQ(particles.is_fixed[1], 0);
  ASSERT_EQ(stage.springs().size(), 1u);
  const spring& s = stage.springs()[0];
  EXPECT_TRUE((s.a == 0 && s.b == 1) || (s.a == 1 && s.b == 0));
  EXPECT_DOUBLE_EQ(s.rest_length, 0.5);
}

// Defaults: dt = 0.01, mu = 0.2, K = 20, m = 1, g0 = 9.8. At the start the spring has its rest
// length (0.5), so its force is zero and only gravity acts:
//   v = (1, -1, 0)(1 - 0.2 * 0.01) + 0.01 (0, 0, -9.8) = (0.998, -0.998, -0.098)
//   semi-implicit: p = (0.1, 0, 0.5) + 0.01 v = (0.10998, -0.00998, 0.49902)
//   explicit:      p = (0.1, 0, 0.5) + 0.01 (1, -1, 0) = (0.11, -0.01, 0.5)
TEST(SingleSpring, FirstSemiImplicitStepMatchesTheHandComputation) {
  single_spring stage;
  stage.load_model();
  stage.step();
  const particle_system& particles = stage.particles();
  expect_vec_eq(particles.get_velocity(1), {0.998, -0.998, -0.098}, "v1");
  expect_vec_eq(particles.get_position(1), {0.10998, -0.00998, 0.49902}, "p1");
  expect_vec_eq(particles.get_position(0), {0.1, 0.0, 1.0}, "p0 is fixed");
  EXPECT_EQ(particles.get_velocity(0), glm::dvec3(0.0));
}

TEST(SingleSpring, FirstExplicitStepMatchesTheHandComputation) {
  single_spring stage;
  stage.parameters.dynamics.integrator = integrator_kind::explicit_euler;
  stage.load_model();
  stage.step();
  const particle_system& particles = stage.particles();
  expect_vec_eq(particles.get_velocity(1), {0.998, -0.998, -0.098}, "v1");
  expect_vec_eq(particles.get_position(1), {0.11, -0.01, 0.5}, "p1");
}

// Second semi-implicit step, where the spring is stretched: from the first step,
// d = p1 - p0 = (0.00998, -0.00998, -0.50098), |d| = sqrt(2 * 0.00998^2 + 0.50098^2),
// F = K (L0 - |d|) d / |d|, v2 = v1 (1 - mu dt) + dt (F/m + g), p2 = p1 + dt v2.
TEST(SingleSpring, SecondStepFollowsEquationTwo) {
  single_spring stage;
  stage.parameters.stiffness = 50.0;
  stage.parameters.dynamics.mass = 0.5;
  stage.load_model();
  stage.step();
  stage.step();
  const glm::dvec3 p1 = {0.10998, -0.00998, 0.49902};
  const glm::dvec3 v1 = {0.998, -0.998, -0.098};
  const glm::dvec3 d = p1 - glm::dvec3(0.1, 0.0, 1.0);
  const double length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  const glm::dvec3 force = 50.0 * (0.5 - length) / length * d;
  const glm::dvec3 v2 = v1 * (1.0 - 0.2 * 0.01) + 0.01 * (force / 0.5 + glm::dvec3(0, 0, -9.8));
  const glm::dvec3 p2 = p1 + 0.01 * v2;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(stage.particles().get_velocity(1)[c], v2[c], 1e-14) << "c = " << c;
    EXPECT_NEAR(stage.particles().get_position(1)[c], p2[c], 1e-14) << "c = " << c;
  }
  EXPECT_GT(force.z, 0.0) << "the stretched spring pulls p1 up";
}

TEST(CoupledSprings, InitialChainMatchesTheModel) {
  for (const int n : {1, 2, 5}) {
    coupled_springs stage;
    stage.parameters.mass_count = n;
    stage.load_model();
    const particle_system& particles = stage.particles();
    ASSERT_EQ(particles.size(), static_cast<std::size_t>(n + 1));
    ASSERT_EQ(stage.springs().size(), static_cast<std::size_t>(n));
    for (int i = 0; i <= n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      expect_vec_eq(particles.get_position(k), {0.1, 0.0, 1.0 - 0.5 * i}, "p_i");
      const glm::dvec3 v = i == n ? glm::dvec3(1.0, -1.0, 0.0) : glm::dvec3(0.0);
      EXPECT_EQ(particles.get_velocity(k), v) << "n = " << n << ", i = " << i;
      EXPECT_EQ(particles.is_fixed[k], i == 0 ? 1 : 0) << "n = " << n << ", i = " << i;
    }
    // spring i joins i-1 and i (in either order), rest length 0.5.
    for (int i = 1; i <= n; ++i) {
      const spring& s = stage.springs()[static_cast<std::size_t>(i - 1)];
      const auto lo = std::min(s.a, s.b);
      const auto hi = std::max(s.a, s.b);
      EXPECT_EQ(lo, static_cast<std::uint32_t>(i - 1));
      EXPECT_EQ(hi, static_cast<std::uint32_t>(i));
      EXPECT_DOUBLE_EQ(s.rest_length, 0.5);
    }
  }
}

// n = 3, defaults dt = 0.01, mu = 0.2, g0 = 9.8. Every spring starts at its rest length, so the
// first step is gravity and damping alone (semi-implicit):
//   masses 1, 2: v = (0, 0, -0.098), p = p_i + (0, 0, -0.00098)
//   mass 3:      v = (0.998, -0.998, -0.098), p = (0.1, 0, -0.5) + 0.01 v
TEST(CoupledSprings, FirstStepMatchesTheHandComputation) {
  coupled_springs stage;
  stage.parameters.mass_count = 3;
  stage.load_model();
  stage.step();
  const particle_system& particles = stage.particles();
  expect_vec_eq(particles.get_position(0), {0.1, 0.0, 1.0}, "p0 is fixed");
  expect_vec_eq(particles.get_velocity(1), {0.0, 0.0, -0.098}, "v1");
  expect_vec_eq(particles.get_velocity(2), {0.0, 0.0, -0.098}, "v2");
  expect_vec_eq(particles.get_velocity(3), {0.998, -0.998, -0.098}, "v3");
  expect_vec_eq(particles.get_position(1), {0.1, 0.0, 0.5 - 0.00098}, "p1");
  expect_vec_eq(particles.get_position(2), {0.1, 0.0, 0.0 - 0.00098}, "p2");
  expect_vec_eq(particles.get_position(3), {0.10998, -0.00998, -0.5 - 0.00098}, "p3");
}

}  // namespace
}  // namespace clothlab
