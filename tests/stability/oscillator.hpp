// The single spring of stage 1 turned into a 1D harmonic oscillator, the test bench of the
// stability tests: gravity and damping off, the mass straight below the fixed p0 = (0.1, 0, 1)
// at extension x0 and at rest. The spring force on it is then K (L0 - L) along the axis,
// x'' = -(K/m) x exactly (x = L - L0), so x(t) = x0 cos(omega t), omega = sqrt(K/m).
#pragma once

#include "core/single_spring.hpp"

namespace clothlab::testing {

constexpr double rest_length = 0.5;  // L0 of single_spring::load_model
constexpr double fixed_z = 1.0;      // z of p0

inline single_spring axial_oscillator(integrator_kind integrator, double time_step,
                                      double stiffness, double extension, double damping = 0.0) {
  single_spring_parameters p;
  p.dynamics.time_step = time_step;
  p.dynamics.damping = damping;
  p.dynamics.mass = 1.0;
  p.dynamics.gravity = 0.0;
  p.dynamics.integrator = integrator;
  p.stiffness = stiffness;
  single_spring spring(p);
  spring.particles().set_position(1, {0.1, 0.0, fixed_z - (rest_length + extension)});
  spring.particles().set_velocity(1, {0.0, 0.0, 0.0});
  return spring;
}

// x = L - L0 of the oscillator (the mass stays on the vertical axis).
inline double extension(const single_spring& spring) {
  return fixed_z - spring.particles().position[5] - rest_length;
}

}  // namespace clothlab::testing
