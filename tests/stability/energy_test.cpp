// Energy accounting: each scheme's exact energy behaviour on the undamped oscillator (from the
// eigenvalues of its step map, see stability.hpp) and on a free fall, against compute_energy.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/energy.hpp"
#include "core/spring_mesh.hpp"
#include "oscillator.hpp"

namespace clothlab {
namespace {

constexpr double stiffness = 4.0;  // with m = 1: omega = 2
constexpr double amplitude = 0.1;
constexpr double time_step = 0.05;  // h = omega dt = 0.1
constexpr double h = 0.1;
// E0 = K x0^2 / 2 (at rest, no gravity)
constexpr double initial_energy = 0.5 * stiffness * amplitude * amplitude;

TEST(Energy, BreakdownOfAHandMadeState) {
  single_spring spring = testing::axial_oscillator(integrator_kind::semi_implicit, 0.01, 4.0, 0.1);
  spring.parameters.dynamics.gravity = 9.8;
  spring.particles().set_velocity(1, {3.0, 0.0, 4.0});  // |v| = 5
  spring.particles().set_velocity(0, {7.0, 0.0, 0.0});  // fixed: its velocity does not count
  const energy_breakdown e = compute_energy(spring);
  EXPECT_DOUBLE_EQ(e.kinetic, 12.5);               // m |v|^2 / 2
  EXPECT_DOUBLE_EQ(e.gravity, 9.8 * (1.0 - 0.6));  // m g0 z of p1 only, z = 0.4
  EXPECT_NEAR(e.spring, 0.5 * 4.0 * 0.01, 1e-15);  // K x^2 / 2
  EXPECT_DOUBLE_EQ(e.total, e.kinetic + e.gravity + e.spring);
}

// Explicit Euler maps (x, v/omega) by sqrt(1 + h^2) times a rotation: E_n = E0 (1 + h^2)^n.
TEST(Energy, ExplicitEulerGainsEnergyAtTheTheoreticalRate) {
  single_spring spring =
      testing::axial_oscillator(integrator_kind::explicit_euler, time_step, stiffness, amplitude);
  for (int n = 1; n <= 100; ++n) {
    spring.step();
    EXPECT_NEAR(compute_energy(spring).total / initial_energy, std::pow(1 + h * h, n), 1e-9)
        << "step " << n;
  }
}

// Backward Euler (linearised once, exact for this linear spring): E_n = E0 / (1 + h^2)^n.
TEST(Energy, ImplicitEulerLosesEnergyAtTheTheoreticalRate) {
  single_spring spring =
      testing::axial_oscillator(integrator_kind::implicit_euler, time_step, stiffness, amplitude);
  for (int n = 1; n <= 100; ++n) {
    spring.step();
    EXPECT_NEAR(compute_energy(spring).total / initial_energy, std::pow(1 + h * h, -n), 1e-9)
        << "step " << n;
  }
}

// Semi-implicit Euler keeps x^2 + u^2 - h x u exactly (u = v / omega): starting with u = 0 the
// energy stays within [E0 / (1 + h/2), E0 / (1 - h/2)], forever, without drifting.
TEST(Energy, SemiImplicitEulerKeepsEnergyBounded) {
  single_spring spring =
      testing::axial_oscillator(integrator_kind::semi_implicit, time_step, stiffness, amplitude);
  double lowest = initial_energy, highest = initial_energy;
  for (int n = 1; n <= 20000; ++n) {  // 160 periods
    spring.step();
    const double e = compute_energy(spring).total;
    lowest = std::min(lowest, e);
    highest = std::max(highest, e);
  }
  EXPECT_GE(lowest, initial_energy / (1 + h / 2) * (1 - 1e-9));
  EXPECT_LE(highest, initial_energy / (1 - h / 2) * (1 + 1e-9));
  EXPECT_LT(lowest, initial_energy * 0.98);  // it does oscillate (by about h/2)
}

// Velocity Verlet keeps (1 - h^2/4) x^2 + u^2: E stays within [(1 - h^2/4) E0, E0].
TEST(Energy, VelocityVerletKeepsEnergyBounded) {
  single_spring spring =
      testing::axial_oscillator(integrator_kind::velocity_verlet, time_step, stiffness, amplitude);
  for (int n = 1; n <= 20000; ++n) {
    spring.step();
    const double e = compute_energy(spring).total;
    ASSERT_GE(e, (1 - h * h / 4) * initial_energy * (1 - 1e-9)) << "step " << n;
    ASSERT_LE(e, initial_energy * (1 + 1e-9)) << "step " << n;
  }
}

// RK4 multiplies the mode by R(i h) = 1 + ih - h^2/2 - ih^3/6 + h^4/24:
// |R|^2 = 1 - h^6/72 + h^8/576, a slow loss.
TEST(Energy, RungeKutta4LosesEnergySlowlyAtTheTheoreticalRate) {
  single_spring spring =
      testing::axial_oscillator(integrator_kind::runge_kutta_4, time_step, stiffness, amplitude);
  const double factor = 1 - std::pow(h, 6) / 72 + std::pow(h, 8) / 576;
  for (int n = 1; n <= 1000; ++n)
    spring.step();
  EXPECT_NEAR(compute_energy(spring).total / initial_energy, std::pow(factor, 1000), 1e-10);
}

// A free fall (K = 0) from the single spring's start, v0 = (1, -1, 0): the horizontal motion
// keeps its kinetic energy and the vertical one, from rest, gives after n steps of dt:
//   semi-implicit and implicit: v_z = -g n dt, z = z0 - g dt^2 n (n + 1) / 2,
//                               E_n - E0 = -m g^2 dt^2 n / 2 = -m g^2 dt t / 2 (O(dt) drift)
//   explicit:                   z = z0 - g dt^2 n (n - 1) / 2, E_n - E0 = +m g^2 dt t / 2
//   Verlet and RK4:             exact for a constant acceleration: E_n = E0.
//   XPBD, no constraint:        semi-implicit Euler over its substeps h = dt / substeps:
//                               E_n - E0 = -m g^2 h t / 2.
// (XPBD is the teacher's copy's: where it is absent, its line is skipped.)
TEST(Energy, FreeFallDriftsAsComputedByHand) {
  constexpr double g = 9.8, dt = 0.01;
  constexpr int steps = 50;
  constexpr double t = steps * dt;
  for (integrator_kind kind : all_integrators) {
    if (kind == integrator_kind::xpbd && !xpbd_available())
      continue;
    single_spring_parameters p;
    p.stiffness = 0.0;
    p.dynamics = {.time_step = dt, .damping = 0.0, .mass = 1.0, .gravity = g, .integrator = kind};
    single_spring fall(p);
    const double e0 = compute_energy(fall).total;
    EXPECT_DOUBLE_EQ(e0, 0.5 * 2.0 + g * 0.5);  // |v0|^2 / 2 + g z0
    for (int n = 0; n < steps; ++n)
      fall.step();
    const double substep = dt / p.dynamics.xpbd.substeps;
    const double drift =
        kind == integrator_kind::semi_implicit || kind == integrator_kind::implicit_euler
            ? -g * g * dt * t / 2
        : kind == integrator_kind::explicit_euler ? g * g * dt * t / 2
        : kind == integrator_kind::xpbd           ? -g * g * substep * t / 2
                                                  : 0.0;
    EXPECT_NEAR(compute_energy(fall).total - e0, drift, 1e-11) << integrator_name(kind);
  }
}

// The pinned, damped cloth under every stable scheme: after a second its energy has gone down
// from the start (it fell, and the damping worked) and its springs are stretched. (Explicit
// Euler would need dt < mu / omega_max^2 = 3e-5 s here.)
TEST(SolutionEnergy, TheClothLosesEnergyWithDampingUnderEveryStableScheme) {
  for (integrator_kind kind : {integrator_kind::semi_implicit, integrator_kind::velocity_verlet,
                               integrator_kind::runge_kutta_4, integrator_kind::implicit_euler}) {
    cloth_parameters p;
    p.grid_size = 10;
    p.dynamics.integrator = kind;
    p.dynamics.time_step = 0.001;
    p.dynamics.damping = 2.0;
    spring_mesh cloth(p);
    const double e0 = compute_energy(cloth).total;
    EXPECT_DOUBLE_EQ(e0, 0.0);  // flat at z = 0, at rest, unstretched
    for (int n = 0; n < 1000; ++n)
      cloth.step();
    const energy_breakdown e = compute_energy(cloth);
    EXPECT_LT(e.total, e0) << integrator_name(kind);
    EXPECT_GT(e.spring, 0.0) << integrator_name(kind);
  }
}

TEST(Energy, CsvRowsReadBackExactly) {
  std::ostringstream out;
  write_energy_csv_header(out);
  write_energy_csv_row(out, 3, 0.30000000000000004, {0.1, -2.5, 1e-17, -2.4});
  EXPECT_EQ(out.str(),
            "step,t,kinetic,gravity,spring,total\n"
            "3,0.30000000000000004,0.10000000000000001,-2.5,1.0000000000000001e-17,-2."
            "3999999999999999\n");
}

}  // namespace
}  // namespace clothlab
