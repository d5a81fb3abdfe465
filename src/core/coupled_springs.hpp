// Stage 2 (question 5): a chain of n masses hanging from the fixed p0 = (0.1, 0, 1).
// Mass i starts at p0 + i (0, 0, -0.5); spring i joins masses i-1 and i; the last mass starts
// with velocity (1, -1, 0). Particle 0 is p0, then 1..n down the chain.
#pragma once

#include <span>
#include <vector>

#include "core/integrator.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring.hpp"
#include "core/step_phases.hpp"

namespace clothlab {

class coupled_springs {
 public:
  coupled_springs_parameters parameters;  // edited live; mass_count is read by load_model

  explicit coupled_springs(const coupled_springs_parameters& p = {});

  void load_model();  // initialisation of the chain (rebuilds it for mass_count)
  // Force computation (question 5): the forces of every spring of the chain on both of its
  // ends, and the mouse drag on one mass when it is on (parameters.drag), from the current
  // positions, into particles().force.
  void compute_force();
  // The same forces at any positions (flat, 3k + c), for the integrators with several stages.
  void compute_force(std::span<const double> position, std::span<double> force) const;
  void apply_force();          // numerical integration of one step (model.md)
  void apply_constraints() {}  // none: the fixed p0 is apply_force's (it never moves it)
  // One step, the handout's phases in their order (question 3): forces, integration,
  // constraints; `phase` wraps each (the window times them).
  template <class Wrap = run_phase>
  void step(Wrap&& phase = {}) {
    phase(step_phase::forces, [this] { compute_force(); });
    phase(step_phase::integration, [this] { apply_force(); });
    phase(step_phase::constraints, [this] { apply_constraints(); });
  }

  const particle_system& particles() const { return particles_; }
  particle_system& particles() { return particles_; }  // to set a state by hand (tests, labs)
  std::span<const spring> springs() const { return springs_; }

 private:
  particle_system particles_;
  time_integrator integrator_;   // the scheme's scratch arrays, kept between steps
  std::vector<spring> springs_;  // spring i joins particles i-1 and i (energy, drawing)
  double rest_length_ = 0.5;     // L0, m, of every spring: the initial spacing
};

}  // namespace clothlab
