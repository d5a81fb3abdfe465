#include "core/energy.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace clothlab {

energy_breakdown compute_energy(const particle_system& particles,
                                std::span<const spring_set> spring_sets, double mass,
                                double gravity) {
  energy_breakdown energy;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      continue;
    const glm::dvec3 v = particles.get_velocity(k);
    energy.kinetic += 0.5 * mass * glm::dot(v, v);                     // m |v|^2 / 2
    energy.gravity += mass * gravity * particles.position[3 * k + 2];  // m g0 z
  }
  for (const spring_set& set : spring_sets) {
    for (const spring& s : set.springs) {
      const double length = glm::length(particles.get_position(s.a) - particles.get_position(s.b));
      const double extension = length - s.rest_length;
      energy.spring += 0.5 * set.stiffness * extension * extension;  // K (L - L0)^2 / 2
    }
  }
  energy.total = energy.kinetic + energy.gravity + energy.spring;
  return energy;
}

energy_breakdown compute_energy(const single_spring& stage) {
  const spring_set sets[] = {{stage.springs(), stage.parameters.stiffness}};
  return compute_energy(stage.particles(), sets, stage.parameters.dynamics.mass,
                        stage.parameters.dynamics.gravity);
}

energy_breakdown compute_energy(const coupled_springs& stage) {
  const spring_set sets[] = {{stage.springs(), stage.parameters.stiffness}};
  return compute_energy(stage.particles(), sets, stage.parameters.dynamics.mass,
                        stage.parameters.dynamics.gravity);
}

energy_breakdown compute_energy(const spring_mesh& stage) {
  const std::array<spring_set, 3> sets = stage.spring_sets();
  const cloth_parameters effective = stage.effective_parameters();
  return compute_energy(stage.particles(), sets, effective.dynamics.mass,
                        effective.dynamics.gravity);
}

void write_energy_csv_header(std::ostream& out) {
  out << "step,t,kinetic,gravity,spring,total\n";
}

void write_energy_csv_row(std::ostream& out, long step, double time,
                          const energy_breakdown& energy) {
  char line[160];
  std::snprintf(line, sizeof line, "%ld,%.17g,%.17g,%.17g,%.17g,%.17g\n", step, time,
                energy.kinetic, energy.gravity, energy.spring, energy.total);
  out << line;
}

}  // namespace clothlab
