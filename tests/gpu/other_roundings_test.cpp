// The agreement cases' tolerances hold for other roundings than this machine's GPU (llvmpipe),
// shown on the CPU, with no GPU: the CPU cloth run as a float path of another rounding would run
// it, against the CPU cloth in double. And the case that failed on an NVIDIA GPU (a contact
// decided on its boundary) fails here too, so the check can see what a real GPU saw.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/spring_mesh.hpp"

#include "agreement_cases.hpp"
#include "single_precision.hpp"

namespace clothlab {
namespace {

// The CPU cloth as a float path of another rounding runs it: every step, each force component
// off by up to the rounding of one structural spring's force in float (its length, from float
// coordinates below P, off by u P: K_struct u P), at random; the state then stored in float,
// as the GPU stores it. `seed` picks the roundings.
class float_emulation {
 public:
  float_emulation(const cloth_parameters& p, std::uint32_t seed) : cloth(p), random_(seed) {
    store_in_float();
  }

  void step(double largest_coordinate) {
    const double force_rounding =
        cloth.structural_stiffness() * single_precision::unit_roundoff * largest_coordinate;
    cloth.compute_force();
    cloth.add_drag_force();
    for (double& f : cloth.particles().force)
      f += force_rounding * between_minus_one_and_one();
    cloth.integrate_step();
    cloth.apply_constraints();
    store_in_float();
  }

  spring_mesh cloth;

 private:
  void store_in_float() {
    for (std::vector<double>* values : {&cloth.particles().position, &cloth.particles().velocity}) {
      for (double& x : *values)
        x = static_cast<float>(x);
    }
  }
  double between_minus_one_and_one() {
    return 2.0 * (static_cast<double>(random_()) / 4294967296.0) - 1.0;
  }

  std::mt19937 random_;  // (its raw numbers are the same with every standard library)
};

// The parameters as the GPU holds them (floats), so that both runs have the same ground and
// sphere: a coordinate stored as a float is compared with the float z_g, as on the GPU.
cloth_parameters as_floats(cloth_parameters p) {
  p.ground_height = static_cast<float>(p.ground_height);
  p.sphere.centre = glm::dvec3(glm::vec3(p.sphere.centre));
  p.sphere.radius = static_cast<float>(p.sphere.radius);
  return p;
}

struct emulated_difference {
  double position = 0.0;  // m: the largest over the seeds
  double velocity = 0.0;  // m/s
  single_precision::bounds tolerance{};
};

emulated_difference emulate(const agreement_case& given, int seeds) {
  agreement_case c = given;
  c.parameters = as_floats(c.parameters);
  spring_mesh reference(c.parameters);
  double largest = largest_coordinate(reference);
  for (int s = 0; s < c.steps; ++s) {
    reference.step();
    largest = largest_coordinate(reference, largest);
  }
  emulated_difference worst;
  worst.tolerance = tolerance_of(c, largest);
  for (int seed = 0; seed < seeds; ++seed) {
    float_emulation emulated(c.parameters, static_cast<std::uint32_t>(seed));
    for (int s = 0; s < c.steps; ++s)
      emulated.step(largest);
    const auto& a = reference.particles();
    const auto& b = emulated.cloth.particles();
    for (std::size_t i = 0; i < a.position.size(); ++i) {
      worst.position = std::max(worst.position, std::abs(a.position[i] - b.position[i]));
      worst.velocity = std::max(worst.velocity, std::abs(a.velocity[i] - b.velocity[i]));
    }
  }
  return worst;
}

constexpr int seeds = 8;

TEST(SolutionGpuTolerances, AFloatClothOfOtherRoundingsStaysWithinThemInEveryCase) {
  for (const agreement_case& c : agreement_cases()) {
    const emulated_difference d = emulate(c, seeds);
    const std::string integrator(integrator_name(c.parameters.dynamics.integrator));
    std::printf(
        "  %-10s %-13s %d roundings: max |dp| = %.2g m (tolerance %.2g), max |dv| = %.2g m/s "
        "(tolerance %.2g)\n",
        c.name, integrator.c_str(), seeds, d.position, d.tolerance.position, d.velocity,
        d.tolerance.velocity);
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
  std::printf("  SphereDrag explicit: max |dv| = %.2g m/s (tolerance %.2g)\n", d.velocity,
              d.tolerance.velocity);
  EXPECT_GT(d.velocity, d.tolerance.velocity);
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
// farther from the surface than the paths may be apart (the position tolerance, with a factor 2
// to spare), so none can differ between them.
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
    const double tolerance = tolerance_of(c, largest).position;
    const std::string integrator(integrator_name(c.parameters.dynamics.integrator));
    std::printf("  %s %s: nearest decision %.2g m from the surface, tolerance %.2g m\n", c.name,
                integrator.c_str(), nearest, tolerance);
    EXPECT_GT(nearest, 2 * tolerance) << integrator;
    EXPECT_GT(particles_on_sphere(cloth), 0) << integrator << ": the case must touch the sphere";
  }
}

}  // namespace
}  // namespace clothlab
