// Stage 1 (handout section 3, questions 2 to 4): one spring from the fixed point
// p0 = (0.1, 0, 1) to the moving mass p1, which starts at (0.1, 0, 0.5) with velocity (1, -1, 0).
#pragma once

#include <array>
#include <span>

#include "core/integrator.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring.hpp"
#include "core/step_phases.hpp"

namespace clothlab {

class single_spring {
 public:
  single_spring_parameters parameters;  // edited live; read at every step

  explicit single_spring(const single_spring_parameters& p = {});

  void load_model();  // initialisation: p0, p1, v1 and L0 = |p1 - p0| (particle 0 is p0)
  // Force computation: the spring force on both ends (equation 2), and the mouse drag on p1
  // when it is on (parameters.drag), from the current positions, into particles().force.
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
  time_integrator integrator_;  // the scheme's scratch arrays, kept between steps
  std::array<spring, 1> springs_{};
};

// Question 2's 1D start (--start 1d, the window's "1D start" box): of v1, only its component
// along the spring (p1 - p0) is kept, so that the mass moves on the spring's line, the motion of
// the 1D model. Applied after load_model.
void keep_velocity_along_spring(single_spring& stage);

}  // namespace clothlab
