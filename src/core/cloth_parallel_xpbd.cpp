// XPBD on the parallel CPU path (--backend cpu-parallel --integrator xpbd): the readable
// solver's step (xpbd.cpp) with its loops shared among the threads. Every particle's prediction
// and velocity is its own; the constraints are solved colour by colour, and the constraints of
// one colour share no particle (cloth_constraint_colour), so the threads solve a colour at once
// and no order of theirs changes a number: the result is the readable path's, bitwise (tested).
// The teacher's alone (grading/lab.json), like the rest of the path.
#include <omp.h>

#include <algorithm>

#include "core/cloth_parallel.hpp"
#include "core/contacts.hpp"
#include "core/spring_mesh.hpp"  // apply_ground_contact

namespace clothlab {

void cloth_parallel::step_xpbd(const cloth_parameters& p) {
  if (!xpbd_constraints_listed_)
    list_xpbd_constraints();
  // The state in the readable path's layout (3k + c), where the readable solver's arithmetic
  // applies as it is written (glm::dvec3).
  particle_system& state = xpbd_state_;
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(vx_.size());
  {
    const double *x = x_[current_].data(), *y = y_[current_].data(), *z = z_[current_].data();
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      state.position[3 * k] = x[k];
      state.position[3 * k + 1] = y[k];
      state.position[3 * k + 2] = z[k];
      state.velocity[3 * k] = vx_[k];
      state.velocity[3 * k + 1] = vy_[k];
      state.velocity[3 * k + 2] = vz_[k];
    }
  }
  const dynamics_parameters& d = p.dynamics;
  const xpbd_parameters& settings = d.xpbd;
  const double h = d.time_step / settings.substeps;
  const double m = d.mass;
  const glm::dvec3 g = {0.0, 0.0, -d.gravity};
  const double damping_factor = 1.0 - d.damping * h;
  cloth_parameters over_substep = p;  // the ground's friction over h
  over_substep.dynamics.time_step = h;
  xpbd_external_.resize(state.position.size());
  xpbd_cloth_external_force(p, state.position, state.is_fixed, xpbd_normals_, xpbd_external_);
  const std::array<xpbd_compliance, 3> compliance = {
      compliance_of(p.structural_stiffness, h, settings.constraint_damping),
      compliance_of(p.shear_stiffness, h, settings.constraint_damping),
      compliance_of(p.bending_stiffness, h, settings.constraint_damping)};
  xpbd_previous_.resize(state.position.size());
  xpbd_multiplier_.resize(xpbd_constraints_.size());

  std::span<glm::dvec3> position = as_vectors(state.position);
  std::span<glm::dvec3> velocity = as_vectors(state.velocity);
  std::span<glm::dvec3> x_prev = as_vectors(xpbd_previous_);
  std::span<const glm::dvec3> f_ext = as_vectors(std::span<const double>(xpbd_external_));
  const std::uint8_t* fixed = state.is_fixed.data();
  const xpbd_constraint* constraints = xpbd_constraints_.data();
  double* lambda = xpbd_multiplier_.data();
  const auto constraint_count = static_cast<std::ptrdiff_t>(xpbd_constraints_.size());
  const double inverse_mass = 1.0 / m;

#pragma omp parallel num_threads(threads())
  for (int substep = 0; substep < settings.substeps; ++substep) {
    // 1. Predict (and the multipliers back to 0).
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      x_prev[k] = position[k];
      if (fixed[k])
        continue;
      velocity[k] = damping_factor * velocity[k] + h * (f_ext[k] / m + g);
      position[k] = position[k] + h * velocity[k];
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t c = 0; c < constraint_count; ++c)
      lambda[c] = 0.0;
    // 2. Colour by colour, each colour's constraints on every thread at once.
    for (int iteration = 0; iteration < settings.iterations; ++iteration) {
      for (int colour = 0; colour < cloth_constraint_colours; ++colour) {
        const auto first = static_cast<std::ptrdiff_t>(xpbd_colour_start_[colour]);
        const auto end = static_cast<std::ptrdiff_t>(xpbd_colour_start_[colour + 1]);
#pragma omp for schedule(static)
        for (std::ptrdiff_t c = first; c < end; ++c) {
          const xpbd_constraint& s = constraints[c];
          const xpbd_compliance& alpha = compliance[s.set];
          if (!alpha.active)
            continue;
          const double w_a = fixed[s.a] ? 0.0 : inverse_mass;
          const double w_b = fixed[s.b] ? 0.0 : inverse_mass;
          lambda[c] += project_distance_constraint(position[s.a], position[s.b], x_prev[s.a],
                                                   x_prev[s.b], w_a, w_b, s.rest_length,
                                                   alpha.alpha_tilde, alpha.gamma, lambda[c]);
        }
      }
    }
    // 3. The velocity is the motion over the substep.
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      if (!fixed[k])
        velocity[k] = (position[k] - x_prev[k]) / h;
    }
    // 4. The contacts over h, as the readable path makes them (xpbd.hpp), on one thread.
#pragma omp single
    {
      if (p.sphere.enabled)
        apply_sphere_contact(p.sphere, h, state);
      apply_ground_contact(over_substep, state);
    }
  }

  double *x = x_[current_].data(), *y = y_[current_].data(), *z = z_[current_].data();
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    x[k] = state.position[3 * k];
    y[k] = state.position[3 * k + 1];
    z[k] = state.position[3 * k + 2];
    vx_[k] = state.velocity[3 * k];
    vy_[k] = state.velocity[3 * k + 1];
    vz_[k] = state.velocity[3 * k + 2];
  }
}

}  // namespace clothlab
