// The parts of the cloth's step beyond the handout's functions (spring_mesh.cpp): its parameters
// at this N (question 10), the mouse drag, the stability lab's schemes and the constraints.
// None of it is a question of the lab; spring_mesh::step (spring_mesh.hpp) calls them in order.
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
  if (scheme == integrator_kind::semi_implicit || scheme == integrator_kind::explicit_euler) {
    apply_force();  // question 6
    return;
  }
  const cloth_parameters at_this_n = effective_parameters();  // the mass at this N
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
  }
  integrator_.step(at_this_n.dynamics, forces, particles_);
}

// compute_force works on the current state: the stage's positions are swapped in, and the
// current state (with its normals) is put back after.
void spring_mesh::forces_at(std::span<const double> position, std::span<double> force) {
  stage_state_.position.assign(position.begin(), position.end());
  stage_state_.force.resize(particles_.force.size());
  std::swap(particles_.position, stage_state_.position);
  std::swap(particles_.force, stage_state_.force);
  std::swap(normals_, stage_normals_);
  compute_force();
  add_drag_force();
  std::copy(particles_.force.begin(), particles_.force.end(), force.begin());
  std::swap(particles_.position, stage_state_.position);
  std::swap(particles_.force, stage_state_.force);
  std::swap(normals_, stage_normals_);
}

void spring_mesh::apply_constraints() {
  // In the order of docs/model.md: the sphere (an addition), the ground (question 9),
  // self-collision (an addition), then tearing (an addition). The pins are apply_force's: it
  // never moves a fixed vertex.
  const double dt = parameters.dynamics.time_step;
  if (parameters.sphere.enabled)
    apply_sphere_contact(parameters.sphere, dt, particles_);
  if (parameters.ground_enabled)  // question 9
    apply_ground_contact(parameters.ground_height, parameters.ground_friction, dt, particles_);
  if (parameters.self_collision_thickness > 0.0)
    self_collision_.apply(grid_size_, self_collision_distance(parameters), particles_);
  if (parameters.tear_strain > 0.0)
    tear_springs(parameters.tear_strain);
}

}  // namespace clothlab
