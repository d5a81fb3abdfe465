// Question 4 (and 10): why a large stiffness K or a large time step dt makes the simulation
// explode, in numbers.
//
// Near a state, the springs act on small displacements x as x'' = -M^-1 K x (K the stiffness
// matrix, M = m I): independent modes x'' = -omega^2 x, omega^2 the eigenvalues of M^-1 K, plus
// the damping. One step of a scheme maps a mode's (x, v) to A (x, v), A a 2 x 2 matrix; the mode
// grows by rho(A), the largest |eigenvalue| of A, per step. The run is stable when rho <= 1 for
// every mode, and the stiffest mode, omega_max, decides: the step-size limits below decrease
// with omega.
//
// omega_max is bounded by Gershgorin's theorem in block form (Feingold and Varga) on M^-1 K,
// linearised at rest: a spring of stiffness K_s between i and j adds K_s u u^T to the diagonal
// blocks of i and j and -K_s u u^T to the block (i, j), each of norm K_s (u the unit direction).
// Every eigenvalue lies within sum_j |K_ij| of an eigenvalue of a diagonal block K_ii, so
//   omega_max^2 <= max over moving i of (1/m) [ sum_{springs s of i} K_s
//                                               + sum_{springs s of i to a moving j} K_s ]
// (a spring to a fixed or pinned particle has no off-diagonal block). This is exact for the
// single spring (K / m); for a chain it gives 3K/m (n = 2, exact 2.618 K/m) up to 4K/m, the
// exact limit of long chains; for the cloth's interior 2 (4 K_struct + 4 K_shear + 4 K_bend) / m.
// It also holds at any state where every spring has L >= L0/2: the linearised block is then
// K [(1 - L0/L) I + (L0/L) u u^T], of eigenvalues K along u and K (1 - L0/L) across, both
// at most K in size.
//
// Step-size limits for one mode (omega, damping rate mu), derived from each scheme's A
// (Jury's conditions on lambda^2 - trace lambda + det):
//   semi-implicit  trace 2 - mu dt - (omega dt)^2, det 1 - mu dt:
//                  stable iff (omega dt)^2 + 2 mu dt < 4, i.e.
//                  dt < 4 / (mu + sqrt(mu^2 + 4 omega^2))      (= 2/omega undamped; exact)
//   explicit       trace 2 - mu dt, det 1 - mu dt + (omega dt)^2:
//                  stable iff omega^2 dt < mu (and, when mu >= 2 omega, dt < (mu - sqrt(mu^2 -
//                  4 omega^2)) / omega^2): dt < mu / omega^2; never without damping, where each
//                  step multiplies the amplitude by sqrt(1 + (omega dt)^2) > 1           (exact)
//   verlet         2/omega undamped (the leapfrog's); with damping, the first dt at which
//                  rho(A) exceeds 1, found numerically on the exact A
//   rk4            2 sqrt(2)/omega = 2.83/omega undamped: the classical RK4 stability region
//                  meets the imaginary axis at |omega dt| = 2 sqrt 2 (2.785 is where it meets
//                  the negative real axis, the limit for pure damping); with damping, numerical
//   implicit       none: rho(A) < 1 for every dt > 0 (it damps every mode, the stiffest most)
//   xpbd           none: one substep of a linear spring is backward Euler after a damped
//                  prediction (amplification_factor takes dt as the substep)
#pragma once

#include <span>
#include <string>

#include "core/coupled_springs.hpp"
#include "core/force_model.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

// rho(A): the growth of a mode of angular frequency omega (rad/s) per step of length dt (s)
// with damping rate mu (1/s), for the scheme as implemented (integrator.cpp; for xpbd, per
// substep of length dt, xpbd.hpp).
double amplification_factor(integrator_kind integrator, double omega, double damping, double dt);

// The largest stable dt (s) for that mode: infinity when every dt is stable, 0 when none is
// (explicit Euler without damping).
double time_step_limit(integrator_kind integrator, double omega, double damping);

// The Gershgorin bound on omega_max (rad/s) above, for the given springs; 0 without springs.
double gershgorin_omega_max(const particle_system& particles,
                            std::span<const spring_set> spring_sets, double mass);

struct stability_estimate {
  double omega_max = 0.0;        // rad/s: upper bound on the stiffest mode (Gershgorin)
  double time_step_limit = 0.0;  // s: the current integrator's limit for omega_max
  double ratio = 0.0;            // dt / time_step_limit: below 1 is stable (0 when no limit)
  std::string explanation;       // one line: the condition, its value and where dt stands
};

// For a stage with its current parameters (the cloth's effective ones, question 10).
stability_estimate estimate_stability(const particle_system& particles,
                                      std::span<const spring_set> spring_sets,
                                      const dynamics_parameters& dynamics);
stability_estimate estimate_stability(const single_spring& stage);
stability_estimate estimate_stability(const coupled_springs& stage);
stability_estimate estimate_stability(const spring_mesh& stage);

// Divergence beyond NaN. A diverging run blows up geometrically (by rho per step), so it is
// caught early and cheaply by bounding the speeds: one pass over the velocities after every
// step, looking for a non-finite position or velocity, or a speed beyond speed_bound.
struct divergence_status {
  bool diverged = false;
  std::string reason;  // empty when not diverged, e.g. "speed 5.1e+04 m/s of particle 3 > ..."
};
divergence_status divergence_check(const particle_system& particles, double speed_bound);

// The speed bound of a stage: 1000 times its characteristic speed
//   v_c = max(1 m/s, largest initial speed, sqrt(2 g0 H)),
// H the height the stage can fall (spring 1 m, chain 0.5 (n + 1) m, cloth S + 1 m): no stable
// run comes near it, and a diverging one passes it within a few tens of steps.
double divergence_speed_bound(double gravity, double fall_height, double initial_speed);
divergence_status divergence_check(const single_spring& stage);
divergence_status divergence_check(const coupled_springs& stage);
divergence_status divergence_check(const spring_mesh& stage);
double divergence_speed_bound(const spring_mesh& stage);  // the bound the cloth's check uses

}  // namespace clothlab
