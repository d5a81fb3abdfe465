// The cpu-parallel path (cloth_parallel) against the readable CPU path (spring_mesh): the same
// model in double precision, summed in the same order, so that after 1000 steps the two agree
// to 1e-9 relative (the measured difference is printed). Threads: 2, whatever the machine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/cloth_parallel.hpp"
#include "core/spring_mesh.hpp"

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

// Runs both paths `steps` steps; the fast path's state (and its torn springs) read back into
// fast_result. Returns the relative difference of the states.
double run_both(int steps, spring_mesh& readable, spring_mesh& fast_result) {
  cloth_parallel fast(2);
  fast.load(readable);
  const cloth_parameters at_this_n = readable.effective_parameters();  // question 10
  for (int s = 0; s < steps; ++s) {
    readable.step();
    fast.step(at_this_n);
  }
  fast.read_state(fast_result);
  EXPECT_TRUE(fast_result.particles().is_finite());
  return relative_difference(fast_result, readable);
}

double run_both(const cloth_parameters& p, int steps) {
  spring_mesh readable(p);
  spring_mesh fast_result(p);
  return run_both(steps, readable, fast_result);
}

// The springs that remain, family by family, and the triangles drawn: the same on both.
void expect_same_springs(const spring_mesh& fast, const spring_mesh& readable) {
  for (spring_family family : all_spring_families) {
    EXPECT_EQ(fast.springs(family).size(), readable.springs(family).size())
        << "family " << static_cast<int>(family);
  }
  const int n = readable.grid_size();
  int differ = 0;
  for (int kv = 0; kv + 1 < n; ++kv) {
    for (int ku = 0; ku + 1 < n; ++ku) {
      for (const bool upper : {false, true})
        differ += fast.triangle_intact(ku, kv, upper) != readable.triangle_intact(ku, kv, upper);
    }
  }
  EXPECT_EQ(differ, 0) << "triangles drawn on one path and not on the other";
}

