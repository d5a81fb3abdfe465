// The cpu-parallel path (cloth_parallel) against the readable CPU path (spring_mesh): the same
// model in double precision, summed in the same order, so that after 1000 steps the two agree
// to 1e-9 relative (the measured difference is printed). Threads: 2, whatever the machine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cloth_parallel.hpp"
#include "spring_mesh.hpp"

namespace clothlab {
namespace {

// max |a - b| / max(1, |b|) over every coordinate of every particle's position and velocity.
double relative_difference(const spring_mesh& a, const spring_mesh& b) {
  double worst = 0.0;
  const auto compare = [&](const std::vector<double>& u, const std::vector<double>& w) {
    for (std::size_t i = 0; i < u.size(); ++i)
      worst = std::max(worst, std::abs(u[i] - w[i]) / std::max(1.0, std::abs(w[i])));
  };
  compare(a.particles().position, b.particles().position);
  compare(a.particles().velocity, b.particles().velocity);
  return worst;
}

double run_both(const cloth_parameters& p, int steps) {
  spring_mesh readable(p);
  spring_mesh fast_result(p);
  cloth_parallel fast(2);
  fast.load(readable);
  for (int s = 0; s < steps; ++s) {
    readable.step();
    fast.step(p);
  }
  fast.read_state(fast_result);
  EXPECT_TRUE(fast_result.particles().is_finite());
  return relative_difference(fast_result, readable);
}

struct agreement_case {
  const char* name;
  cloth_parameters parameters;
  int steps;
};

std::vector<agreement_case> cases() {
  cloth_parameters hanging;  // the default cloth: pinned corners, ground, N = 20
  hanging.grid_size = 24;
  cloth_parameters windy = hanging;
  windy.wind_strength = 30.0;
  windy.wind_direction = {1.0, 2.0, 0.5};
  windy.ground_height = -0.4;
  cloth_parameters explicit_euler = hanging;  // stable only with a small dt (question 4)
  explicit_euler.dynamics.integrator = integrator_kind::explicit_euler;
  explicit_euler.dynamics.time_step = 0.0002;
  explicit_euler.dynamics.damping = 5.0;
  cloth_parameters draped = hanging;
  draped.pins = pin_mode::none;
  draped.sphere = {.enabled = true, .centre = {0.0, 0.0, -0.4}, .radius = 0.3};
  draped.drag = {
      .enabled = true, .ku = 23, .kv = 23, .target = {0.6, 0.6, 0.3}, .stiffness = 500.0};
  cloth_parameters scaled = hanging;
  scaled.scaling = resolution_scaling::resolution_independent;
  scaled.dynamics.time_step = 0.001;
  return {{"hanging", hanging, 1000},
          {"windy", windy, 1000},
          {"explicit", explicit_euler, 1000},
          {"sphere and drag", draped, 1000},
          {"resolution-independent", scaled, 1000}};
}

// (It needs the lab's solution on the readable path: label core-solution.)
TEST(SolutionClothParallel, AgreesWithTheReadablePathAfterAThousandSteps) {
  for (const agreement_case& c : cases()) {
    const double difference = run_both(c.parameters, c.steps);
    std::printf("  %-24s %d steps: max relative difference %.3g\n", c.name, c.steps, difference);
    EXPECT_LE(difference, 1e-9) << c.name;
  }
}

// The comparison can fail: a 0.1 % stiffer cloth on the fast path is far outside 1e-9.
TEST(ClothParallel, TheComparisonSeesAStifferCloth) {
  cloth_parameters p = cases()[0].parameters;
  spring_mesh readable(p);
  spring_mesh fast_result(p);
  cloth_parallel fast(2);
  fast.load(readable);
  cloth_parameters stiffer = p;
  stiffer.structural_stiffness *= 1.001;
  for (int s = 0; s < 200; ++s) {
    readable.step();
    fast.step(stiffer);
  }
  fast.read_state(fast_result);
  EXPECT_GT(relative_difference(fast_result, readable), 1e-6);
}

TEST(ClothParallel, RefusesWhatOnlyTheReadablePathRunsByName) {
  cloth_parameters p;
  std::string error;
  EXPECT_TRUE(cloth_parallel::supports(p, error)) << error;
  p.dynamics.integrator = integrator_kind::runge_kutta_4;
  EXPECT_FALSE(cloth_parallel::supports(p, error));
  EXPECT_NE(error.find("rk4"), std::string::npos) << error;
  EXPECT_THROW(cloth_parallel().step(p), std::invalid_argument);
  // Tearing and self-collision run here too.
  p.dynamics.integrator = integrator_kind::semi_implicit;
  p.tear_strain = 0.1;
  p.self_collision_thickness = 0.01;
  EXPECT_TRUE(cloth_parallel::supports(p, error)) << error;
}

}  // namespace
}  // namespace clothlab
