// The parameters of clothlab's three stages, one struct per stage (docs/model.md).
// Every field carries its unit and its default. The window edits these structs and nothing
// else; the command line fills them once.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <optional>
#include <string_view>

namespace clothlab {

// The three stages of the lab.
enum class stage_kind { spring, coupled, cloth };
std::string_view stage_name(stage_kind stage);  // "spring", "coupled", "cloth"

// How one step of length dt advances (model.md, "Integrators"; integrator.hpp for the added
// ones). The first two multiply the velocity by (1 - mu dt); the others treat the damping as the
// force -mu m v, which is the same to first order in dt.
enum class integrator_kind {
  semi_implicit,    // v <- (1 - mu dt) v + dt a(p), then p <- p + dt v (the handout's code order)
  explicit_euler,   // p <- p + dt v and v <- (1 - mu dt) v + dt a(p), both from the old state
  velocity_verlet,  // half kick, drift, half kick: second order, symplectic without damping
  runge_kutta_4,    // classical fourth-order Runge-Kutta on (p, v)
  implicit_euler,   // backward Euler linearised once per step (Baraff and Witkin 1998)
  xpbd  // each spring a distance constraint of compliance 1/K (Macklin et al. 2016): xpbd.hpp
};
inline constexpr std::array<integrator_kind, 6> all_integrators = {
    integrator_kind::semi_implicit,   integrator_kind::explicit_euler,
    integrator_kind::velocity_verlet, integrator_kind::runge_kutta_4,
    integrator_kind::implicit_euler,  integrator_kind::xpbd};

// "semi-implicit", "explicit", "verlet", "rk4", "implicit", "xpbd" (the command line's names).
std::string_view integrator_name(integrator_kind kind);
// The inverse of integrator_name; nullopt for an unknown name.
std::optional<integrator_kind> parse_integrator(std::string_view name);

// XPBD's own numbers (docs/model.md, "XPBD"): a step of dt is `substeps` substeps of
// h = dt / substeps, each `iterations` Gauss-Seidel sweeps over the springs' constraints.
struct xpbd_parameters {
  int substeps = 10;                // per step: h = dt / substeps
  int iterations = 1;               // sweeps over every constraint per substep
  double constraint_damping = 0.0;  // beta, N s/m: the paper's damping along each spring
};

// What every stage shares: time step, damping, mass, gravity and the integrator.
struct dynamics_parameters {
  double time_step = 0.002;  // dt, s
  double damping = 0.0;      // mu, 1/s: the velocity is multiplied by (1 - mu dt) every step
  double mass = 1.0;         // m, kg, of every moving particle
  double gravity = 9.8;      // g0, m/s^2: gravity is (0, 0, -g0)
  integrator_kind integrator = integrator_kind::semi_implicit;
  xpbd_parameters xpbd = {};  // read by the xpbd integrator only
};

// K_d, N/m: the default stiffness of the mouse drag's spring, on every stage.
inline constexpr double default_drag_stiffness = 1000.0;

// The mouse drag on a mass of stages 1 and 2 (an addition, docs/model.md "Drag"): particle
// `mass` is pulled towards the target q by a spring of stiffness K_d and rest length 0,
// F_d = K_d (q - p). The fixed p0 (particle 0) cannot be dragged.
struct mass_drag_parameters {
  bool enabled = false;
  int mass = 1;                               // the dragged particle: 1..n (0 is the fixed p0)
  glm::dvec3 target = {0, 0, 0};              // q, m
  double stiffness = default_drag_stiffness;  // K_d, N/m
};

// Stage 1: one spring from the fixed p0 = (0.1, 0, 1) to p1 (handout section 3).
struct single_spring_parameters {
  dynamics_parameters dynamics{.time_step = 0.01, .damping = 0.2};
  double stiffness = 20.0;    // K, N/m
  mass_drag_parameters drag;  // the mouse drag on p1 (addition)
};

// Stage 2: a chain of masses hanging from p0 (question 5).
struct coupled_springs_parameters {
  dynamics_parameters dynamics{.time_step = 0.01, .damping = 0.2};
  double stiffness = 20.0;    // K, N/m, of every spring of the chain
  int mass_count = 2;         // n, moving masses (1 gives the single spring)
  mass_drag_parameters drag;  // the mouse drag on one mass of the chain (addition)
};

enum class pin_mode {
  corners,  // particles (0, 0) and (N-1, 0) never move (question 7)
  none      // free fall
};

// Question 10: what stays fixed when the grid size N changes.
enum class resolution_scaling {
  per_particle,           // the handout's: m and the three K are per particle and per spring
  resolution_independent  // the cloth of the reference grid, resolved with N x N particles
};
// "per-particle", "resolution-independent"
std::string_view resolution_scaling_name(resolution_scaling scaling);
std::optional<resolution_scaling> parse_resolution_scaling(std::string_view name);

// Additions to the lab (docs/model.md, "Interaction and contacts"), each off by default.

// The mouse drag: particle (ku, kv) is pulled towards the target q by a spring of stiffness K_d
// and rest length 0, F_d = K_d (q - p). A pinned particle cannot be dragged.
struct drag_parameters {
  bool enabled = false;
  int ku = 0;  // the dragged particle (ku, kv)
  int kv = 0;
  glm::dvec3 target = {0, 0, 0};              // q, m
  double stiffness = default_drag_stiffness;  // K_d, N/m
};

// A sphere the cloth collides with (after the integrator, before the ground).
struct sphere_parameters {
  bool enabled = false;
  glm::dvec3 centre = {0.0, 0.0, -0.6};  // c, m
  double radius = 0.3;                   // r, m
  double friction = 5.0;  // mu_s, 1/s: tangential velocity *= (1 - mu_s dt) in contact
};

// Stage 3: the N x N cloth (handout section 4).
struct cloth_parameters {
  dynamics_parameters dynamics{.time_step = 0.002, .damping = 0.5};
  int grid_size = 20;                    // N: N x N particles (rebuilds the cloth)
  double side_length = 1.0;              // S, m: side of the initial flat square (rebuilds)
  double structural_stiffness = 5000.0;  // K_struct, N/m: (ku,kv)-(ku+1,kv) and (ku,kv)-(ku,kv+1)
  double shear_stiffness = 2000.0;       // K_shear, N/m: the two diagonals of each cell
  double bending_stiffness = 500.0;      // K_bend, N/m: (ku,kv)-(ku+2,kv) and (ku,kv)-(ku,kv+2)
  pin_mode pins = pin_mode::corners;     // which particles never move (rebuilds)
  double wind_strength = 0.0;            // K_w, N: F_w = K_w <n, u_w> n
  glm::dvec3 wind_direction = {0.0, 1.0, 0.0};  // u_w, normalised before use; must not be zero
  bool ground_enabled = true;                   // the plane z = ground_height (question 9)
  double ground_height = -1.0;                  // z_g, m
  double ground_friction = 2.0;  // mu_g, 1/s: tangential velocity *= (1 - mu_g dt) in contact
  // Question 10. per_particle: mass and stiffnesses above are used as they are, whatever N.
  // resolution_independent: they describe the cloth as resolved by the reference grid, and
  // effective_cloth_parameters() derives the per-particle mass and per-spring stiffnesses of
  // the current N from them (same total mass, same stretching and bending response).
  resolution_scaling scaling = resolution_scaling::per_particle;
  int reference_grid_size = 20;  // N_ref: the grid whose particles have mass m and springs K
  drag_parameters drag;          // the mouse drag (addition)
  sphere_parameters sphere;      // a sphere to drape the cloth over (addition)
  double tear_strain = 0.0;      // epsilon: a spring longer than (1 + epsilon) L0 tears; 0: never
  double self_collision_thickness = 0.0;  // d, m: non-neighbours are kept d apart; 0: off
};

// The parameters that the simulation of an N x N cloth really uses: the identity in
// per_particle mode; in resolution_independent mode (h = S / (N - 1), h_ref = S / (N_ref - 1)):
//   mass per particle     m_N        = m N_ref^2 / N^2          (total mass M = m N_ref^2 fixed)
//   structural and shear  K_N        = K                         (2D stretching is scale-free)
//   bending               K_bend,N   = K_bend (h_ref / h)^4      (bending energy ~ K_bend h^4)
// Derivation in parameters.cpp. The result has scaling = per_particle (it is resolved).
cloth_parameters effective_cloth_parameters(const cloth_parameters& parameters);
// The fast paths (cloth_parallel, gpu_cloth, gpu_cloth_compute) take the parameters at their N,
// effective_cloth_parameters' result, from whoever chose the path: throws std::invalid_argument
// naming `who` for parameters still to be resolved (resolution_independent).
void check_effective(const cloth_parameters& parameters, const char* who);
// The bending stiffness of that result for an N x N grid (N = grid_size), alone: what a step
// asks for many times, without a copy of the parameters.
double effective_bending_stiffness(const cloth_parameters& parameters, int grid_size);

}  // namespace clothlab
