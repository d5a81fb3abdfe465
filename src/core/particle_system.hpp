// The state of a set of particles, laid out as in the handout: flat arrays of doubles where
// coordinate c (0 = x, 1 = y, 2 = z) of particle k is at index 3k + c.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
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

// A flat array (3k + c) seen as one glm::dvec3 per particle: as_vectors(position)[k] is the
// position of particle k, as the handout's vertices[k]. The arrays stay flat for the code that
// reads doubles (the parallel CPU path, the GPU upload, the export); a glm::dvec3 is three
// doubles and nothing else, so both views are of the same memory.
static_assert(sizeof(glm::dvec3) == 3 * sizeof(double) && alignof(glm::dvec3) == alignof(double),
              "glm::dvec3 must be laid out as three doubles");
inline std::span<glm::dvec3> as_vectors(std::vector<double>& flat) {
  return {reinterpret_cast<glm::dvec3*>(flat.data()), flat.size() / 3};
}
inline std::span<const glm::dvec3> as_vectors(const std::vector<double>& flat) {
  return {reinterpret_cast<const glm::dvec3*>(flat.data()), flat.size() / 3};
}
inline std::span<glm::dvec3> as_vectors(std::span<double> flat) {
  return {reinterpret_cast<glm::dvec3*>(flat.data()), flat.size() / 3};
}
inline std::span<const glm::dvec3> as_vectors(std::span<const double> flat) {
  return {reinterpret_cast<const glm::dvec3*>(flat.data()), flat.size() / 3};
}

}  // namespace clothlab
