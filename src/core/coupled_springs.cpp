#include "core/coupled_springs.hpp"

#include <algorithm>

#include "core/integrator.hpp"

namespace clothlab {

coupled_springs::coupled_springs(const coupled_springs_parameters& p) : parameters(p) {
  load_model();
}

void coupled_springs::load_model() {
  const int n = std::max(parameters.mass_count, 1);
  const glm::dvec3 p0 = {0.1, 0.0, 1.0};     // fixed top
  const glm::dvec3 link = {0.0, 0.0, -0.5};  // initial offset between neighbours
  particles_.resize(static_cast<std::size_t>(n) + 1);
  particles_.is_fixed[0] = 1;
  springs_.clear();
  for (int i = 0; i <= n; ++i) {
    particles_.set_position(i, p0 + double(i) * link);
    if (i > 0) {
      const auto a = static_cast<std::uint32_t>(i - 1);
      const auto b = static_cast<std::uint32_t>(i);
      springs_.push_back({a, b, glm::length(link)});
    }
  }
  rest_length_ = glm::length(link);                                        // L0 = 0.5 m
  particles_.set_velocity(static_cast<std::size_t>(n), {1.0, -1.0, 0.0});  // the last mass
}

void coupled_springs::compute_force() {
  compute_force(particles_.position, particles_.force);
}

void coupled_springs::compute_force(std::span<const double> position,
                                    std::span<double> force) const {
  std::span<const glm::dvec3> p = as_vectors(position);  // p[i]: 0 the fixed p0, 1..n the masses
  std::span<glm::dvec3> forces = as_vectors(force);      // forces[i]: the force on p[i], N
  std::fill(force.begin(), force.end(), 0.0);
  const double K = parameters.stiffness;  // every spring of the chain
  const double L0 = rest_length_;         // every spring's rest length
  // BEGIN SOLUTION Q5: the springs of the chain
  // STUDENT(handout)| // TODO Q5 (coupled springs): add the other springs of the chain (handout
  // STUDENT(handout)| // section 3.5, figure 4). The chain has n = p.size() - 1 masses below the
  // STUDENT(handout)| // fixed p[0]; spring i (i = 1..n) joins p[i - 1] and p[i], with stiffness K
  // STUDENT(handout)| // and rest length L0. A spring pulls on both of its ends:
  // STUDENT(handout)| // spring_force(a, b, K, L0) is equation 2, the force on the end at a; decide
  // STUDENT(handout)| // which force each end gets (forces[i], the force on p[i]). For now only the
  // STUDENT(handout)| // first spring acts, and only on mass 1: the masses below it fall. Done when
  // STUDENT(handout)| // ./test.sh -L q5 passes and the chain hangs and sways.
  // STUDENT(guided)| // TODO Q5 (coupled springs): the chain has n = p.size() - 1 masses, and
  // STUDENT(guided)| // spring i (i = 1..n) joins p[i - 1] and p[i]. Give every spring of the chain
  // STUDENT(guided)| // its force, on BOTH of its ends (equation 2):
  // STUDENT(guided)| //   F = spring_force(p[i], p[i - 1], K, L0) pulls p[i], and -F pulls p[i - 1].
  // STUDENT(guided)| // For now only the first spring acts, and only on mass 1: the masses below
  // STUDENT(guided)| // it fall.
  // STUDENT| forces[1] += spring_force(p[1], p[0], K, L0);
  const std::size_t n = p.size() - 1;  // moving masses
  for (std::size_t i = 1; i <= n; ++i) {
    // Spring i joins p[i - 1] and p[i]: F on p[i], and the reaction -F on p[i - 1].
    const glm::dvec3 F = spring_force(p[i], p[i - 1], K, L0);
    forces[i] += F;
    forces[i - 1] -= F;
  }
  // END SOLUTION Q5

  // The mouse drag (an addition, docs/model.md): F_d = K_d (q - p_k) on the dragged mass k;
  // the fixed p0 cannot be dragged.
  add_mass_drag_force(parameters.drag, particles_.is_fixed, position, force);
}

void coupled_springs::apply_force() {
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
  // Numerical integration: the handout's code of section 2 (question 3), for every mass of the
  // chain (p0, fixed, never moves), F its force from compute_force, g = (0, 0, -g0).
  const double dt = d.time_step;                // the time step, s
  const double mu = d.damping;                  // the damping, 1/s
  const double m = d.mass;                      // the mass, kg
  const glm::dvec3 g = {0.0, 0.0, -d.gravity};  // gravity, m/s^2
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (particles_.is_fixed[i])
      continue;
    const glm::dvec3 F = particles_.get_force(i);
    glm::dvec3 p = particles_.get_position(i);
    glm::dvec3 v = particles_.get_velocity(i);
    if (d.integrator == integrator_kind::semi_implicit) {
      v = (1.0 - mu * dt) * v + dt * (F / m + g);  // the handout's order: the speed first,
      p = p + dt * v;                              // then the position with the new speed
    } else {
      p = p + dt * v;  // equation 6: the position with the speed at the start of the step
      v = (1.0 - mu * dt) * v + dt * (F / m + g);
    }
    particles_.set_position(i, p);
    particles_.set_velocity(i, v);
  }
}

}  // namespace clothlab
