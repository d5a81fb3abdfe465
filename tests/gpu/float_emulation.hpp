// The CPU cloth run as a float path of another rounding would run it, with no GPU: what the
// GPU tests' tolerances are checked on (other_roundings_test.cpp), and what they take from the
// cloth that the student's questions build, where that cloth carries a rounding further than
// single_precision's bounds assume (agreement_cases.hpp, tolerance_of).
#pragma once

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/spring_mesh.hpp"
#include "single_precision.hpp"

namespace clothlab {

// Every step, each force component off by up to the rounding of one structural spring's force
// in float (its length, from float coordinates below P, off by u P: K_struct u P), at random;
// the state then stored in float, as the GPU stores it. `seed` picks the roundings.
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
inline cloth_parameters as_floats(cloth_parameters p) {
  p.ground_height = static_cast<float>(p.ground_height);
  p.sphere.centre = glm::dvec3(glm::vec3(p.sphere.centre));
  p.sphere.radius = static_cast<float>(p.sphere.radius);
  return p;
}

// How far float runs of other roundings end from the cloth in double after `steps` steps: the
// largest difference over the seeds first_seed, first_seed + 1, ... (`seeds` of them).
struct float_spread {
  double position = 0.0;  // m
  double velocity = 0.0;  // m/s
};

inline float_spread spread_of_float_runs(const cloth_parameters& given, int steps,
                                         std::uint32_t first_seed, int seeds) {
  const cloth_parameters p = as_floats(given);
  spring_mesh reference(p);
  double largest = 0.0;
  const auto take_largest = [&largest](const spring_mesh& cloth) {
    for (double x : cloth.particles().position)
      largest = std::max(largest, std::abs(x));
  };
  take_largest(reference);
  for (int s = 0; s < steps; ++s) {
    reference.step();
    take_largest(reference);
  }
  float_spread worst;
  for (int seed = 0; seed < seeds; ++seed) {
    float_emulation emulated(p, first_seed + static_cast<std::uint32_t>(seed));
    for (int s = 0; s < steps; ++s)
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

}  // namespace clothlab