std::size_t spring_count(const spring_mesh& cloth) {
  std::size_t count = 0;
  for (spring_family family : all_spring_families)
    count += cloth.springs(family).size();
  return count;
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

// Tearing (docs/model.md, last in the step): a corner of the hanging cloth dragged hard down
// and away tears springs; both paths tear the same ones at the same steps (a spring torn one
// step apart would change every later state), and the fast path hands them back for drawing.
TEST(SolutionClothParallel, TearsTheSameSpringsAsTheReadablePath) {
  cloth_parameters p;
  p.grid_size = 24;
  p.tear_strain = 0.25;
  p.drag = {.enabled = true, .ku = 23, .kv = 23, .target = {1.5, 1.5, -1.0}, .stiffness = 5000.0};
  spring_mesh readable(p);
  spring_mesh fast_result(p);
  const std::size_t intact = spring_count(readable);
  const double difference = run_both(1000, readable, fast_result);
  const std::size_t torn = intact - spring_count(readable);
  std::printf("  %zu springs torn; max relative difference %.3g\n", torn, difference);
  EXPECT_GT(torn, 0u) << "the case must tear springs";
  EXPECT_LE(difference, 1e-9);
  expect_same_springs(fast_result, readable);
}

// A cloth loaded with springs already torn keeps them torn on the fast path (a run can switch
// paths at any step).
TEST(SolutionClothParallel, KeepsTheSpringsTornBeforeItWasLoaded) {
  cloth_parameters p;
  p.grid_size = 8;
  spring_mesh readable(p);
  readable.particles().set_position(spring_mesh::index(3, 3, 8), {5.0, 5.0, 5.0});
  ASSERT_GT(readable.tear_springs(0.5), 0u);
  readable.particles().set_position(spring_mesh::index(3, 3, 8), {0.0, 0.0, 0.0});
  spring_mesh fast_result(p);
  EXPECT_LE(run_both(300, readable, fast_result), 1e-9);
  expect_same_springs(fast_result, readable);
}

// Self-collision (after the contacts): a cloth lying on the ground, one corner dragged over it
// to the opposite one, folds onto itself. The pass changes the outcome (against the same run
// without it), and both paths agree.
TEST(SolutionClothParallel, AgreesWithSelfCollisionOfAClothFoldingOnItself) {
  cloth_parameters p;
  p.grid_size = 24;
  p.pins = pin_mode::none;
  p.ground_height = -0.02;
  p.drag = {.enabled = true, .ku = 23, .kv = 23, .target = {-0.4, -0.4, 0.05}, .stiffness = 300.0};
  p.self_collision_thickness = 0.03;  // h = 1/23 = 0.043
  spring_mesh readable(p);
  spring_mesh fast_result(p);
  const double difference = run_both(1000, readable, fast_result);
  cloth_parameters without = p;
  without.self_collision_thickness = 0.0;
  spring_mesh no_pass(without);
  for (int s = 0; s < 1000; ++s)
    no_pass.step();
  const double effect = relative_difference(no_pass, readable);
  std::printf("  max relative difference %.3g (self-collision changes the state by %.3g)\n",
              difference, effect);
  EXPECT_GT(effect, 1e-3) << "the case must bring parts of the cloth closer than d";
  EXPECT_LE(difference, 1e-9);
}

// Everything at once: drag, sphere, ground, self-collision and tearing, with the wind.
TEST(SolutionClothParallel, AgreesWithEveryContactAndTearingTogether) {
  cloth_parameters p;
  p.grid_size = 20;
  p.pins = pin_mode::none;
  p.wind_strength = 10.0;
  p.wind_direction = {1.0, 0.0, 0.3};
  p.sphere = {.enabled = true, .centre = {0.0, 0.0, -0.3}, .radius = 0.2};
  p.self_collision_thickness = 0.03;
  p.tear_strain = 0.2;
  p.drag = {.enabled = true, .ku = 0, .kv = 0, .target = {-1.0, -1.0, 0.5}, .stiffness = 3000.0};
  spring_mesh readable(p);
  spring_mesh fast_result(p);
  const std::size_t intact = spring_count(readable);
  const double difference = run_both(1000, readable, fast_result);
  std::printf("  %zu springs torn; max relative difference %.3g\n", intact - spring_count(readable),
              difference);
  EXPECT_LE(difference, 1e-9);
  expect_same_springs(fast_result, readable);
}

// XPBD (xpbd.hpp): the parallel path runs the readable solver's arithmetic, colour by colour,
// the constraints of a colour sharing no particle, so that no order of the threads changes a
// number: the two paths agree bitwise (difference 0), with the wind, the drag, the sphere, the
// ground, the paper's damping, several sweeps, tearing and question 10's scaling.
TEST(ClothParallelXpbd, AgreesBitwiseWithTheReadableSolver) {
  std::vector<agreement_case> xpbd_cases;
  for (agreement_case c : cases()) {
    if (c.parameters.dynamics.integrator == integrator_kind::explicit_euler)
      continue;
    c.parameters.dynamics.integrator = integrator_kind::xpbd;
    c.parameters.dynamics.time_step = 0.01;  // a step the Euler schemes could not take
    c.steps = 150;
    xpbd_cases.push_back(c);
  }
  cloth_parameters damped = xpbd_cases[0].parameters;
  damped.dynamics.xpbd = {.substeps = 4, .iterations = 3, .constraint_damping = 30.0};
  xpbd_cases.push_back({"damped, 4 x 3 sweeps", damped, 150});
  cloth_parameters tearing = damped;
  tearing.tear_strain = 0.25;
  tearing.drag = {
      .enabled = true, .ku = 23, .kv = 23, .target = {1.5, 1.5, -1.0}, .stiffness = 5000.0};
  xpbd_cases.push_back({"tearing", tearing, 150});
  for (const agreement_case& c : xpbd_cases) {
    spring_mesh readable(c.parameters);
    spring_mesh fast_result(c.parameters);
    const std::size_t intact = spring_count(readable);
    const double difference = run_both(c.steps, readable, fast_result);
    const std::size_t torn = intact - spring_count(readable);
    std::printf("  xpbd, %-24s %d steps: max relative difference %.3g, %zu springs torn\n", c.name,
                c.steps, difference, torn);
    EXPECT_EQ(difference, 0.0) << c.name;
    EXPECT_EQ(torn > 0, c.parameters.tear_strain > 0.0) << c.name;
    expect_same_springs(fast_result, readable);
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
