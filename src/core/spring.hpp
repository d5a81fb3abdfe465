// Springs and the one spring-force function that serves the single spring, the chain and the
// cloth (handout equation 2).
#pragma once

#include <cstdint>
#include <span>

namespace clothlab {

// A spring between particles a and b; its stiffness comes from the stage's parameters.
struct spring {
  std::uint32_t a;     // particle index
  std::uint32_t b;     // particle index
  double rest_length;  // L0, m: the distance in the initial configuration
};

// For every spring, adds to the forces of both ends (Newton's third law):
//   F_a = K (L0 - |p_a - p_b|) (p_a - p_b) / |p_a - p_b|,   F_b = -F_a.
// position and force are flat arrays (3k + c).
void accumulate_spring_forces(std::span<const spring> springs, double stiffness,
                              std::span<const double> position, std::span<double> force);

}  // namespace clothlab
