// The spring force (handout equation 2) and stages 1 and 2 (single spring, coupled springs):
// initial states from model.md and first steps computed by hand; the mouse drag on a mass
// (model.md, "Drag": F_d = K_d (q - p) added to the dragged mass's force).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/coupled_springs.hpp"
#include "core/particle_system.hpp"
#include "core/single_spring.hpp"
#include "core/spring.hpp"

namespace clothlab {
namespace {

void expect_vec_eq(const glm::dvec3& actual, const glm::dvec3& expected, const char* what) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(actual[c], expected[c]) << what << ", coordinate " << c;
  }
}

// p_a = (0, 0, 0), p_b = (3, 4, 0): |p_a - p_b| = 5, L0 = 4, K = 2:
// F_a = 2 (4 - 5) (-3, -4, 0) / 5 = (1.2, 1.6, 0), pulling a towards b; F_b = -F_a.
TEST(SpringForce, StretchedSpringMatchesEquationTwoOnBothEnds) {
  const glm::dvec3 a = {0.0, 0.0, 0.0};
  const glm::dvec3 b = {3.0, 4.0, 0.0};
  expect_vec_eq(spring_force(a, b, 2.0, 4.0), {1.2, 1.6, 0.0}, "F_a");
  expect_vec_eq(spring_force(b, a, 2.0, 4.0), {-1.2, -1.6, 0.0}, "F_b");
}

// A compressed spring pushes its ends apart: p_a = (0,0,1), p_b = (0,0,0), L0 = 3, K = 5:
// F_a = 5 (3 - 1) (0, 0, 1) / 1 = (0, 0, 10).
TEST(SpringForce, CompressedSpringPushesTheEndsApart) {
  const glm::dvec3 a = {0.0, 0.0, 1.0};
  const glm::dvec3 b = {0.0, 0.0, 0.0};
  expect_vec_eq(spring_force(a, b, 5.0, 3.0), {0.0, 0.0, 10.0}, "F_a");
  expect_vec_eq(spring_force(b, a, 5.0, 3.0), {0.0, 0.0, -10.0}, "F_b");
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

// ---- The mouse drag on a mass (issue 10; model.md, "Drag") ----------------------------------

void expect_vec_near(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance,
                     const char* what) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(actual[c], expected[c], tolerance) << what << ", coordinate " << c;
  }
}

// A stage (single spring, or a chain of one mass) with p1 = (0.7, 0, 0.2) at rest, pulled by the
// drag (K_d = 100) towards q = (0.2, 0.5, 0.4). K = 20, L0 = 0.5, p0 = (0.1, 0, 1):
//   d = p1 - p0 = (0.6, 0, -0.8), |d| = 1, spring F_s = 20 (0.5 - 1) d = (-6, 0, 8)
//   drag F_d = 100 (q - p1) = 100 (-0.5, 0.5, 0.2) = (-50, 50, 20)
//   F1 = F_s + F_d = (-56, 50, 28).
// One semi-implicit step (dt = 0.01, mu = 0.2, m = 1, g0 = 9.8) from v1 = 0:
//   v1' = 0.01 (F1 / m + g) = (-0.56, 0.5, 0.182), p1' = p1 + 0.01 v1' = (0.6944, 0.005, 0.20182)
// A chain of n masses in its initial state.
coupled_springs chain_of(int n) {
  coupled_springs_parameters p;
  p.mass_count = n;
  return coupled_springs(p);
}

template <class Stage>
void pull_p1_by_hand(Stage& stage) {
  stage.parameters.drag = {
      .enabled = true, .mass = 1, .target = {0.2, 0.5, 0.4}, .stiffness = 100.0};
  stage.particles().set_position(1, {0.7, 0.0, 0.2});
  stage.particles().set_velocity(1, {0.0, 0.0, 0.0});
}

TEST(SingleSpringDrag, ForceOnP1IsTheSpringPlusKdTimesTargetMinusPosition) {
  single_spring stage;
  pull_p1_by_hand(stage);
  stage.compute_force();
  expect_vec_near(stage.particles().get_force(1), {-56.0, 50.0, 28.0}, 1e-12, "F1");
  // The fixed p0 feels no force: the handout's code of section 2 computes p1's alone (and the
  // drag never acts on p0).
  expect_vec_near(stage.particles().get_force(0), {0.0, 0.0, 0.0}, 1e-12, "F0");
  stage.apply_force();
  expect_vec_near(stage.particles().get_velocity(1), {-0.56, 0.5, 0.182}, 1e-12, "v1");
  expect_vec_near(stage.particles().get_position(1), {0.6944, 0.005, 0.20182}, 1e-12, "p1");
}

