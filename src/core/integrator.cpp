#include "integrator.hpp"

namespace clothlab {

void integrate(const dynamics_parameters& dynamics, particle_system& particles) {
  const double dt = dynamics.time_step;
  const double damping_factor = 1.0 - dynamics.damping * dt;  // (1 - mu dt)
  const double inverse_mass = 1.0 / dynamics.mass;
  const double gravity[3] = {0.0, 0.0, -dynamics.gravity};  // g = (0, 0, -g0)
  const std::size_t n = particles.size();
  double* p = particles.position.data();
  double* v = particles.velocity.data();
  const double* f = particles.force.data();

  switch (dynamics.integrator) {
    case integrator_kind::semi_implicit:
      // v <- (1 - mu dt) v + dt a(p), then p <- p + dt v with the new v.
      for (std::size_t k = 0; k < n; ++k) {
        if (particles.is_fixed[k])
          continue;
        for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
          const double a = f[i] * inverse_mass + gravity[i - 3 * k];
          v[i] = damping_factor * v[i] + dt * a;
          p[i] = p[i] + dt * v[i];
        }
      }
      break;
    case integrator_kind::explicit_euler:
      // p_new = p + dt v and v_new = (1 - mu dt) v + dt a(p), both from the old state (eq. 6).
      for (std::size_t k = 0; k < n; ++k) {
        if (particles.is_fixed[k])
          continue;
        for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
          const double a = f[i] * inverse_mass + gravity[i - 3 * k];
          p[i] = p[i] + dt * v[i];
          v[i] = damping_factor * v[i] + dt * a;
        }
      }
      break;
  }
}

}  // namespace clothlab
