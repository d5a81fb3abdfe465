#include "core/implicit_euler.hpp"

#include <algorithm>
#include <cmath>

namespace clothlab {
namespace {

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    sum += a[i] * b[i];
  return sum;
}

}  // namespace

// The spring Jacobian. For a spring between a and b, with d = p_a - p_b, L = |d|, u = d / L,
// the force on a is f_a = -K (L - L0) u (handout equation 2). With dL/dp_a = u^T and
// du/dp_a = (I - u u^T) / L:
//   df_a/dp_a = -K [ u u^T + (L - L0) / L (I - u u^T) ]
//             = K [ (L0/L - 1) I - (L0/L) u u^T ]                =: J_s
// and df_a/dp_b = df_b/dp_a = -J_s, df_b/dp_b = J_s (f_b = -f_a depends on d only).
// Along the spring J_s u = -K u: the stiffness K. Across it, J_s w = -K (1 - L0/L) w: the
// tension per unit length. When the spring is compressed (L < L0) that transverse term is
// positive, J_s is not negative definite and A may lose definiteness, which CG needs: as is
// usual since Choi and Ko (2002), the transverse coefficient is clamped at 0,
//   J_s = -K [ c I + (1 - c) u u^T ],   c = max(0, 1 - L0/L),
// which changes the linearisation only, not the forces, and keeps the scheme first order.
void implicit_euler_solver::step(const dynamics_parameters& dynamics, const force_model& forces,
                                 particle_system& particles) {
  const double dt = dynamics.time_step;
  const double m = dynamics.mass;
  const std::size_t dof = particles.position.size();
  mass_term_ = 1.0 + dynamics.damping * dt;  // from M - dt df/dv = m (1 + mu dt) I
  stiffness_term_ = dt * dt / m;             // from -dt^2 df/dx, divided by m

  // The blocks J_s at p0 (resized only when the topology changes).
  std::size_t spring_count = 0;
  for (const spring_set& set : forces.spring_sets)
    spring_count += set.springs.size();
  jacobian_blocks_.resize(spring_count);
  block_springs_.resize(spring_count);
  std::size_t s_index = 0;
  for (const spring_set& set : forces.spring_sets) {
    for (const spring& s : set.springs) {
      const std::size_t a = 3 * std::size_t{s.a};
      const std::size_t b = 3 * std::size_t{s.b};
      double u[3] = {particles.position[a] - particles.position[b],
                     particles.position[a + 1] - particles.position[b + 1],
                     particles.position[a + 2] - particles.position[b + 2]};
      const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      block& j = jacobian_blocks_[s_index];
      block_springs_[s_index] = &s;
      ++s_index;
      if (length == 0.0) {  // no direction: no linearised stiffness
        j.fill(0.0);
        continue;
      }
      for (double& c : u)
        c /= length;
      const double transverse = std::max(0.0, 1.0 - s.rest_length / length);  // c
      const double k = set.stiffness;
      // -K [c I + (1 - c) u u^T]
      j = {-k * (transverse + (1 - transverse) * u[0] * u[0]),
           -k * (transverse + (1 - transverse) * u[1] * u[1]),
           -k * (transverse + (1 - transverse) * u[2] * u[2]),
           -k * (1 - transverse) * u[0] * u[1],
           -k * (1 - transverse) * u[0] * u[2],
           -k * (1 - transverse) * u[1] * u[2]};
    }
  }

  rhs_.resize(dof);
  solution_.resize(dof);
  residual_.resize(dof);
  direction_.resize(dof);
  product_.resize(dof);
  preconditioned_.resize(dof);
  inverse_diagonal_.resize(dof);

  // b = dt (f0 / m + (dt / m) J v0), f0 / m = F / m + g - mu v0. First J v0 into product_.
  std::fill(product_.begin(), product_.end(), 0.0);
  std::fill(inverse_diagonal_.begin(), inverse_diagonal_.end(), 0.0);  // holds diag(J) for now
  for (std::size_t i = 0; i < spring_count; ++i) {
    const block& j = jacobian_blocks_[i];
    const std::size_t a = 3 * std::size_t{block_springs_[i]->a};
    const std::size_t b = 3 * std::size_t{block_springs_[i]->b};
    const double dv[3] = {particles.velocity[a] - particles.velocity[b],
                          particles.velocity[a + 1] - particles.velocity[b + 1],
                          particles.velocity[a + 2] - particles.velocity[b + 2]};
    const double jx = j[0] * dv[0] + j[3] * dv[1] + j[4] * dv[2];
    const double jy = j[3] * dv[0] + j[1] * dv[1] + j[5] * dv[2];
    const double jz = j[4] * dv[0] + j[5] * dv[1] + j[2] * dv[2];
    product_[a] += jx;
    product_[a + 1] += jy;
    product_[a + 2] += jz;
    product_[b] -= jx;
    product_[b + 1] -= jy;
    product_[b + 2] -= jz;
    for (int c = 0; c < 3; ++c) {
      inverse_diagonal_[a + c] += j[c];
      inverse_diagonal_[b + c] += j[c];
    }
  }
  const double gravity[3] = {0.0, 0.0, -dynamics.gravity};
  for (std::size_t k = 0; k < particles.size(); ++k) {
    for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
      if (particles.is_fixed[k]) {  // the filter: no row, no column
        rhs_[i] = 0.0;
        inverse_diagonal_[i] = 0.0;
        continue;
      }
      const double acceleration =
          particles.force[i] / m + gravity[i - 3 * k] - dynamics.damping * particles.velocity[i];
      rhs_[i] = dt * (acceleration + dt / m * product_[i]);
      // Jacobi preconditioner: 1 / A_ii, A_ii = (1 + mu dt) - (dt^2 / m) J_ii > 0.
      inverse_diagonal_[i] = 1.0 / (mass_term_ - stiffness_term_ * inverse_diagonal_[i]);
    }
  }

  // Preconditioned conjugate gradient from dv = 0.
  std::fill(solution_.begin(), solution_.end(), 0.0);
  residual_ = rhs_;
  const double rhs_norm = std::sqrt(dot(rhs_, rhs_));
  last_iterations_ = 0;
  if (rhs_norm > 0.0) {
    for (std::size_t i = 0; i < dof; ++i)
      preconditioned_[i] = inverse_diagonal_[i] * residual_[i];
    direction_ = preconditioned_;
    double rz = dot(residual_, preconditioned_);
    const int max_iterations = 3 * static_cast<int>(dof) + 100;
    double residual_norm = rhs_norm;
    while (last_iterations_ < max_iterations) {
      multiply(particles, direction_, product_);
      const double curvature = dot(direction_, product_);
      // A residual so small that its squares underflow (a run at rest after a long time): the
      // step is solved; dividing 0 by 0 would make it NaN.
      if (!(rz > 0.0) || !(curvature > 0.0))
        break;
      const double alpha = rz / curvature;
      for (std::size_t i = 0; i < dof; ++i) {
        solution_[i] += alpha * direction_[i];
        residual_[i] -= alpha * product_[i];
      }
      ++last_iterations_;
      residual_norm = std::sqrt(dot(residual_, residual_));
      if (!(residual_norm > tolerance * rhs_norm))  // converged (or NaN: stop, let it show)
        break;
      for (std::size_t i = 0; i < dof; ++i)
        preconditioned_[i] = inverse_diagonal_[i] * residual_[i];
      const double rz_next = dot(residual_, preconditioned_);
      const double beta = rz_next / rz;
      rz = rz_next;
      for (std::size_t i = 0; i < dof; ++i)
        direction_[i] = preconditioned_[i] + beta * direction_[i];
    }
  }

  // v1 = v0 + dv, p1 = p0 + dt v1 (dv is 0 for fixed particles).
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      continue;
    for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
      particles.velocity[i] += solution_[i];
      particles.position[i] += dt * particles.velocity[i];
    }
  }
}

