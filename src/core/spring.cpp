#include "spring.hpp"

#include <cmath>

namespace clothlab {

void accumulate_spring_forces(std::span<const spring> springs, double stiffness,
                              std::span<const double> position, std::span<double> force) {
  for (const spring& s : springs) {
    const std::size_t a = 3 * std::size_t{s.a};
    const std::size_t b = 3 * std::size_t{s.b};
    // d = p_a - p_b, L = |d|
    const double dx = position[a] - position[b];
    const double dy = position[a + 1] - position[b + 1];
    const double dz = position[a + 2] - position[b + 2];
    const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
    // F_a = K (L0 - L) d / L; F_b = -F_a
    const double scale = stiffness * (s.rest_length - length) / length;
    const double fx = scale * dx;
    const double fy = scale * dy;
    const double fz = scale * dz;
    force[a] += fx;
    force[a + 1] += fy;
    force[a + 2] += fz;
    force[b] -= fx;
    force[b + 1] -= fy;
    force[b + 2] -= fz;
  }
}

}  // namespace clothlab
