// Backward Euler linearised once per step (Baraff and Witkin, "Large steps in cloth simulation",
// SIGGRAPH 1998), the scheme that stays stable at any time step.
//
// Backward Euler takes the slopes at the END of the step:
//   v1 = v0 + dt M^-1 f(p1, v1),   p1 = p0 + dt v1.
// Linearising f once about the start, f(p1, v1) ~ f0 + df/dx (p1 - p0) + df/dv (v1 - v0), and
// writing dv = v1 - v0, p1 - p0 = dt (v0 + dv), gives one linear system per step:
//   (M - dt df/dv - dt^2 df/dx) dv = dt (f0 + dt df/dx v0).
// Here M = m I, f0 = F(p0) + m g - mu m v0 (springs, wind, gravity, damping), df/dv = -mu m I
// (the damping force -mu m v) and df/dx = J, the spring Jacobian (implicit_euler.cpp); the wind
// is explicit (its force at the start of the step, not differentiated). Dividing by m:
//   A dv = b,   A = (1 + mu dt) I - (dt^2 / m) J,   b = dt (f0 / m + (dt / m) J v0).
// A is symmetric positive definite (J is made negative semi-definite, see the .cpp), so the
// system is solved by the conjugate gradient, matrix-free: A x is computed spring by spring
// from 3 x 3 blocks stored once per step. Fixed and pinned particles are constraints: their rows
// and columns are removed by zeroing their components of every CG vector (filtered CG), so
// their dv is 0.
#pragma once

#include <array>
#include <vector>

#include "core/force_model.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"

namespace clothlab {

class implicit_euler_solver {
 public:
  // One step: particles.force holds F(p0) (springs and wind at the start of the step).
  void step(const dynamics_parameters& dynamics, const force_model& forces,
            particle_system& particles);

  int last_iterations() const { return last_iterations_; }  // CG iterations of the last step

  static constexpr double tolerance = 1e-10;  // relative residual at which CG stops

 private:
  using block = std::array<double, 6>;  // symmetric 3 x 3: xx, yy, zz, xy, xz, yz

  // y <- A x for the current blocks, zero for fixed particles (the filter).
  void multiply(const particle_system& particles, const std::vector<double>& x,
                std::vector<double>& y) const;

  double mass_term_ = 1.0;                    // 1 + mu dt
  double stiffness_term_ = 0.0;               // dt^2 / m
  std::vector<block> jacobian_blocks_;        // J_s of every spring, in spring_set order
  std::vector<const spring*> block_springs_;  // the spring of each block
  std::vector<double> rhs_, solution_, residual_, direction_, product_, preconditioned_,
      inverse_diagonal_;
  int last_iterations_ = 0;
};

}  // namespace clothlab