// The chain's Q5 stub is exact for one mass (its only spring on mass 1), so this holds on the
// student's copy as well.
TEST(CoupledSpringsDrag, ForceOnTheOnlyMassIsTheSpringPlusKdTimesTargetMinusPosition) {
  coupled_springs stage = chain_of(1);
  pull_p1_by_hand(stage);
  stage.step();
  expect_vec_near(stage.particles().get_force(1), {-56.0, 50.0, 28.0}, 1e-12, "F1");
  expect_vec_near(stage.particles().get_velocity(1), {-0.56, 0.5, 0.182}, 1e-12, "v1");
  expect_vec_near(stage.particles().get_position(1), {0.6944, 0.005, 0.20182}, 1e-12, "p1");
}

// The fixed p0 cannot be dragged: a drag on particle 0 (or on no particle at all) adds nothing.
// Same state as above: F1 is the spring's (-6, 0, 8); the fixed p0 feels no force.
TEST(SingleSpringDrag, TheFixedPointCannotBeDragged) {
  for (const int mass : {0, 2, -1}) {
    single_spring stage;
    pull_p1_by_hand(stage);
    stage.parameters.drag.mass = mass;
    stage.step();
    expect_vec_near(stage.particles().get_force(0), {0.0, 0.0, 0.0}, 1e-12, "F0");
    expect_vec_near(stage.particles().get_force(1), {-6.0, 0.0, 8.0}, 1e-12, "F1");
    expect_vec_eq(stage.particles().get_position(0), {0.1, 0.0, 1.0}, "p0 stays");
  }
}

// Every integrator sees the drag at each of its stages: with no spring (K = 0), no gravity and
// no damping, a mass released at rest at p(0) is a harmonic oscillator about the target q,
//   p(t) = q + (p(0) - q) cos(omega t),   omega = sqrt(K_d / m).
// K_d = 100, m = 1: omega = 10; |p(0) - q| = 0.5; t = 0.1 (1000 steps of 1e-4 s). The worst
// scheme here (explicit Euler) grows the amplitude by exp(omega^2 dt^2 n / 2) - 1 = 5e-4.
// Without the drag (or with it at the start of the step only) the mass misses by 0.1 m or more.
template <class Stage>
void expect_every_integrator_oscillates_about_the_target(Stage stage, const char* name) {
  const glm::dvec3 start = {0.1, 0.0, 0.5};
  const glm::dvec3 q = {0.1, 0.3, 0.1};  // p(0) - q = (0, -0.3, 0.4)
  const double omega = 10.0, dt = 1e-4;
  const int steps = 1000;
  for (const integrator_kind kind : all_integrators) {
    stage.parameters.stiffness = 0.0;
    stage.parameters.dynamics = {
        .time_step = dt, .damping = 0.0, .mass = 1.0, .gravity = 0.0, .integrator = kind};
    stage.parameters.drag = {.enabled = true, .mass = 1, .target = q, .stiffness = 100.0};
    stage.load_model();
    stage.particles().set_position(1, start);
    stage.particles().set_velocity(1, {0.0, 0.0, 0.0});
    for (int i = 0; i < steps; ++i)
      stage.step();
    const glm::dvec3 expected = q + (start - q) * std::cos(omega * dt * steps);
    const glm::dvec3 p = stage.particles().get_position(1);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(p[c], expected[c], 2e-3)
          << name << ", integrator " << integrator_name(kind) << ", coordinate " << c;
    }
  }
}

TEST(SingleSpringDrag, EveryIntegratorOscillatesAboutTheTarget) {
  expect_every_integrator_oscillates_about_the_target(single_spring{}, "single spring");
}

TEST(CoupledSpringsDrag, EveryIntegratorOscillatesAboutTheTargetInAChainOfOne) {
  expect_every_integrator_oscillates_about_the_target(chain_of(1), "chain of one");
}

