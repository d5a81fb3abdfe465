// Question 2's exact solution (src/window/spring_motion.hpp) against the simulated spring: with
// the 1D start, the error is the integrator's alone, so it shrinks with dt at the integrator's
// order, down to rounding for fourth-order Runge-Kutta.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

#include "core/single_spring.hpp"
#include "window/spring_motion.hpp"

namespace clothlab {
namespace {

// The largest |simulated - exact| over 5 s of the default spring (K = 20, mu = 0.2), started
// with only the component of v1 along the spring, as the window's 1D start does.
double largest_error(integrator_kind integrator, double time_step) {
  single_spring_parameters parameters;
  parameters.dynamics.time_step = time_step;
  parameters.dynamics.integrator = integrator;
  single_spring spring(parameters);
  spring.load_model();
  particle_system& particles = spring.particles();
  const glm::dvec3 axis = particles.get_position(1) - particles.get_position(0);
  const glm::dvec3 v = particles.get_velocity(1);
  particles.set_velocity(1, glm::dot(v, axis) / glm::dot(axis, axis) * axis);
  spring_motion motion;
  long step = 0;
  double time = 0.0;
  motion.record(spring, time, step);
  while (time < 5.0) {
    spring.step();
    ++step;
    time += time_step;
    motion.record(spring, time, step);
  }
  return motion.largest_error();
}

TEST(SpringMotion, SemiImplicitEulerDepartsFromTheExactSolutionInProportionToDt) {
  const double coarse = largest_error(integrator_kind::semi_implicit, 0.01);
  const double fine = largest_error(integrator_kind::semi_implicit, 0.001);
  EXPECT_GT(coarse, 1e-3);                // visible in the plot at the default dt
  EXPECT_NEAR(coarse / fine, 10.0, 1.0);  // first order
}

TEST(SpringMotion, RungeKuttaFollowsTheExactSolutionToItsOrder) {
  EXPECT_LT(largest_error(integrator_kind::runge_kutta_4, 0.01), 1e-6);
}

// The plot's samples are the steps, not the frames: a frame that takes 50 steps at once (a
// stalled frame, a screenshot) leaves no gap between them, which the plot would draw as a chord.
TEST(SpringMotion, KeepsASampleOfEveryStepOverTheLastTenSeconds) {
  for (const double time_step : {0.01, 0.001}) {
    single_spring_parameters parameters;
    parameters.dynamics.time_step = time_step;
    single_spring spring(parameters);
    spring.load_model();
    spring_motion motion;
    motion.record(spring, 0.0, 0);
    long step = 0;
    double time = 0.0;
    while (time < 30.0) {
      for (int i = 0; i < 50; ++i) {  // one frame's steps, each recorded as it is taken
        spring.step();
        ++step;
        time += time_step;
        motion.record(spring, time, step);
      }
    }
    const std::vector<float>& times = motion.times();
    ASSERT_GE(times.size(), 2u);
    EXPECT_LE(times.size(), spring_motion::max_samples + 1);
    EXPECT_NEAR(times.back(), time, 1e-4);
    EXPECT_NEAR(times.back() - times.front(), spring_motion::window_seconds, 0.011);
    float widest_gap = 0.0f;
    for (std::size_t i = 1; i < times.size(); ++i)
      widest_gap = std::max(widest_gap, times[i] - times[i - 1]);
    // dt = 0.01 s: every step; dt = 1 ms: every tenth step.
    EXPECT_LT(widest_gap, std::max(time_step, 0.01) * 1.01) << "dt = " << time_step;
    // Each sample is the spring's state then: the last one is the spring now.
    const particle_system& particles = spring.particles();
    const double length = glm::length(particles.get_position(1) - particles.get_position(0));
    const double rest = spring.springs()[0].rest_length;
    EXPECT_LE(std::abs(motion.simulated().back()), length - rest + 1e-6);
  }
}

TEST(DampedOscillator, OverdampedAndSpringlessCasesStartFromTheirInitialState) {
  for (const double omega_squared : {0.0, 1.0, 100.0}) {
    const damped_oscillator model{
        .omega_squared = omega_squared, .damping = 30.0, .forcing = 9.8, .x0 = 0.25, .v0 = -1.0};
    EXPECT_NEAR(model.position(0.0), 0.25, 1e-12) << "omega^2 = " << omega_squared;
    const double h = 1e-6;  // x'(0) by a central difference
    EXPECT_NEAR((model.position(h) - model.position(-h)) / (2 * h), -1.0, 1e-5);
  }
}

}  // namespace
}  // namespace clothlab
