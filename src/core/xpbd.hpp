// XPBD, the stability lab's sixth way to step a stage (--integrator xpbd; docs/model.md, "XPBD";
// Macklin, Mueller and Chentanez, "XPBD: Position-Based Simulation of Compliant Constrained
// Dynamics", MIG 2016). Every spring of stiffness K and rest length L0 between particles a and b
// becomes a distance constraint
//   C = |p_a - p_b| - L0,   of compliance alpha = 1 / K   (m/N: K keeps its meaning).
// A step of dt is `substeps` substeps of h = dt / substeps ("small steps"); each substep:
//   1. predicts every moving particle under the forces that are not springs (gravity, the wind,
//      the mouse drag, held at their values at the start of the step) and the damping mu:
//        v <- (1 - mu h) v + h (F_ext / m + g),   x_prev = p,   p <- p + h v;
//   2. sets every multiplier lambda to 0, then `iterations` times visits every constraint, colour
//      by colour (below), and moves its two ends by the paper's equation (26):
//        dlambda = (-C - alpha~ lambda - gamma n.((p_a - x_prev_a) - (p_b - x_prev_b)))
//                  / ((1 + gamma)(w_a + w_b) + alpha~),
//        p_a += w_a dlambda n,   p_b -= w_b dlambda n,   lambda += dlambda,
//      with n = (p_a - p_b) / |p_a - p_b|, w = 1/m (0 for a fixed or pinned particle),
//      alpha~ = alpha / h^2 and gamma = alpha~ beta~ / h, beta~ = h^2 beta (beta, N s/m, the
//      constraint's damping: --xpbd-damping);
//   3. takes the velocity from the motion: v = (p - x_prev) / h;
//   4. makes the contacts (the cloth's sphere and ground, over h: force_model::contacts).
// Self-collision and tearing come after the whole step, as for the other integrators. On a
// linear spring one visit of its constraint is exactly backward Euler of m x'' = -K x - beta x'
// over h: stable at every dt.
//
// The order of the visits is a Gauss-Seidel order: a constraint sees the moves of those before
// it. The cloth's springs are visited in 12 colours (cloth_constraint_colour), each a set of
// springs that share no particle, so that a colour's constraints can be solved all at once (the
// parallel CPU path's threads, the GPU's invocations) and every path computes the same numbers.
// A chain's springs are visited in their order, from the fixed end down.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/force_model.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring.hpp"

