// Springs and the one spring-force function that serves the single spring, the chain and the
// cloth (handout equation 2).
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace clothlab {

// A spring between particles a and b; its stiffness comes from the stage's parameters.
struct spring {
  std::uint32_t a;     // particle index
  std::uint32_t b;     // particle index
  double rest_length;  // L0, m: the distance in the initial configuration
};

// Handout equation 2: the force that a spring of stiffness K and rest length L0 between the
// particles at p_i and p_j exerts on the one at p_i (the one at p_j feels the opposite force):
//   F = K (L0 - |p_i - p_j|) (p_i - p_j) / |p_i - p_j|.
inline glm::dvec3 spring_force(const glm::dvec3& p_i, const glm::dvec3& p_j, double K, double L0) {
  const glm::dvec3 d = p_i - p_j;
  const double L = glm::length(d);
  return K * (L0 - L) / L * d;
}

}  // namespace clothlab
