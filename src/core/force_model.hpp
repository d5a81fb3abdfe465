// The forces of a stage seen by an integrator: a function of the positions that the schemes with
// several stages per step (Verlet, RK4) evaluate at intermediate states, the spring data that
// the implicit scheme differentiates, and what XPBD needs: the forces that are not springs and
// the order in which to visit the springs.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring.hpp"

namespace clothlab {

// One family of springs and its stiffness (the cloth has three, the spring and the chain one).
struct spring_set {
  std::span<const spring> springs;
  double stiffness;  // K, N/m
};

// F(p), the forces that do not depend on the velocity. The velocity-dependent damping belongs to
// the integrator (model.md's (1 - mu dt) factor, or the force -mu m v).
struct force_model {
  std::span<const spring_set> spring_sets;  // every family with its stiffness (implicit scheme)
  // force <- F(position): the stage's own compute_force at the given positions (the cloth's
  // wind with the normals of THOSE positions).
  std::function<void(std::span<const double> position, std::span<double> force)> compute;
  // force <- the forces that are not springs at the given positions (the cloth's wind, the mouse
  // drag; not gravity): XPBD's, whose springs are constraints (xpbd.hpp). Empty: none.
  std::function<void(std::span<const double> position, std::span<double> force)> external = {};
  // XPBD's colour of a spring: the springs are visited by increasing colour, and two springs of
  // one colour share no particle (the cloth's cloth_constraint_colour). Empty: every spring has
  // colour 0 and they are visited in the order of their sets (a chain's, from the fixed end).
  std::function<int(const spring&)> colour = {};
  // XPBD's contacts at the end of every substep h (the cloth's sphere and ground, over h, on the
  // particles as they are): a contact made once after the step would be undone in the next
  // step's first substep, and its push turned into a speed of its depth over h. Empty: none.
  std::function<void(double substep, particle_system& particles)> contacts = {};
};

// force <- F(position), by forces.compute.
void evaluate_forces(const force_model& forces, std::span<const double> position,
                     std::span<double> force);

// The mouse drag on a mass of stages 1 and 2 (model.md, "Drag"): adds F_d = K_d (q - p_k) to
// force[k], k = drag.mass, when the drag is on, k is one of the particles and it is not fixed
// (the fixed p0 cannot be dragged). Positions and forces flat, 3k + c.
void add_mass_drag_force(const mass_drag_parameters& drag, std::span<const std::uint8_t> is_fixed,
                         std::span<const double> position, std::span<double> force);

}  // namespace clothlab
