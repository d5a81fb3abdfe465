// Order of convergence of every integrator on the single spring as a 1D oscillator: the error
// against x0 cos(omega t) at a fixed time T, when dt halves, divides by 2^order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/integrator.hpp"
#include "core/spring_mesh.hpp"
#include "oscillator.hpp"

namespace clothlab {
namespace {

// |x(T) - x0 cos(omega T)| with K = 4, m = 1 (omega = 2), x0 = 0.1, T = 3.5 (omega T = 7 rad,
// where neither sin nor cos vanishes, so no error term cancels by chance).
double error_at_final_time(integrator_kind integrator, double time_step) {
  constexpr double stiffness = 4.0, amplitude = 0.1, final_time = 3.5;
  single_spring spring = testing::axial_oscillator(integrator, time_step, stiffness, amplitude);
  const long steps = std::lround(final_time / time_step);
  for (long s = 0; s < steps; ++s)
    spring.step();
  const double t = static_cast<double>(steps) * time_step;
  return std::abs(testing::extension(spring) - amplitude * std::cos(2.0 * t));
}

// e(dt) = C dt^p (1 + O(dt)): e(dt) / e(dt/2) = 2^p up to the next term, which the chosen
// steps keep below 5% (omega dt <= 2e-3 for the first-order schemes, 2e-2 for Verlet, 8e-2
// for RK4, whose next term is O(dt^2) relative: (omega dt)^2 / 10 < 1e-3).
void expect_order(integrator_kind integrator, const std::vector<double>& time_steps, int order) {
  const double expected = std::pow(2.0, order);
  for (std::size_t i = 0; i + 1 < time_steps.size(); ++i) {
    const double coarse = error_at_final_time(integrator, time_steps[i]);
    const double fine = error_at_final_time(integrator, time_steps[i + 1]);
    EXPECT_NEAR(coarse / fine, expected, 0.05 * expected)
        << integrator_name(integrator) << ", dt = " << time_steps[i] << ": errors " << coarse
        << ", " << fine;
  }
}

TEST(Convergence, SemiImplicitEulerIsFirstOrder) {
  expect_order(integrator_kind::semi_implicit, {1e-3, 5e-4, 2.5e-4}, 1);
}

TEST(Convergence, ExplicitEulerIsFirstOrder) {
  expect_order(integrator_kind::explicit_euler, {1e-3, 5e-4, 2.5e-4}, 1);
}

TEST(Convergence, VelocityVerletIsSecondOrder) {
  expect_order(integrator_kind::velocity_verlet, {1e-2, 5e-3, 2.5e-3}, 2);
}

TEST(Convergence, RungeKutta4IsFourthOrder) {
  expect_order(integrator_kind::runge_kutta_4, {4e-2, 2e-2, 1e-2}, 4);
}

TEST(Convergence, ImplicitEulerIsFirstOrder) {
  expect_order(integrator_kind::implicit_euler, {1e-3, 5e-4, 2.5e-4}, 1);
}

// With damping, Verlet solves its last half kick exactly for the -mu v term and stays second
// order: x'' = -omega^2 x - mu x' has x = x0 e^(-mu t / 2) (cos(w t) + mu / (2 w) sin(w t)),
// w = sqrt(omega^2 - mu^2 / 4).
TEST(Convergence, VelocityVerletStaysSecondOrderWithDamping) {
  constexpr double stiffness = 4.0, amplitude = 0.1, damping = 0.8, final_time = 3.5;
  auto error = [&](double dt) {
    single_spring spring = testing::axial_oscillator(integrator_kind::velocity_verlet, dt,
                                                     stiffness, amplitude, damping);
    const long steps = std::lround(final_time / dt);
    for (long s = 0; s < steps; ++s)
      spring.step();
    const double t = static_cast<double>(steps) * dt;
    const double w = std::sqrt(stiffness - damping * damping / 4);
    const double exact = amplitude * std::exp(-damping * t / 2) *
                         (std::cos(w * t) + damping / (2 * w) * std::sin(w * t));
    return std::abs(testing::extension(spring) - exact);
  };
  EXPECT_NEAR(error(1e-2) / error(5e-3), 4.0, 0.2);
  EXPECT_NEAR(error(5e-3) / error(2.5e-3), 4.0, 0.2);
}

// BEGIN TEACHER
// (The teacher's copy only: the errors measured here go down to 1e-9 m, below the rounding of an
// answer to questions 8 and 13 that computes in single precision, a right answer; the student
// copy's schemes are the same code.)
// The cloth with wind: the multi-stage schemes evaluate the springs AND the wind (with the
// normals of each stage's positions) at their intermediate states, so they keep their order on
// the full model. Were the wind frozen at the start of the step, RK4 would drop to first order.
// The error at T = 0.1 s against RK4 with a 16 times smaller step, when dt halves.
double cloth_error(integrator_kind integrator, double time_step) {
  auto run = [](integrator_kind kind, double dt) {
    cloth_parameters p;
    p.grid_size = 6;
    p.ground_enabled = false;
    p.wind_strength = 50.0;
    p.wind_direction = {0.3, 1.0, 0.2};
    p.dynamics.integrator = kind;
    p.dynamics.time_step = dt;
    spring_mesh cloth(p);
    const long steps = std::lround(0.1 / dt);
    for (long s = 0; s < steps; ++s)
      cloth.step();
    return cloth.particles().position;
  };
  const std::vector<double> reference = run(integrator_kind::runge_kutta_4, time_step / 16);
  const std::vector<double> position = run(integrator, time_step);
  double largest = 0.0;
  for (std::size_t i = 0; i < position.size(); ++i)
    largest = std::max(largest, std::abs(position[i] - reference[i]));
  return largest;
}

TEST(Convergence, MultiStageSchemesKeepTheirOrderOnTheClothWithWind) {
  for (double dt : {4e-3, 2e-3}) {  // RK4 reaches round-off (1e-14) below
    EXPECT_NEAR(cloth_error(integrator_kind::velocity_verlet, dt) /
                    cloth_error(integrator_kind::velocity_verlet, dt / 2),
                4.0, 0.4)
        << "dt = " << dt;
    EXPECT_NEAR(cloth_error(integrator_kind::runge_kutta_4, dt) /
                    cloth_error(integrator_kind::runge_kutta_4, dt / 2),
                16.0, 2.0)
        << "dt = " << dt;
  }
}
// END TEACHER

TEST(Integrators, NamesReadBack) {
  for (integrator_kind kind : all_integrators)
    EXPECT_EQ(parse_integrator(integrator_name(kind)), kind);
  EXPECT_EQ(parse_integrator("verlet"), integrator_kind::velocity_verlet);
  EXPECT_EQ(parse_integrator("rk4"), integrator_kind::runge_kutta_4);
  EXPECT_EQ(parse_integrator("implicit"), integrator_kind::implicit_euler);
  EXPECT_FALSE(parse_integrator("leapfrog").has_value());
}

// The Euler schemes are each stage's own apply_force (the cloth's is question 6): the stability
// lab's integrator refuses them to any other caller.
TEST(Integrators, TheStabilityLabIntegratorRefusesTheEulerSchemes) {
  particle_system particles;
  particles.resize(1);
  const force_model no_forces{{}, [](std::span<const double>, std::span<double>) {}};
  for (const auto kind : {integrator_kind::semi_implicit, integrator_kind::explicit_euler}) {
    dynamics_parameters dynamics;
    dynamics.integrator = kind;
    time_integrator integrator;
    EXPECT_THROW(integrator.step(dynamics, no_forces, particles), std::invalid_argument)
        << integrator_name(kind);
  }
}

}  // namespace
}  // namespace clothlab
