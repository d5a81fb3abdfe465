#include "core/single_spring.hpp"

#include <algorithm>

#include "core/integrator.hpp"

namespace clothlab {

single_spring::single_spring(const single_spring_parameters& p) : parameters(p) {
  load_model();
}

void single_spring::load_model() {
  const glm::dvec3 p0 = {0.1, 0.0, 1.0};  // fixed end
  const glm::dvec3 p1 = {0.1, 0.0, 0.5};  // moving mass
  particles_.resize(2);
  particles_.set_position(0, p0);
  particles_.is_fixed[0] = 1;
  particles_.set_position(1, p1);
  particles_.set_velocity(1, {1.0, -1.0, 0.0});
  springs_[0] = {0, 1, glm::length(p1 - p0)};  // L0 = |p1 - p0| = 0.5
}

void single_spring::compute_force() {
  compute_force(particles_.position, particles_.force);
}

void single_spring::compute_force(std::span<const double> position, std::span<double> force) const {
  // The handout's code of section 2: the spring (K, L0) pulls p1 by equation 2; p0 is fixed.
  std::span<const glm::dvec3> p = as_vectors(position);  // p[0] = p0, p[1] = p1
  std::span<glm::dvec3> forces = as_vectors(force);
  std::fill(force.begin(), force.end(), 0.0);
  forces[1] = spring_force(p[1], p[0], parameters.stiffness, springs_[0].rest_length);
  // The mouse drag (an addition, docs/model.md): F_d = K_d (q - p1) on p1; p0 is fixed.
  add_mass_drag_force(parameters.drag, particles_.is_fixed, position, force);
}

void single_spring::apply_force() {
  const dynamics_parameters& d = parameters.dynamics;
  if (d.integrator != integrator_kind::semi_implicit &&
      d.integrator != integrator_kind::explicit_euler) {
    // The stability lab's other schemes (integrator.hpp), not the handout's.
    const spring_set sets[] = {{springs_, parameters.stiffness}};
    const auto forces_at = [this](std::span<const double> position, std::span<double> force) {
      compute_force(position, force);
    };
    // XPBD's forces that are not springs: the mouse drag (its spring is a constraint).
    const auto drag_at = [this](std::span<const double> position, std::span<double> force) {
      std::fill(force.begin(), force.end(), 0.0);
      add_mass_drag_force(parameters.drag, particles_.is_fixed, position, force);
    };
    integrator_.step(d, {sets, forces_at, drag_at}, particles_);
    return;
  }
  // Numerical integration: the handout's code of section 2 (question 3), for the mass p1
  // (p0 is fixed), F the force of compute_force, g = (0, 0, -g0).
  const double dt = d.time_step;                // the time step, s
  const double mu = d.damping;                  // the damping, 1/s
  const double m = d.mass;                      // the mass, kg
  const glm::dvec3 g = {0.0, 0.0, -d.gravity};  // gravity, m/s^2
  const glm::dvec3 F = particles_.get_force(1);
  glm::dvec3 p1 = particles_.get_position(1);
  glm::dvec3 v1 = particles_.get_velocity(1);
  if (d.integrator == integrator_kind::semi_implicit) {
    v1 = (1.0 - mu * dt) * v1 + dt * (F / m + g);  // the handout's order: the speed first,
    p1 = p1 + dt * v1;                             // then the position with the new speed
  } else {
    p1 = p1 + dt * v1;  // equation 6: the position with the speed at the start of the step
    v1 = (1.0 - mu * dt) * v1 + dt * (F / m + g);
  }
  particles_.set_position(1, p1);
  particles_.set_velocity(1, v1);
}

void keep_velocity_along_spring(single_spring& stage) {
  particle_system& particles = stage.particles();
  const glm::dvec3 axis = particles.get_position(1) - particles.get_position(0);
  const glm::dvec3 v = particles.get_velocity(1);
  particles.set_velocity(1, glm::dot(v, axis) / glm::dot(axis, axis) * axis);
}

}  // namespace clothlab
