// Question 4: the predicted step-size limits against the schemes' own amplification and against
// measured divergence; the Gershgorin bound against exact frequencies; the divergence check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/coupled_springs.hpp"
#include "core/energy.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"
#include "core/stability.hpp"
#include "oscillator.hpp"

namespace clothlab {
namespace {

// Runs the stage for a number of steps; returns the first step at which divergence_check fails,
// or 0 when it never does.
template <class Stage>
long divergence_step(Stage& stage, long steps) {
  for (long s = 1; s <= steps; ++s) {
    stage.step();
    if (divergence_check(stage).diverged)
      return s;
  }
  return 0;
}

single_spring undamped_spring(double stiffness, double time_step) {
  single_spring_parameters p;  // the stage as loaded: gravity on, swinging (1, -1, 0) start
  p.stiffness = stiffness;
  p.dynamics.damping = 0.0;
  p.dynamics.time_step = time_step;
  return single_spring(p);
}

TEST(GershgorinBound, IsExactForTheSingleSpring) {
  for (double k : {1.0, 20.0, 4000.0}) {
    single_spring spring = undamped_spring(k, 0.01);
    spring.parameters.dynamics.mass = 2.0;
    EXPECT_DOUBLE_EQ(estimate_stability(spring).omega_max, std::sqrt(k / 2.0));
  }
}

// The chain fixed at the top: omega_j = 2 sqrt(K/m) sin((2j - 1) pi / (2 (2n + 1))), j = 1..n
// (the tridiagonal stiffness matrix with a free end). The bound is sqrt(3 K/m) for n = 2 (the
// upper mass: two springs, one moving neighbour) and sqrt(4 K/m) for n >= 3.
TEST(GershgorinBound, BoundsTheChainsHighestFrequencyFromAbove) {
  constexpr double k = 20.0, m = 1.0;
  for (int n : {1, 2, 3, 5, 10, 40}) {
    coupled_springs_parameters p;
    p.stiffness = k;
    p.mass_count = n;
    const coupled_springs chain(p);
    const double exact =
        2 * std::sqrt(k / m) * std::sin((2.0 * n - 1) * std::numbers::pi / (2.0 * (2 * n + 1)));
    const double bound = estimate_stability(chain).omega_max;
    const double expected_bound = n == 1   ? std::sqrt(k / m)
                                  : n == 2 ? std::sqrt(3 * k / m)
                                           : std::sqrt(4 * k / m);
    EXPECT_DOUBLE_EQ(bound, expected_bound) << "n = " << n;
    EXPECT_GE(bound, exact * (1 - 1e-12)) << "n = " << n;
  }
}

// An interior particle of the cloth has 4 springs of each family, all to moving particles:
// omega_max^2 <= 2 (4 K_struct + 4 K_shear + 4 K_bend) / m.
TEST(GershgorinBound, CountsTheClothsTwelveInteriorSprings) {
  cloth_parameters p;
  p.grid_size = 8;
  p.dynamics.mass = 0.5;
  const spring_mesh cloth(p);
  const double expected =
      std::sqrt(8 * (p.structural_stiffness + p.shear_stiffness + p.bending_stiffness) / 0.5);
  EXPECT_DOUBLE_EQ(estimate_stability(cloth).omega_max, expected);
}

// The closed forms of stability.hpp against the schemes' amplification factors: just below the
// limit every mode is bounded, just above one grows.
TEST(StepSizeLimit, ClosedFormsMatchTheSchemesAmplification) {
  for (integrator_kind kind : all_integrators) {
    if (kind == integrator_kind::implicit_euler)
      continue;
    for (double damping : {0.0, 0.5, 3.0}) {
      if (kind == integrator_kind::explicit_euler && damping == 0.0)
        continue;
      const double omega = 10.0;
      const double limit = time_step_limit(kind, omega, damping);
      EXPECT_LE(amplification_factor(kind, omega, damping, 0.999 * limit), 1 + 1e-12)
          << integrator_name(kind) << " mu = " << damping;
      EXPECT_GT(amplification_factor(kind, omega, damping, 1.001 * limit), 1 + 1e-9)
          << integrator_name(kind) << " mu = " << damping;
    }
  }
}

TEST(StepSizeLimit, HandDerivedValues) {
  constexpr double omega = 4.0;
  constexpr double infinity = std::numeric_limits<double>::infinity();
  EXPECT_DOUBLE_EQ(time_step_limit(integrator_kind::semi_implicit, omega, 0.0), 0.5);  // 2/omega
  // (omega dt)^2 + 2 mu dt = 4 with mu = 6: 16 dt^2 + 12 dt - 4 = 0, dt = 1/4.
  EXPECT_DOUBLE_EQ(time_step_limit(integrator_kind::semi_implicit, omega, 6.0), 0.25);
  EXPECT_EQ(time_step_limit(integrator_kind::explicit_euler, omega, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(time_step_limit(integrator_kind::explicit_euler, omega, 2.0), 2.0 / 16.0);
  EXPECT_DOUBLE_EQ(time_step_limit(integrator_kind::velocity_verlet, omega, 0.0), 0.5);
  EXPECT_DOUBLE_EQ(time_step_limit(integrator_kind::runge_kutta_4, omega, 0.0),
                   2 * std::numbers::sqrt2 / omega);
  EXPECT_EQ(time_step_limit(integrator_kind::implicit_euler, omega, 0.0), infinity);
  // Explicit Euler without damping grows by sqrt(1 + (omega dt)^2) per step.
  EXPECT_NEAR(amplification_factor(integrator_kind::explicit_euler, omega, 0.0, 0.25),
              std::sqrt(2.0), 1e-14);
  // Backward Euler shrinks it by 1 / sqrt(1 + (omega dt)^2), at any dt.
  EXPECT_NEAR(amplification_factor(integrator_kind::implicit_euler, omega, 0.0, 0.25),
              1 / std::sqrt(2.0), 1e-14);
}

// The criterion: the single spring as loaded (gravity, swinging start), no damping,
// semi-implicit Euler, stable at 0.9 of the predicted limit 2 / sqrt(K/m) and divergent at 1.1.
TEST(PredictedLimit, SemiImplicitSingleSpringStableBelowDivergentAbove) {
  for (double k : {20.0, 500.0}) {
    const double limit = estimate_stability(undamped_spring(k, 0.01)).time_step_limit;
    ASSERT_DOUBLE_EQ(limit, 2 / std::sqrt(k));
    single_spring below = undamped_spring(k, 0.9 * limit);
    EXPECT_EQ(divergence_step(below, 5000), 0) << "K = " << k;
    single_spring above = undamped_spring(k, 1.1 * limit);
    EXPECT_GT(divergence_step(above, 5000), 0) << "K = " << k;
  }
}

// In the linear regime (amplitude 1e-4 m, far below L0): bounded just below the limit, growing
// geometrically just above it (rho = 1.88 per step for Verlet, 1.41 for RK4, at 1.05 x).
// (Far from it the spring's force flips sign when the mass passes the anchor, which can trap
// RK4's unstable growth in a bounded chaotic motion: the test stays linear.)
TEST(PredictedLimit, VerletAndRungeKuttaLimitsHoldOnTheOscillator) {
  constexpr double amplitude = 1e-4;
  auto largest_extension = [&](integrator_kind kind, double time_step) {
    single_spring spring = testing::axial_oscillator(kind, time_step, 4.0, amplitude);
    double largest = 0.0;
    for (int s = 0; s < 40; ++s) {
      spring.step();
      largest = std::max(largest, std::abs(testing::extension(spring)));
    }
    return largest;
  };
  for (integrator_kind kind : {integrator_kind::velocity_verlet, integrator_kind::runge_kutta_4}) {
    const double limit = time_step_limit(kind, 2.0, 0.0);  // K = 4, m = 1: omega = 2
    EXPECT_LE(largest_extension(kind, 0.95 * limit), amplitude * (1 + 1e-9))
        << integrator_name(kind);
    EXPECT_GT(largest_extension(kind, 1.05 * limit), 100 * amplitude) << integrator_name(kind);
  }
}

// Backward Euler at 20 times the semi-implicit limit: the spring and the cloth stay put.
TEST(SolutionPredictedLimit, ImplicitStaysStableAtTwentyTimesTheExplicitLimit) {
  single_spring spring = undamped_spring(500.0, 0.01);
  spring.parameters.dynamics.integrator = integrator_kind::implicit_euler;
  spring.parameters.dynamics.time_step = 20 * 2 / std::sqrt(500.0);
  EXPECT_EQ(divergence_step(spring, 200), 0);

  spring_mesh cloth;  // default: K_struct 5000, N = 20, mu = 0.5
  cloth.parameters.dynamics.integrator = integrator_kind::semi_implicit;
  const double semi_implicit_limit = estimate_stability(cloth).time_step_limit;
  cloth.parameters.dynamics.integrator = integrator_kind::implicit_euler;
  cloth.parameters.dynamics.time_step = 20 * semi_implicit_limit;
  EXPECT_EQ(divergence_step(cloth, 30), 0);
  EXPECT_LT(cloth.integrator().implicit_solver().last_iterations(), 1000);
  // The pinned corners (question 7's two, any two) have not moved.
  const spring_mesh initial;
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    if (cloth.particles().is_fixed[k]) {
      EXPECT_EQ(cloth.particles().get_position(k), initial.particles().get_position(k)) << k;
    }
  }
}

TEST(DivergenceCheck, CatchesNonFiniteValuesAndRunawaySpeeds) {
  particle_system particles;
  particles.resize(3);
  EXPECT_FALSE(divergence_check(particles, 10.0).diverged);
  particles.set_velocity(1, {0.0, 8.0, -6.0});  // speed 10: at the bound, not beyond
  EXPECT_FALSE(divergence_check(particles, 10.0).diverged);
  particles.set_velocity(2, {0.0, 8.0, -6.1});
  const divergence_status fast = divergence_check(particles, 10.0);
  EXPECT_TRUE(fast.diverged);
  EXPECT_NE(fast.reason.find("particle 2"), std::string::npos) << fast.reason;
  particles.set_velocity(2, {0.0, 0.0, 0.0});
  particles.position[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(divergence_check(particles, 10.0).diverged);
}

// The check stops a diverging run long before the numbers overflow: at 1.1 times the limit the
// amplitude grows by about 2.4 per step, and the speed bound (1000 x 4.4 m/s) is met within
// about 20 steps, while NaN would take hundreds.
TEST(DivergenceCheck, StopsADivergingSpringWithinTensOfSteps) {
  single_spring spring = undamped_spring(20.0, 1.1 * 2 / std::sqrt(20.0));
  const long step = divergence_step(spring, 1000);
  EXPECT_GT(step, 0);
  EXPECT_LT(step, 40);
  EXPECT_TRUE(spring.particles().is_finite());
}

}  // namespace
}  // namespace clothlab
