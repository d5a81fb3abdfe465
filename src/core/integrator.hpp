// Time integration of a particle system whose forces are already computed (model.md).
#pragma once

#include "parameters.hpp"
#include "particle_system.hpp"

namespace clothlab {

// One step of length dt with the acceleration a = F / m + (0, 0, -g0) and the damping factor
// (1 - mu dt), by the chosen integrator. Fixed particles do not move and keep a zero velocity.
void integrate(const dynamics_parameters& dynamics, particle_system& particles);

}  // namespace clothlab
