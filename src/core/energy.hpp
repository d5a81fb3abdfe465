// The mechanical energy of a stage: what each integrator does with it shows its
// character. Without damping the exact motion keeps the total constant; explicit Euler makes it
// grow, the symplectic schemes (semi-implicit Euler, Verlet) keep it within a bounded
// oscillation, and the implicit scheme makes it decay.
#pragma once

#include <ostream>
#include <span>

#include "core/coupled_springs.hpp"
#include "core/force_model.hpp"
#include "core/particle_system.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

struct energy_breakdown {
  double kinetic = 0.0;  // J: sum over moving particles of m |v|^2 / 2
  double gravity = 0.0;  // J: sum over moving particles of m g0 z (zero at z = 0)
  double spring = 0.0;   // J: sum over every spring of K (L - L0)^2 / 2
  double total = 0.0;    // J: the sum of the three (the wind's work is not a potential)
};

// The energies of a particle system with the given springs, mass m and gravity g0.
// Fixed and pinned particles carry no kinetic or gravitational energy (they never move).
energy_breakdown compute_energy(const particle_system& particles,
                                std::span<const spring_set> spring_sets, double mass,
                                double gravity);

// The same for each stage with its current parameters (the cloth's effective mass and
// stiffnesses, question 10).
energy_breakdown compute_energy(const single_spring& stage);
energy_breakdown compute_energy(const coupled_springs& stage);
energy_breakdown compute_energy(const spring_mesh& stage);

// --energy-csv: the header `step,t,kinetic,gravity,spring,total`, then one row per step written,
// numbers as %.17g (t = step dt, model.md).
void write_energy_csv_header(std::ostream& out);
void write_energy_csv_row(std::ostream& out, long step, double time,
                          const energy_breakdown& energy);

}  // namespace clothlab
