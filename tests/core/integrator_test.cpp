// The two integrators of model.md against the harmonic oscillator's analytic solution and against
// the theory of their discrete maps, plus damping, gravity and fixed particles by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/coupled_springs.hpp"
#include "core/integrator.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring.hpp"

namespace clothlab {

// The two Euler schemes of model.md as the chain runs them (coupled_springs::apply_force, the
// handout's code of section 2, on any particles); the cloth's are question 6's, tested in
// tests/lab.
struct integrator_test_access {
  static void integrate(const dynamics_parameters& dynamics, particle_system& particles) {
    coupled_springs chain;
    chain.parameters.dynamics = dynamics;
    chain.particles() = particles;
    chain.apply_force();
    particles = chain.particles();
  }
};

namespace {

// A mass m on a spring (stiffness K, rest length L0) hanging from a fixed point at the origin,
// moving along z only: particle 1 is at z = -(L0 + x), x the extension, so the spring force on it
// is F_z = K (L0 - |z|)(-1) = K x and x'' = -(K/m) x: a 1D harmonic oscillator of angular
// frequency w = sqrt(K/m), x(t) = x0 cos(w t) + (v0/w) sin(w t). Gravity and damping are 0.
class vertical_oscillator {
 public:
  vertical_oscillator(double stiffness, double mass, double extension, double extension_rate,
                      integrator_kind integrator, double time_step)
      : stiffness_(stiffness) {
    dynamics_.time_step = time_step;
    dynamics_.damping = 0.0;
    dynamics_.mass = mass;
    dynamics_.gravity = 0.0;
    dynamics_.integrator = integrator;
    particles_.resize(2);
    particles_.is_fixed[0] = 1;
    particles_.set_position(1, {0.0, 0.0, -(rest_length + extension)});
    particles_.set_velocity(1, {0.0, 0.0, -extension_rate});
  }

  void step() {
    // The spring's force on particle 1 (equation 2); particle 0 is fixed.
    std::fill(particles_.force.begin(), particles_.force.end(), 0.0);
    const glm::dvec3 F = spring_force(particles_.get_position(1), particles_.get_position(0),
                                      stiffness_, springs_[0].rest_length);
    for (int c = 0; c < 3; ++c)
      particles_.force[static_cast<std::size_t>(3 + c)] = F[c];
    integrator_test_access::integrate(dynamics_, particles_);
  }

  double extension() const { return -particles_.position[5] - rest_length; }
  double extension_rate() const { return -particles_.velocity[5]; }
  double angular_frequency() const { return std::sqrt(stiffness_ / dynamics_.mass); }
  // E = (K x^2 + m v^2) / 2
  double energy() const {
    const double x = extension();
    const double v = extension_rate();
    return 0.5 * (stiffness_ * x * x + dynamics_.mass * v * v);
  }
  // The motion stays on the z axis: x and y of the moving particle remain exactly 0.
  bool stays_on_the_axis() const {
    return particles_.position[3] == 0.0 && particles_.position[4] == 0.0 &&
           particles_.velocity[3] == 0.0 && particles_.velocity[4] == 0.0;
  }

  static constexpr double rest_length = 1.0;