namespace clothlab {

// Whether XPBD is built here. It is not in the student copy (xpbd_absent.cpp in place of
// xpbd.cpp): a student could step the cloth with it instead of writing question 8. There,
// every function that would run it throws std::invalid_argument(xpbd_unavailable_reason()).
bool xpbd_available();
const char* xpbd_unavailable_reason();  // "" where it is available

// The cloth's 12 colours, for the spring from its lower end a = (ku, kv) to b: each family's two
// directions, each split by the parity of its place along them, so that no two springs of a
// colour share a particle:
//   0, 1   structural (ku, kv)-(ku+1, kv), ku even / odd
//   2, 3   structural (ku, kv)-(ku, kv+1), kv even / odd
//   4, 5   shear (ku, kv)-(ku+1, kv+1), ku even / odd
//   6, 7   shear (ku, kv)-(ku-1, kv+1), ku even / odd
//   8, 9   bending (ku, kv)-(ku+2, kv), floor(ku / 2) even / odd
//   10, 11 bending (ku, kv)-(ku, kv+2), floor(kv / 2) even / odd
// No fewer colours can do: an inner particle has 12 springs, each of which needs its own colour.
inline constexpr int cloth_constraint_colours = 12;
int cloth_constraint_colour(const spring& s, int grid_size);

// One distance constraint as the solver visits it.
struct xpbd_constraint {
  std::uint32_t a;     // particle index
  std::uint32_t b;     // particle index
  double rest_length;  // L0, m
  std::uint32_t set;   // its spring set (force_model::spring_sets), whose K gives alpha = 1/K
};

// Equation (26) for one distance constraint, the two ends at p_a and p_b (moved in place), their
// positions at the start of the substep x_prev_a, x_prev_b, inverse masses w_a, w_b, and
// alpha~ = alpha / h^2, gamma = alpha beta / h, lambda the multiplier so far in this substep.
// Returns dlambda (0 for two fixed ends or ends at the same point, which have no direction).
// Every CPU path calls it, so that they round alike.
inline double project_distance_constraint(glm::dvec3& p_a, glm::dvec3& p_b,
                                          const glm::dvec3& x_prev_a, const glm::dvec3& x_prev_b,
                                          double w_a, double w_b, double rest_length,
                                          double alpha_tilde, double gamma, double lambda) {
  const double w = w_a + w_b;
  const glm::dvec3 d = p_a - p_b;
  const double L = glm::length(d);
  if (w == 0.0 || L == 0.0)
    return 0.0;
  const glm::dvec3 n = d / L;  // grad_a C; grad_b C = -n
  const double C = L - rest_length;
  const double closing = glm::dot(n, (p_a - x_prev_a) - (p_b - x_prev_b));  // grad C.(x - x_prev)
  const double delta_lambda =
      (-C - alpha_tilde * lambda - gamma * closing) / ((1.0 + gamma) * w + alpha_tilde);
  p_a += (w_a * delta_lambda) * n;
  p_b -= (w_b * delta_lambda) * n;
  return delta_lambda;
}

// alpha~ = alpha / h^2 and gamma = alpha~ beta~ / h (beta~ = h^2 beta) of a spring set of
// stiffness K over a substep h: alpha = 1/K. A set with K <= 0 has no constraint (infinite
// compliance): `active` is false.
struct xpbd_compliance {
  bool active = false;
  double alpha_tilde = 0.0;  // 1 / (K h^2), 1/kg
  double gamma = 0.0;        // beta / (K h), no unit
};
inline xpbd_compliance compliance_of(double stiffness, double substep, double constraint_damping) {
  if (!(stiffness > 0.0))
    return {};
  return {true, 1.0 / (stiffness * substep * substep), constraint_damping / (stiffness * substep)};
}

// The cloth's forces that are not springs, F_ext, at the given positions (flat, 3k + c): the
// wind K_w <n, u_w> n with the normals of those positions (`normals` is scratch), and the mouse
// drag K_d (q - p_k) on its particle unless fixed. p: the parameters at its N (p.grid_size).
void xpbd_cloth_external_force(const cloth_parameters& p, std::span<const double> position,
                               std::span<const std::uint8_t> is_fixed, std::vector<double>& normals,
                               std::span<double> force);

// Runs the steps; keeps the constraints in visiting order and the scratch arrays between steps.
class xpbd_solver {
 public:
  // One step of dynamics.time_step with dynamics.xpbd's substeps, iterations and damping, on the
  // springs of forces.spring_sets (each set's K), the particles moved by forces.external (at the
  // start of the step; none when it is empty), visited in forces.colour's order, the contacts
  // of forces.contacts at the end of every substep.
  void step(const dynamics_parameters& dynamics, const force_model& forces,
            particle_system& particles);

  // The constraints in visiting order, colour by colour, of the last step.
  std::span<const xpbd_constraint> constraints() const { return constraints_; }

 private:
  // constraints_ from the spring sets, sorted by colour (stable): again only when the springs
  // changed (tearing removes some; a new N).
  void order_constraints(const force_model& forces);

  std::vector<xpbd_constraint> constraints_;
  std::vector<const spring*> ordered_from_;  // each set's first spring when ordered
  std::vector<std::size_t> ordered_sizes_;   // and its size
  std::vector<double> multiplier_;           // lambda of every constraint, this substep
  std::vector<double> previous_position_;    // x_prev, 3k + c
  std::vector<double> external_force_;       // F_ext at the start of the step, 3k + c
  std::vector<double> inverse_mass_;         // w = 1/m, 0 for fixed particles
  std::vector<xpbd_compliance> compliance_;  // per spring set, this step
};

}  // namespace clothlab