void implicit_euler_solver::multiply(const particle_system& particles, const std::vector<double>& x,
                                     std::vector<double>& y) const {
  // y = (1 + mu dt) x - (dt^2 / m) J x, J x assembled spring by spring.
  for (std::size_t i = 0; i < x.size(); ++i)
    y[i] = mass_term_ * x[i];
  for (std::size_t i = 0; i < jacobian_blocks_.size(); ++i) {
    const block& j = jacobian_blocks_[i];
    const std::size_t a = 3 * std::size_t{block_springs_[i]->a};
    const std::size_t b = 3 * std::size_t{block_springs_[i]->b};
    const double d[3] = {x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]};
    const double jx = stiffness_term_ * (j[0] * d[0] + j[3] * d[1] + j[4] * d[2]);
    const double jy = stiffness_term_ * (j[3] * d[0] + j[1] * d[1] + j[5] * d[2]);
    const double jz = stiffness_term_ * (j[4] * d[0] + j[5] * d[1] + j[2] * d[2]);
    y[a] -= jx;
    y[a + 1] -= jy;
    y[a + 2] -= jz;
    y[b] += jx;
    y[b + 1] += jy;
    y[b + 2] += jz;
  }
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      y[3 * k] = y[3 * k + 1] = y[3 * k + 2] = 0.0;
  }
}

}  // namespace clothlab
