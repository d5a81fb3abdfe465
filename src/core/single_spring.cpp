#include "single_spring.hpp"

#include <algorithm>

#include "integrator.hpp"

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
  const spring_set sets[] = {{springs_, parameters.stiffness}};
  compute_spring_forces(sets, particles_.position, particles_.force);
}

void single_spring::apply_force() {
  const spring_set sets[] = {{springs_, parameters.stiffness}};
  const auto forces_at = [&sets](std::span<const double> position, std::span<double> force) {
    compute_spring_forces(sets, position, force);
  };
  integrator_.step(parameters.dynamics, {sets, forces_at}, particles_);
}

}  // namespace clothlab
