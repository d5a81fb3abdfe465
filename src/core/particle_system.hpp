// The state of a set of particles, laid out as in the handout: flat arrays of doubles where
// coordinate c (0 = x, 1 = y, 2 = z) of particle k is at index 3k + c.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace clothlab {

struct particle_system {
  std::vector<double> position;        // p, m
  std::vector<double> velocity;        // v, m/s
  std::vector<double> force;           // F, N: spring (and wind) forces of the current step
  std::vector<std::uint8_t> is_fixed;  // 1: fixed or pinned, never moves, velocity stays 0

  std::size_t size() const { return is_fixed.size(); }

  // n particles at the origin, at rest, none fixed.
  void resize(std::size_t n);

  glm::dvec3 get_position(std::size_t k) const {
    return {position[3 * k], position[3 * k + 1], position[3 * k + 2]};
  }
  glm::dvec3 get_velocity(std::size_t k) const {
    return {velocity[3 * k], velocity[3 * k + 1], velocity[3 * k + 2]};
  }
  glm::dvec3 get_force(std::size_t k) const {
    return {force[3 * k], force[3 * k + 1], force[3 * k + 2]};
  }
  void set_position(std::size_t k, const glm::dvec3& p);
  void set_velocity(std::size_t k, const glm::dvec3& v);

  // True when every position and velocity is finite (no NaN, no infinity).
  bool is_finite() const;
};

}  // namespace clothlab
