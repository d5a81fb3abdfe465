#include "core/integrator.hpp"

#include <stdexcept>
#include <string>

namespace clothlab {
void time_integrator::step(const dynamics_parameters& dynamics, const force_model& forces,
                           particle_system& particles) {
  switch (dynamics.integrator) {
    case integrator_kind::semi_implicit:
    case integrator_kind::explicit_euler:
      throw std::invalid_argument(
          "time_integrator: the " + std::string(integrator_name(dynamics.integrator)) +
          " Euler scheme is the stage's own apply_force (the cloth's: question 6)");
    case integrator_kind::velocity_verlet:
      step_velocity_verlet(dynamics, forces, particles);
      break;
    case integrator_kind::runge_kutta_4:
      step_runge_kutta_4(dynamics, forces, particles);
      break;
    case integrator_kind::implicit_euler:
      implicit_.step(dynamics, forces, particles);
      break;
    case integrator_kind::xpbd:
      xpbd_.step(dynamics, forces, particles);
      break;
  }
}

void time_integrator::evaluate_accelerations(const dynamics_parameters& dynamics,
                                             const force_model& forces,
                                             const particle_system& particles,
                                             std::span<const double> position,
                                             std::span<const double> velocity,
                                             const std::vector<double>* known,
                                             std::span<double> acceleration) {
  if (known == nullptr) {
    evaluate_forces(forces, position, stage_force_);
    known = &stage_force_;
  }
  const std::vector<double>& force = *known;
  const double inverse_mass = 1.0 / dynamics.mass;
  const double gravity[3] = {0.0, 0.0, -dynamics.gravity};
  for (std::size_t k = 0; k < particles.size(); ++k) {
    for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
      // a = F / m + g - mu v (the damping force -mu m v divided by m); fixed particles: 0.
      acceleration[i] = particles.is_fixed[k] ? 0.0
                                              : force[i] * inverse_mass + gravity[i - 3 * k] -
                                                    dynamics.damping * velocity[i];
    }
  }
}

// Velocity Verlet (kick, drift, kick):
//   v_half = v0 + dt/2 a(p0, v0)
//   p1     = p0 + dt v_half
//   v1     = v_half + dt/2 (F(p1) / m + g - mu v1)
// The last line is implicit in v1 only through the linear damping term; solved exactly:
//   v1 = (v_half + dt/2 (F(p1) / m + g)) / (1 + mu dt / 2),
// which keeps the scheme second order with damping (taking -mu v_half there would make it first
// order). Without damping it is the symplectic leapfrog: dt < 2/omega.
void time_integrator::step_velocity_verlet(const dynamics_parameters& dynamics,
                                           const force_model& forces, particle_system& particles) {
  const double dt = dynamics.time_step;
  const std::size_t dof = particles.position.size();
  stage_force_.resize(dof);
  stage_acceleration_.resize(dof);
  evaluate_accelerations(dynamics, forces, particles, particles.position, particles.velocity,
                         &particles.force, stage_acceleration_);
  for (std::size_t i = 0; i < dof; ++i) {
    particles.velocity[i] += 0.5 * dt * stage_acceleration_[i];  // v_half (0 for fixed)
    particles.position[i] += dt * particles.velocity[i];         // p1
  }
  evaluate_forces(forces, particles.position, stage_force_);  // F(p1)
  const double inverse_mass = 1.0 / dynamics.mass;
  const double gravity[3] = {0.0, 0.0, -dynamics.gravity};
  const double damping_divisor = 1.0 + 0.5 * dynamics.damping * dt;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      continue;
    for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
      const double kick = 0.5 * dt * (stage_force_[i] * inverse_mass + gravity[i - 3 * k]);
      particles.velocity[i] = (particles.velocity[i] + kick) / damping_divisor;
    }
  }
}

// Classical fourth-order Runge-Kutta on y = (p, v), y' = (v, a(p, v)):
//   k1 = slope(y0), k2 = slope(y0 + dt/2 k1), k3 = slope(y0 + dt/2 k2), k4 = slope(y0 + dt k3),
//   y1 = y0 + dt/6 (k1 + 2 k2 + 2 k3 + k4).
// Each slope evaluates the forces at its own positions (the wind with their normals).
void time_integrator::step_runge_kutta_4(const dynamics_parameters& dynamics,
                                         const force_model& forces, particle_system& particles) {
  const double dt = dynamics.time_step;
  const std::size_t dof = particles.position.size();
  stage_position_.resize(dof);
  stage_velocity_.resize(dof);
  stage_force_.resize(dof);
  stage_acceleration_.resize(dof);
  position_increment_.assign(dof, 0.0);
  velocity_increment_.assign(dof, 0.0);

  constexpr double stage_offset[4] = {0.0, 0.5, 0.5, 1.0};  // where slope s is taken, in dt
  constexpr double stage_weight[4] = {1.0, 2.0, 2.0, 1.0};  // its weight, in dt / 6
  // The slope of p is the stage's velocity, that of v its acceleration; stage 0 is y0 itself.
  stage_position_ = particles.position;
  stage_velocity_ = particles.velocity;
  for (int s = 0; s < 4; ++s) {
    evaluate_accelerations(dynamics, forces, particles, stage_position_, stage_velocity_,
                           s == 0 ? &particles.force : nullptr, stage_acceleration_);
    for (std::size_t i = 0; i < dof; ++i) {
      position_increment_[i] += stage_weight[s] * stage_velocity_[i];
      velocity_increment_[i] += stage_weight[s] * stage_acceleration_[i];
    }
    if (s == 3)
      break;
    // The next stage's state y0 + c dt k_s (k_s = this stage's (velocity, acceleration)).
    const double offset = stage_offset[s + 1] * dt;
    for (std::size_t i = 0; i < dof; ++i) {
      const double slope_of_position = stage_velocity_[i];
      stage_position_[i] = particles.position[i] + offset * slope_of_position;
      stage_velocity_[i] = particles.velocity[i] + offset * stage_acceleration_[i];
    }
  }
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      continue;
    for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
      particles.position[i] += dt / 6.0 * position_increment_[i];
      particles.velocity[i] += dt / 6.0 * velocity_increment_[i];
    }
  }
}

}  // namespace clothlab
