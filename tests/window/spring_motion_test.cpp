// Question 2's exact solution (src/window/spring_motion.hpp) against the simulated spring: with
// the 1D start, the error is the integrator's alone, so it shrinks with dt at the integrator's
// order, down to rounding for fourth-order Runge-Kutta.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

#include "single_spring.hpp"
#include "spring_motion.hpp"

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