 private:
  double stiffness_;
  dynamics_parameters dynamics_;
  particle_system particles_;
  std::array<spring, 1> springs_{spring{0, 1, rest_length}};
};

// |x_numerical(T) - x_exact(T)| after T/dt steps from x0 = 0.1, v0 = 0, with K = 4, m = 1 (w = 2).
double extension_error_at(double final_time, double time_step, integrator_kind integrator) {
  constexpr double amplitude = 0.1;
  vertical_oscillator oscillator(4.0, 1.0, amplitude, 0.0, integrator, time_step);
  const long steps = std::lround(final_time / time_step);
  for (long s = 0; s < steps; ++s) {
    oscillator.step();
  }
  const double t = static_cast<double>(steps) * time_step;
  return std::abs(oscillator.extension() -
                  amplitude * std::cos(oscillator.angular_frequency() * t));
}

// Both integrators are first order. With h = w dt, x0 = A, v0 = 0 (derivation from the exact
// solution of each linear map, by its eigenvalues):
//  - explicit Euler, (x, v/w) -> [[1, h], [-h, 1]] (x, v/w): eigenvalues sqrt(1 + h^2) e^(+-i phi),
//    phi = atan h, and x_n = A (1 + h^2)^(n/2) cos(n phi); at T = n dt this is
//    A cos(wT) + A (w^2 T dt / 2) cos(wT) + O(dt^2): the error is first order, coefficient ~
//    cos(wT).
//  - semi-implicit Euler, (x, v/w) -> [[1 - h^2, h], [-h, 1]]: eigenvalues e^(+-i theta),
//    cos theta = 1 - h^2/2 (theta = h + O(h^3)), and x_n = A cos(n theta) + b sin(n theta) with
//    b = -A h^2 / (2 sin theta) = -A h/2 + O(h^3); at T the error is -(A w dt / 2) sin(wT) +
//    O(dt^2).
// So e(dt) = c1 dt + c2 dt^2 and e(dt)/e(dt/2) = 2 (1 + c2 dt/(2 c1)) + O(dt^2): close to 2 when
// c2 dt / c1 is small. T = 3.5 (wT = 7 rad: sin 7 = 0.66 and cos 7 = 0.75, neither coefficient
// vanishes) and dt <= 1e-3 make c2 dt / c1 below 0.01, so the ratio lies within [1.9, 2.1].
void expect_first_order_convergence(integrator_kind integrator) {
  constexpr double final_time = 3.5;
  const std::vector<double> time_steps = {1e-3, 5e-4, 2.5e-4, 1.25e-4};
  for (std::size_t i = 0; i + 1 < time_steps.size(); ++i) {
    const double coarse = extension_error_at(final_time, time_steps[i], integrator);
    const double fine = extension_error_at(final_time, time_steps[i + 1], integrator);
    EXPECT_GT(coarse / fine, 1.9) << "dt = " << time_steps[i] << ": errors " << coarse << ", "
                                  << fine;
    EXPECT_LT(coarse / fine, 2.1) << "dt = " << time_steps[i] << ": errors " << coarse << ", "
                                  << fine;
  }
  // And the error itself is the predicted one to leading order (see above), within 5%.
  const double dt = time_steps.back();
  const double w = 2.0;
  const double amplitude = 0.1;
  const double predicted =
      integrator == integrator_kind::explicit_euler
          ? amplitude * w * w * final_time * dt / 2.0 * std::abs(std::cos(w * final_time))
          : amplitude * w * dt / 2.0 * std::abs(std::sin(w * final_time));
  EXPECT_NEAR(extension_error_at(final_time, dt, integrator), predicted, 0.05 * predicted);
}

TEST(HarmonicOscillator, SemiImplicitEulerConvergesAtFirstOrder) {
  expect_first_order_convergence(integrator_kind::semi_implicit);
}

TEST(HarmonicOscillator, ExplicitEulerConvergesAtFirstOrder) {
  expect_first_order_convergence(integrator_kind::explicit_euler);
}

// Explicit Euler: x' = x + dt v, v' = v - (K/m) dt x, so
// K x'^2 + m v'^2 = K x^2 + m v^2 + K dt^2 v^2 + (K^2/m) dt^2 x^2 = (1 + w^2 dt^2)(K x^2 + m v^2):
// the energy is multiplied by exactly (1 + w^2 dt^2) at every step.
TEST(HarmonicOscillator, ExplicitEulerGainsEnergyAtTheTheoreticalRate) {
  constexpr double stiffness = 8.0;
  constexpr double mass = 2.0;  // w = 2
  constexpr double dt = 0.01;
  vertical_oscillator oscillator(stiffness, mass, 0.1, 0.3, integrator_kind::explicit_euler, dt);
  const double gain = 1.0 + (stiffness / mass) * dt * dt;
  for (int s = 0; s < 200; ++s) {
    const double before = oscillator.energy();
    oscillator.step();
    EXPECT_NEAR(oscillator.energy() / before, gain, 1e-12) << "step " << s + 1;
  }
  EXPECT_TRUE(oscillator.stays_on_the_axis());
}

// Semi-implicit Euler, with y = w x and h = w dt: (y, v) -> (y + h v', v' = v - h y) conserves
// the quadratic form Q = y^2 - h y v + v^2 exactly (solve M^T S M = S for S symmetric). S has the
// eigenvalues 1 -+ h/2, so for h < 2, (1 - h/2)(y^2 + v^2) <= Q <= (1 + h/2)(y^2 + v^2), and
// the energy E = m (y^2 + v^2)/2 stays within [r^-1, r] E_0, r = (1 + h/2)/(1 - h/2).
void expect_bounded_semi_implicit_energy(double h) {
  constexpr double stiffness = 4.0;
  constexpr double mass = 1.0;  // w = 2
  const double w = 2.0;
  vertical_oscillator oscillator(stiffness, mass, 0.1, 0.05, integrator_kind::semi_implicit, h / w);
  const auto modified_energy = [&] {
    const double y = w * oscillator.extension();
    const double v = oscillator.extension_rate();
    return y * y - h * y * v + v * v;
  };
  const double e0 = oscillator.energy();
  const double q0 = modified_energy();
  const double bound = (1.0 + h / 2.0) / (1.0 - h / 2.0);
  double largest = e0;
  double smallest = e0;
  for (int s = 0; s < 10000; ++s) {
    oscillator.step();
    largest = std::max(largest, oscillator.energy());
    smallest = std::min(smallest, oscillator.energy());
    ASSERT_NEAR(modified_energy() / q0, 1.0, 1e-9) << "h = " << h << ", step " << s + 1;
  }
  EXPECT_LE(largest / e0, bound * (1.0 + 1e-9)) << "h = " << h;
  EXPECT_GE(smallest / e0, (1.0 - 1e-9) / bound) << "h = " << h;
}

TEST(HarmonicOscillator, SemiImplicitEulerEnergyStaysBoundedBelowTheStabilityLimit) {
  expect_bounded_semi_implicit_energy(0.1);
  expect_bounded_semi_implicit_energy(1.0);
  expect_bounded_semi_implicit_energy(1.9);
}

// Above h = w dt = 2 the map [[1 - h^2, h], [-h, 1]] has trace 2 - h^2 < -2, hence a real
// eigenvalue of modulus ((h^2 - 2) + sqrt((h^2 - 2)^2 - 4))/2: 2.43 for h = 2.2. After 100 steps
// the energy has grown by ~2.43^200 ~ 1e77 (or overflowed).
TEST(HarmonicOscillator, SemiImplicitEulerDivergesAboveTheStabilityLimit) {
  const double w = 2.0;
  vertical_oscillator oscillator(4.0, 1.0, 0.1, 0.0, integrator_kind::semi_implicit, 2.2 / w);
  const double e0 = oscillator.energy();
  for (int s = 0; s < 100; ++s) {
    oscillator.step();
  }
  const double e = oscillator.energy();
  EXPECT_TRUE(!std::isfinite(e) || e > 1e50 * e0) << "energy after 100 steps: " << e;
}

// A free particle (no force, no gravity): one step multiplies the velocity by (1 - mu dt).
TEST(Integrator, DampingMultipliesTheVelocityByOneMinusMuDt) {
  for (const auto integrator : {integrator_kind::semi_implicit, integrator_kind::explicit_euler}) {
    dynamics_parameters dynamics{.time_step = 0.01, .damping = 0.5, .mass = 3.0, .gravity = 0.0};
    dynamics.integrator = integrator;
    particle_system particles;
    particles.resize(1);
    const glm::dvec3 p0 = {0.25, -0.5, 2.0};
    const glm::dvec3 v0 = {1.0, 2.0, -3.0};
    particles.set_position(0, p0);
    particles.set_velocity(0, v0);
    integrator_test_access::integrate(dynamics, particles);
    const double factor = 1.0 - 0.5 * 0.01;  // 0.995
    const glm::dvec3 v1 = particles.get_velocity(0);
    const glm::dvec3 p1 = particles.get_position(0);
    // semi-implicit moves with the new velocity, explicit with the old one.
    const glm::dvec3 moved_with = integrator == integrator_kind::semi_implicit ? v0 * factor : v0;
    for (int c = 0; c < 3; ++c) {
      EXPECT_DOUBLE_EQ(v1[c], factor * v0[c]) << integrator_name(integrator) << " c=" << c;
      EXPECT_DOUBLE_EQ(p1[c], p0[c] + 0.01 * moved_with[c]) << integrator_name(integrator);
    }
  }
}

// A particle at rest at the origin under gravity alone, dt = 0.01, g0 = 9.8, any mass:
// semi-implicit: v = -g0 dt = -0.098, then p = dt v = -g0 dt^2 = -0.00098;
// explicit: p = 0 + dt * 0 = 0, v = -0.098.
TEST(Integrator, FirstGravityStepMatchesTheHandComputation) {
  for (const auto integrator : {integrator_kind::semi_implicit, integrator_kind::explicit_euler}) {
    dynamics_parameters dynamics{.time_step = 0.01, .damping = 0.0, .mass = 2.5, .gravity = 9.8};
    dynamics.integrator = integrator;
    particle_system particles;
    particles.resize(1);
    integrator_test_access::integrate(dynamics, particles);
    const glm::dvec3 v = particles.get_velocity(0);
    const glm::dvec3 p = particles.get_position(0);
    EXPECT_EQ(v.x, 0.0);
    EXPECT_EQ(v.y, 0.0);
    EXPECT_DOUBLE_EQ(v.z, -0.098) << integrator_name(integrator);
    EXPECT_EQ(p.x, 0.0);
    EXPECT_EQ(p.y, 0.0);
    if (integrator == integrator_kind::semi_implicit) {
      EXPECT_DOUBLE_EQ(p.z, -0.00098);
    } else {
      EXPECT_EQ(p.z, 0.0);
    }
  }
}

// a = F/m + g: a force of (2, -4, 6) N on a 2 kg mass with g0 = 10, from rest, dt = 0.1:
// v = 0.1 * ((1, -2, 3) + (0, 0, -10)) = (0.1, -0.2, -0.7).
TEST(Integrator, AccelerationIsForceOverMassPlusGravity) {
  dynamics_parameters dynamics{.time_step = 0.1, .damping = 0.0, .mass = 2.0, .gravity = 10.0};
  particle_system particles;
  particles.resize(1);
  particles.force = {2.0, -4.0, 6.0};
  integrator_test_access::integrate(dynamics, particles);
  const glm::dvec3 v = particles.get_velocity(0);
  EXPECT_DOUBLE_EQ(v.x, 0.1);
  EXPECT_DOUBLE_EQ(v.y, -0.2);
  EXPECT_DOUBLE_EQ(v.z, -0.7);
}

TEST(Integrator, FixedParticlesNeverMoveAndKeepZeroVelocity) {
  for (const auto integrator : {integrator_kind::semi_implicit, integrator_kind::explicit_euler}) {
    dynamics_parameters dynamics{.time_step = 0.01, .damping = 0.3, .mass = 1.0, .gravity = 9.8};
    dynamics.integrator = integrator;
    particle_system particles;
    particles.resize(2);
    particles.is_fixed[0] = 1;
    particles.set_position(0, {0.1, 0.2, 0.3});
    particles.force = {5.0, 6.0, 7.0, 5.0, 6.0, 7.0};
    for (int s = 0; s < 10; ++s) {
      integrator_test_access::integrate(dynamics, particles);
    }
    EXPECT_EQ(particles.get_position(0), glm::dvec3(0.1, 0.2, 0.3)) << integrator_name(integrator);
    EXPECT_EQ(particles.get_velocity(0), glm::dvec3(0.0)) << integrator_name(integrator);
    EXPECT_NE(particles.get_position(1), glm::dvec3(0.0)) << "the free particle moves";
  }
}

}  // namespace
}  // namespace clothlab
