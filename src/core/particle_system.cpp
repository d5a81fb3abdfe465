#include "core/particle_system.hpp"

#include <algorithm>
#include <cmath>

namespace clothlab {

void particle_system::resize(std::size_t n) {
  position.assign(3 * n, 0.0);
  velocity.assign(3 * n, 0.0);
  force.assign(3 * n, 0.0);
  is_fixed.assign(n, 0);
}

void particle_system::set_position(std::size_t k, const glm::dvec3& p) {
  for (int c = 0; c < 3; ++c)
    position[3 * k + c] = p[c];
}

void particle_system::set_velocity(std::size_t k, const glm::dvec3& v) {
  for (int c = 0; c < 3; ++c)
    velocity[3 * k + c] = v[c];
}

bool particle_system::is_finite() const {
  auto finite = [](double x) { return std::isfinite(x); };
  return std::all_of(position.begin(), position.end(), finite) &&
         std::all_of(velocity.begin(), velocity.end(), finite);
}

}  // namespace clothlab
