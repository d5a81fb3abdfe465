// Time integration of a particle system (model.md, "Integrators", and the three added schemes).
//
// Every scheme advances the state (p, v) of the moving particles by one step of length dt under
//   p' = v,   v' = a(p, v) = F(p) / m + g - damping,
// F the spring forces (and the cloth's wind), g = (0, 0, -g0). Fixed and pinned particles never
// move and keep a zero velocity; the cloth's ground contact is applied by the stage after the
// step. The five schemes (order: of the global error in dt; limit: for a mode of angular
// frequency omega without damping):
//   semi-implicit: v += dt a(p), then p += dt v with the new v.  Order 1, dt < 2/omega.
//   explicit:      p += dt v and v += dt a(p), from the old state.  Order 1, never stable.
//   verlet:        v_half = v + dt/2 a(p, v), p' = p + dt v_half,
//                  v' = v_half + dt/2 a(p', v') (a depends on v' only through -mu v', so
//                  this is solved in closed form).  Order 2, dt < 2/omega.
//   rk4:           classical Runge-Kutta on (p, v).  Order 4, dt < 2 sqrt(2)/omega.
//   implicit:      backward Euler linearised once per step.  Order 1, every dt.
//   xpbd:          the springs as compliant distance constraints, in substeps (xpbd.hpp).
//                  Order 1, every dt.
// The first two are model.md's and multiply v by (1 - mu dt); the other three apply the damping
// as the force -mu m v (the same to first order in dt). stability.hpp gives every limit exactly.
#pragma once

#include <span>
#include <vector>

#include "core/force_model.hpp"
#include "core/implicit_euler.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/xpbd.hpp"

namespace clothlab {

// Runs the schemes. It keeps the scratch arrays of the multi-stage schemes and the implicit
// solver between steps, so that a step allocates nothing once the size is known.
class time_integrator {
 public:
  // One step of length dynamics.time_step by dynamics.integrator, one of the stability lab's
  // four schemes (verlet, rk4, implicit, xpbd); throws std::invalid_argument for the two Euler
  // schemes, which are each stage's own apply_force. particles.force must hold F(p) at the
  // start of the step (the stage's compute_force; xpbd reads forces.external instead); it is
  // left unchanged.
  void step(const dynamics_parameters& dynamics, const force_model& forces,
            particle_system& particles);

  // The implicit scheme's solver, for its statistics (iterations of the last step).
  const implicit_euler_solver& implicit_solver() const { return implicit_; }

 private:
  void step_velocity_verlet(const dynamics_parameters& dynamics, const force_model& forces,
                            particle_system& particles);
  void step_runge_kutta_4(const dynamics_parameters& dynamics, const force_model& forces,
                          particle_system& particles);
  // acceleration <- F(position) / m + g - mu velocity for moving particles, 0 for fixed ones;
  // the force array is given when already known (F at the start of the step), else computed.
  void evaluate_accelerations(const dynamics_parameters& dynamics, const force_model& forces,
                              const particle_system& particles, std::span<const double> position,
                              std::span<const double> velocity, const std::vector<double>* known,
                              std::span<double> acceleration);

  std::vector<double> stage_position_;  // p of an intermediate stage, 3k + c
  std::vector<double> stage_velocity_;  // v of an intermediate stage
  std::vector<double> stage_force_;     // F at an intermediate stage
  std::vector<double> stage_acceleration_;
  std::vector<double> position_increment_;  // RK4: sum of the weighted slopes of p
  std::vector<double> velocity_increment_;  // RK4: sum of the weighted slopes of v
  implicit_euler_solver implicit_;
  xpbd_solver xpbd_;
};

}  // namespace clothlab
