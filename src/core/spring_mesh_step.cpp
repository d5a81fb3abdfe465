// The parts of the cloth's step beyond the handout's functions (spring_mesh.cpp): its parameters
// at this N (question 10), the mouse drag, the pins and gravity wherever the answers put them, the
// stability lab's schemes and the constraints. None of it is a question of the lab;
// spring_mesh::step (spring_mesh.hpp) calls them in order.
#include <algorithm>

#include "core/contacts.hpp"
#include "core/spring_mesh.hpp"
#include "core/xpbd.hpp"

namespace clothlab {

cloth_parameters spring_mesh::effective_parameters() const {
  cloth_parameters built = parameters;
  built.grid_size = grid_size_;
  return effective_cloth_parameters(built);
}

// The pins: one trial step of apply_force from the state at rest with every vertex moving (speed
// (1, 1, 1), no force); a vertex whose position it leaves exactly as it was is pinned (a free one
// moves by dt (1 - mu dt) along x at least). Only with --pins corners and when load_model marked
// none (question 7 pins in is_fixed or in apply_force, not both): apply_force runs at load only
// for the answers that need it, so that one that prints or crashes stays question 6's. Gravity:
// compute_force on the cloth at rest without wind gives the springs' forces, zero within rounding,
// plus m g if it adds gravity. The state is put back.
void spring_mesh::find_pins_and_gravity() {
  const dynamics_parameters d = effective_parameters().dynamics;
  const particle_system state = particles_;
  std::vector<std::uint8_t> pinned = state.is_fixed;
  const bool marked = std::find(pinned.begin(), pinned.end(), 1) != pinned.end();
  const bool pinning = parameters.pins == pin_mode::corners && !marked;  // --pins none: none
  if (pinning && d.time_step > 0.0 && d.damping * d.time_step != 1.0) {  // else none can tell
    std::fill(particles_.velocity.begin(), particles_.velocity.end(), 1.0);
    std::fill(particles_.force.begin(), particles_.force.end(), 0.0);
    apply_force();
    for (std::size_t k = 0; k < particles_.size(); ++k)
      if (particles_.get_position(k) == state.get_position(k))
        pinned[k] = 1;
    particles_ = state;
  }
  particles_.is_fixed = std::move(pinned);

  const double wind = parameters.wind_strength;
  parameters.wind_strength = 0.0;
  compute_force();
  parameters.wind_strength = wind;
  const glm::dvec3 weight = {0.0, 0.0, -d.mass * d.gravity};  // m g, N
  bool with_gravity = weight.z != 0.0;
  for (std::size_t k = 0; k < particles_.size() && with_gravity; ++k)
    with_gravity = glm::length(particles_.get_force(k) - weight) < 0.5 * std::abs(weight.z);
  gravity_in_forces_ = with_gravity;
  particles_.force = state.force;
}

void spring_mesh::add_drag_force() {
  const drag_parameters& drag = parameters.drag;
  const int n = grid_size_;
  if (!drag.enabled || drag.ku < 0 || drag.ku >= n || drag.kv < 0 || drag.kv >= n)
    return;
  const std::size_t k = index(drag.ku, drag.kv, n);
  if (particles_.is_fixed[k])
    return;  // a pinned vertex cannot be dragged
  as_vectors(particles_.force)[k] +=
      drag.stiffness * (drag.target - as_vectors(particles_.position)[k]);
}

void spring_mesh::integrate_step() {
  const integrator_kind scheme = parameters.dynamics.integrator;
  if (scheme == integrator_kind::semi_implicit) {
    apply_force();  // question 6
    return;
  }
  const cloth_parameters at_this_n = effective_parameters();  // the mass at this N
  const dynamics_parameters& d = at_this_n.dynamics;
  if (scheme == integrator_kind::explicit_euler) {
    // Equation 6 taken literally (model.md): the speeds of apply_force (question 6), and every
    // vertex that it moves moved by its speed at the start of the step, p + dt v(t).
    stage_state_.position = particles_.position;
    stage_state_.velocity = particles_.velocity;
    apply_force();
    std::span<glm::dvec3> p = as_vectors(particles_.position);
    std::span<const glm::dvec3> p_start = as_vectors(stage_state_.position);
    std::span<const glm::dvec3> v_start = as_vectors(stage_state_.velocity);
    for (std::size_t k = 0; k < particles_.size(); ++k)
      if (particles_.is_fixed[k] == 0)
        p[k] = p_start[k] + d.time_step * v_start[k];
    return;
  }
  const std::array<spring_set, 3> sets = spring_sets();
  force_model forces = {sets, [this](std::span<const double> position, std::span<double> force) {
                          forces_at(position, force);
                        }};
  if (scheme == integrator_kind::xpbd) {
    // The wind and the drag move the particles; the springs are constraints, visited colour by
    // colour (xpbd.hpp).
    forces.external = [this, &at_this_n](std::span<const double> position,
                                         std::span<double> force) {
      xpbd_cloth_external_force(at_this_n, position, particles_.is_fixed, normals_, force);
    };
    forces.colour = [n = grid_size_](const spring& s) { return cloth_constraint_colour(s, n); };
    // The sphere and the ground at the end of every substep (xpbd.hpp), in place of after the
    // step (apply_constraints).
    forces.contacts = [this](double substep, particle_system& particles) {
      cloth_parameters over_substep = parameters;  // the contacts' friction over h
      over_substep.dynamics.time_step = substep;
      if (parameters.sphere.enabled)
        apply_sphere_contact(parameters.sphere, substep, particles);
      apply_ground_contact(over_substep, particles);  // question 9
    };
  }
  integrator_.step(d, forces, particles_);
}

// compute_force works on the current state: the stage's positions are swapped in, and the
// current state (with its normals) is put back after.
void spring_mesh::forces_at(std::span<const double> position, std::span<double> force) {
  stage_state_.position.assign(position.begin(), position.end());
  // The current normals stand in until compute_force computes the stage's (with the wind only):
  // an answer may read normals[k] whatever K_w.
  stage_normals_.assign(normals_.begin(), normals_.end());
  stage_state_.force.resize(particles_.force.size());
  std::swap(particles_.position, stage_state_.position);
  std::swap(particles_.force, stage_state_.force);
  std::swap(normals_, stage_normals_);
  compute_force();
  add_drag_force();
  if (gravity_in_forces_) {  // the schemes add g themselves (find_pins_and_gravity)
    const dynamics_parameters d = effective_parameters().dynamics;
    for (glm::dvec3& f : as_vectors(particles_.force))
      f.z += d.mass * d.gravity;
  }
  std::copy(particles_.force.begin(), particles_.force.end(), force.begin());
  std::swap(particles_.position, stage_state_.position);
  std::swap(particles_.force, stage_state_.force);
  std::swap(normals_, stage_normals_);
}

void spring_mesh::apply_constraints() {
  // In the order of docs/model.md: the sphere (an addition), the ground (question 9),
  // self-collision (an addition), then tearing (an addition). The pins are apply_force's: it
  // never moves a fixed vertex.
  // XPBD makes the sphere and ground contacts in its substeps (integrate_step).
  const double dt = parameters.dynamics.time_step;
  const bool contacts_made = parameters.dynamics.integrator == integrator_kind::xpbd;
  if (parameters.sphere.enabled && !contacts_made)
    apply_sphere_contact(parameters.sphere, dt, particles_);
  if (!contacts_made)
    apply_ground_contact(parameters, particles_);  // question 9
  if (parameters.self_collision_thickness > 0.0)
    self_collision_.apply(grid_size_, self_collision_distance(parameters), particles_);
  if (parameters.tear_strain > 0.0)
    tear_springs(parameters.tear_strain);
}

}  // namespace clothlab
