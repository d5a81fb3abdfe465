// The agreement cases' tolerances hold for other roundings than this machine's GPU (llvmpipe)
// and than the four a tolerance takes its spread from, shown on the CPU, with no GPU: the CPU
// cloth run as a float path of another rounding would run it (float_emulation.hpp), against the
// CPU cloth in double. And the case that failed on an NVIDIA GPU (a contact
// decided on its boundary) fails here too, so the check can see what a real GPU saw.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/spring_mesh.hpp"

#include "agreement_cases.hpp"
#include "single_precision.hpp"

namespace clothlab {
namespace {

struct emulated_difference {
  double position = 0.0;  // m: the largest over the seeds
  double velocity = 0.0;  // m/s
  single_precision::bounds tolerance{};
  single_precision::bounds bound{};  // single_precision's alone
};

// The float runs of `seeds` roundings (seeds 0, 1, ...: none of those the tolerance takes its
// spread from) against the cloth in double, and the case's tolerance.
emulated_difference emulate(const agreement_case& c, int seeds) {
  spring_mesh reference(as_floats(c.parameters));
  double largest = largest_coordinate(reference);
  for (int s = 0; s < c.steps; ++s) {
    reference.step();
    largest = largest_coordinate(reference, largest);
  }
  const float_spread spread = spread_of_float_runs(c.parameters, c.steps, 0, seeds);
  return {spread.position, spread.velocity, tolerance_of(c, largest), bound_of(c, largest)};
}

constexpr int seeds = 8;

TEST(SolutionGpuTolerances, AFloatClothOfOtherRoundingsStaysWithinThemInEveryCase) {
  for (const agreement_case& c : agreement_cases()) {
    const emulated_difference d = emulate(c, seeds);
    const std::string integrator(integrator_name(c.parameters.dynamics.integrator));
    std::printf(
        "  %-10s %-13s %d roundings: max |dp| = %.2g m (tolerance %.2g, bound %.2g), max |dv| = "
        "%.2g m/s (tolerance %.2g)\n",
        c.name, integrator.c_str(), seeds, d.position, d.tolerance.position, d.bound.position,
        d.velocity, d.tolerance.velocity);
    EXPECT_LE(d.position, d.tolerance.position) << c.name << ", " << integrator;
    EXPECT_LE(d.velocity, d.tolerance.velocity) << c.name << ", " << integrator;
  }
}

// A case on the contact's boundary (a free cloth dragged by a corner onto a sphere of radius
// 0.28 m, explicit: agreement_cases.hpp says why): a particle resting on the sphere is in contact
// on one path and not on the other, and they end 0.1 m/s apart, as both GPU paths did on an
// NVIDIA GPU. The emulation sees it.
TEST(SolutionGpuTolerances, TheEmulationFindsTheFlippedContactOfACaseOnTheBoundary) {
  agreement_case on_the_boundary = {"SphereDrag", agreement_cloth()};
  cloth_parameters& p = on_the_boundary.parameters;
  p.pins = pin_mode::none;
  p.sphere = {.enabled = true, .centre = {0.0, 0.0, -0.3}, .radius = 0.28};
  p.drag = {.enabled = true, .ku = 11, .kv = 11, .target = {0.6, 0.6, 0.2}, .stiffness = 1000.0};
  on_the_boundary = with_integrator(on_the_boundary, integrator_kind::explicit_euler);
  const emulated_difference d = emulate(on_the_boundary, seeds);
  std::printf("  SphereDrag explicit: max |dv| = %.2g m/s (bound %.2g)\n", d.velocity,
              d.bound.velocity);
  EXPECT_GT(d.velocity, d.bound.velocity);
}

// The smallest | |p - c| - r | of a run's contact decisions (every particle, every step, after
// the integrator, before the contact), m.
double nearest_decision_to_the_sphere(const cloth_parameters& p, int steps) {
  spring_mesh cloth(p);
  double nearest = 1e300;
  for (int s = 0; s < steps; ++s) {
    cloth.compute_force();
    cloth.add_drag_force();
    cloth.integrate_step();
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const double distance = glm::length(cloth.particles().get_position(k) - p.sphere.centre);
      nearest = std::min(nearest, std::abs(distance - p.sphere.radius));
    }
    cloth.apply_constraints();
  }
  return nearest;
}

// The sphere case is off the decision's boundary (agreement_cases.hpp): every decision is
// farther from the surface than the paths may be apart (single_precision's bound, with a factor
// 2 to spare), so none can differ between them.
TEST(SolutionGpuTolerances, TheSphereCaseDecidesEveryContactFarFromTheSurface) {
  for (const agreement_case& c : agreement_cases()) {
    if (!c.parameters.sphere.enabled)
      continue;
    spring_mesh cloth(c.parameters);
    double largest = largest_coordinate(cloth);
    for (int s = 0; s < c.steps; ++s) {
      cloth.step();
      largest = largest_coordinate(cloth, largest);
    }
    const double nearest = nearest_decision_to_the_sphere(c.parameters, c.steps);
    const double tolerance = bound_of(c, largest).position;
    const std::string integrator(integrator_name(c.parameters.dynamics.integrator));
    std::printf("  %s %s: nearest decision %.2g m from the surface, tolerance %.2g m\n", c.name,
                integrator.c_str(), nearest, tolerance);
    EXPECT_GT(nearest, 2 * tolerance) << integrator;
    EXPECT_GT(particles_on_sphere(cloth), 0) << integrator << ": the case must touch the sphere";
  }
}

}  // namespace
}  // namespace clothlab