// Needs question 5's solution (every spring on both ends). A chain of three, mass 2 dragged
// (K_d = 100) towards q = (0.2, 0.5, 0); K = 20, L0 = 0.5, p0 = (0.1, 0, 1), s(a, b) the force of
// the spring a-b on a (equation 2):
//   p1 = (0.1, 0, 0.4):  s(p1, p0) = 20 (0.5 - 0.6) (0, 0, -1)         = (0, 0, 2)
//   p2 = (0.7, 0, -0.4): s(p2, p1) = 20 (0.5 - 1) (0.6, 0, -0.8)       = (-6, 0, 8)
//   p3 = (0.7, 0, -1.1): s(p3, p2) = 20 (0.5 - 0.7) (0, 0, -1)         = (0, 0, 4)
//   drag on p2: 100 (q - p2) = 100 (-0.5, 0.5, 0.4)                    = (-50, 50, 40)
//   F0 = -s(p1, p0) = (0, 0, -2)    F1 = s(p1, p0) - s(p2, p1) = (6, 0, -6)
//   F2 = s(p2, p1) - s(p3, p2) + drag = (-56, 50, 44)                  F3 = (0, 0, 4)
// One semi-implicit step from rest (dt = 0.01, m = 1, g0 = 9.8): v2' = 0.01 (F2 + g) =
// (-0.56, 0.5, 0.342), p2' = p2 + 0.01 v2' = (0.6944, 0.005, -0.39658).
// Tolerances: question 5's answer may compute the springs in single precision (float rounding,
// 1e-6, of forces of size 60), and may give the fixed p0 no force at all (p0 never moves): the
// drag must add nothing to it either way.
constexpr double chain_force_tolerance = 60 * 1e-6;  // N

void expect_fixed_point_force(const glm::dvec3& f0) {
  EXPECT_TRUE(glm::length(f0 - glm::dvec3(0.0, 0.0, -2.0)) <= chain_force_tolerance ||
              glm::length(f0) <= chain_force_tolerance)
      << "F0 = (" << f0.x << ", " << f0.y << ", " << f0.z
      << "): the reaction of spring 1, (0, 0, -2), or nothing; never the drag";
}

TEST(SolutionCoupledSpringsDrag, ForceOnTheDraggedMassIsTheSpringsPlusKdTimesTargetMinusPosition) {
  coupled_springs stage = chain_of(3);
  stage.parameters.drag = {
      .enabled = true, .mass = 2, .target = {0.2, 0.5, 0.0}, .stiffness = 100.0};
  const glm::dvec3 positions[] = {{0.1, 0, 1}, {0.1, 0, 0.4}, {0.7, 0, -0.4}, {0.7, 0, -1.1}};
  for (std::size_t k = 0; k < 4; ++k) {
    stage.particles().set_position(k, positions[k]);
    stage.particles().set_velocity(k, {0.0, 0.0, 0.0});
  }
  stage.step();
  const particle_system& particles = stage.particles();
  expect_fixed_point_force(particles.get_force(0));
  expect_vec_near(particles.get_force(1), {6.0, 0.0, -6.0}, chain_force_tolerance, "F1");
  expect_vec_near(particles.get_force(2), {-56.0, 50.0, 44.0}, chain_force_tolerance, "F2");
  expect_vec_near(particles.get_force(3), {0.0, 0.0, 4.0}, chain_force_tolerance, "F3");
  const double dt = 0.01;
  expect_vec_near(particles.get_velocity(2), {-0.56, 0.5, 0.342}, dt * chain_force_tolerance, "v2");
  expect_vec_near(particles.get_position(2), {0.6944, 0.005, -0.39658},
                  dt * dt * chain_force_tolerance + 1e-15, "p2");
  expect_vec_eq(particles.get_position(0), {0.1, 0.0, 1.0}, "p0 is fixed");
}

// Needs question 5's solution. A drag on the chain's fixed p0 adds nothing: same chain as above
// without the drag's (-50, 50, 40) on p2, and p0 feeling only its spring's reaction.
TEST(SolutionCoupledSpringsDrag, TheFixedPointCannotBeDragged) {
  coupled_springs stage = chain_of(3);
  stage.parameters.drag = {
      .enabled = true, .mass = 0, .target = {0.2, 0.5, 0.0}, .stiffness = 100.0};
  const glm::dvec3 positions[] = {{0.1, 0, 1}, {0.1, 0, 0.4}, {0.7, 0, -0.4}, {0.7, 0, -1.1}};
  for (std::size_t k = 0; k < 4; ++k)
    stage.particles().set_position(k, positions[k]);
  stage.compute_force();
  expect_fixed_point_force(stage.particles().get_force(0));
  expect_vec_near(stage.particles().get_force(2), {-6.0, 0.0, 4.0}, chain_force_tolerance, "F2");
}

}  // namespace
}  // namespace clothlab
