// Stage 3 (handout section 4, questions 6 to 10 and 13): the N x N cloth, the handout's class
// spring_mesh. Vertex s(ku, kv) has index k = ku + N kv.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/contacts.hpp"
#include "core/force_model.hpp"
#include "core/integrator.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring.hpp"
#include "core/spring_family.hpp"
#include "core/step_phases.hpp"

namespace clothlab {

class spring_mesh {
 public:
  cloth_parameters parameters;  // edited live; grid_size, side_length and pins need load_model

  // The handout's class (section 4.1): the constructor builds the N x N grid (load_model) ...
  explicit spring_mesh(const cloth_parameters& p = {});
  void load_model();  // the flat grid at rest at z = 0, its springs and its pins (question 7)
  // ... compute_force puts in forces[k] the force on every vertex: its springs (question 8)
  // and the wind (question 13), from the current positions ...
  void compute_force();
  // ... and apply_force integrates over one step dt (question 6): explicit Euler in the
  // handout's code order (semi-implicit, the default; integrate_step builds equation 6's order,
  // --integrator explicit, on it). A fixed vertex never moves. Gravity: the acceleration g
  // here, or the force m g in compute_force, as the handout's section 4.1 puts it (the tests
  // accept either).
  void apply_force();
  // The three stiffnesses K (N/m), as the simulation uses them at this N (question 10).
  double structural_stiffness() const { return stiffness(spring_family::structural); }
  double shear_stiffness() const { return stiffness(spring_family::shear); }
  double bending_stiffness() const { return stiffness(spring_family::bending); }
  double spacing() const { return spacing_; }   // h = S / (N - 1), between grid neighbours, m
  int grid_size() const { return grid_size_; }  // N of the last load_model
  static std::size_t index(int ku, int kv, int n) {
    return static_cast<std::size_t>(ku) + static_cast<std::size_t>(n) * kv;
  }
  // Whether the spring from s(ku, kv) to its neighbour s(ku + du, kv + dv) pulls: false when
  // that neighbour is outside the grid (or more than two vertices away), and once the spring
  // has torn (tearing is an addition of clothlab, off by default).
  bool spring_intact(int ku, int kv, int du, int dv) const;

  // One step, the handout's phases in their order (question 3): the forces (compute_force, then
  // the mouse drag), the integration (apply_force, or a scheme of the stability lab), the
  // constraints (the ground of question 9, and the additions). Every caller steps the cloth
  // with it: the window (which wraps each phase in a timer: `phase`), the headless run, the
  // benchmarks. The normals, the last phase of a drawn frame, are the drawing's: computed once
  // after the frame's steps from the final positions (and by compute_force itself, at the
  // start of every step, when the wind needs them). XPBD has no spring forces: its springs are
  // constraints, solved with the wind and the drag in its integration (xpbd.hpp).
  template <class Wrap = run_phase>
  void step(Wrap&& phase = {}) {
    phase(step_phase::forces, [this] {
      if (parameters.dynamics.integrator == integrator_kind::xpbd)
        return;
      compute_force();
      add_drag_force();
    });
    phase(step_phase::integration, [this] { integrate_step(); });
    phase(step_phase::constraints, [this] { apply_constraints(); });
  }

  // ---- Beyond the handout (spring_mesh_step.cpp, spring_mesh_geometry.cpp, tearing.cpp): what
  // the rest of clothlab needs from the cloth. None of it is a question of the lab.

  // The mouse drag (docs/model.md): F_d = K_d (q - p) on the dragged vertex, added to forces.
  void add_drag_force();
  // apply_force for the handout's Euler (semi-implicit); for equation 6 taken literally
  // (explicit), apply_force's speeds with each vertex moved by its speed at the start of the
  // step; the stability lab's Verlet, RK4, implicit Euler and XPBD (integrator.hpp) otherwise.
  void integrate_step();
  // The constraints after the integration, in the order of docs/model.md: the sphere, the
  // ground (question 9), self-collision, tearing (each off unless its parameter says so).
  void apply_constraints();
  // Recomputes normals() from the current positions. compute_force computes them only when
  // the wind needs them: call it before using normals() (exporting the state, for instance).
  void compute_normals();

  const particle_system& particles() const { return particles_; }
  particle_system& particles() { return particles_; }           // to carry a state in (GPU -> CPU)
  std::span<const double> normals() const { return normals_; }  // unit, 3k + c
  std::span<const spring> springs(spring_family family) const {
    return springs_[static_cast<int>(family)];
  }
  // The initial position x0 of every particle, flat (3k + c): the flat cloth at rest, whose
  // distances are the rest lengths (model.md).
  std::span<const double> rest_positions() const { return rest_position_; }
  // The parameters the simulation uses: effective_cloth_parameters(parameters) for the N of the
  // last load_model, i.e. parameters themselves in the per_particle scaling (question 10).
  cloth_parameters effective_parameters() const;
  double stiffness(spring_family family) const;   // K of a family (effective_parameters())
  std::array<spring_set, 3> spring_sets() const;  // the families with their K, in order
  // The integrator's state, e.g. integrator().implicit_solver().last_iterations() (CG).
  const time_integrator& integrator() const { return integrator_; }

  // Tearing (tearing.cpp): removes every spring longer than (1 + strain) L0, for the rest of
  // the run (until load_model); returns how many. apply_constraints calls it when
  // tear_strain > 0.
  std::size_t tear_springs(double strain);
  // Removes, as tearing does, every spring s of every family for which torn(family, s) is
  // true; returns how many. For carrying a torn state in from another path (cloth_parallel,
  // gpu_cloth::read_state).
  std::size_t remove_springs(const std::function<bool(spring_family, const spring&)>& torn);
  std::size_t remove_springs_if(const std::function<bool(const spring&)>& torn);
  // Whether a triangle of the drawn mesh still has its three springs: each cell (ku, kv) is split
  // along its diagonal (ku, kv)-(ku+1, kv+1) into the lower triangle (ku, kv), (ku+1, kv),
  // (ku+1, kv+1) and the upper one (ku, kv), (ku+1, kv+1), (ku, kv+1). 0 <= ku, kv < N - 1.
  bool triangle_intact(int ku, int kv, bool upper) const;

 private:
  int grid_size_ = 0;
  double spacing_ = 0.0;  // h of the last load_model, m
  particle_system particles_;
  std::vector<double> rest_position_;           // x0, the initial positions, 3k + c
  std::vector<double> normals_;                 // n, unit, 3k + c (compute_normals)
  std::array<std::vector<spring>, 3> springs_;  // indexed by spring_family

  // Beyond the handout: the state of tearing, self-collision and the stability lab's schemes.
  // 1 where the spring from vertex k to the vertex at (du, dv) from it (du, dv in [-2, 2]) has
  // torn, at spring_slot(k, du, dv); 0 elsewhere.
  std::vector<std::uint8_t> spring_torn_;
  self_collision self_collision_;  // its scratch arrays, kept between steps
  time_integrator integrator_;     // the scheme's scratch arrays, kept between steps
  particle_system stage_state_;    // the current state, kept aside while forces_at runs
                                   // (and the state at the start of an explicit step)
  std::vector<double> stage_normals_;
  void list_springs();  // springs_ of the grid, each once (load_model)
  // What the rest of clothlab needs to know of the answers (load_model). The pins: every vertex
  // that apply_force never moves is marked in is_fixed (question 7 may pin the corners there or
  // in apply_force, as the handout's section 4.3 suggests), where the GPU path, the drawing,
  // the mouse and the contacts read them. Gravity: whether compute_force adds the force m g
  // (the handout's section 4.1) rather than apply_force the acceleration g, so that the
  // stability lab's schemes, which add g themselves, take it off (forces_at).
  void find_pins_and_gravity();
  bool gravity_in_forces_ = false;
  void set_spring_torn(const spring& s);  // both ends' slots
  static std::size_t spring_slot(std::size_t k, int du, int dv) {
    return 25 * k + static_cast<std::size_t>(5 * (dv + 2) + (du + 2));
  }
  // force <- F(position): compute_force and the drag at other positions than the current ones
  // (the intermediate states of the multi-stage schemes).
  void forces_at(std::span<const double> position, std::span<double> force);
};

// (In the header, and without a copy of the parameters: compute_force asks it for every spring
// of every step.) The structural and shear stiffnesses are the same at every N
// (effective_cloth_parameters).
inline double spring_mesh::stiffness(spring_family family) const {
  switch (family) {
    case spring_family::structural:
      return parameters.structural_stiffness;
    case spring_family::shear:
      return parameters.shear_stiffness;
    case spring_family::bending:
      return effective_bending_stiffness(parameters, grid_size_);
  }
  return 0.0;
}

// (In the header: compute_force asks it for every spring of every step.)
inline bool spring_mesh::spring_intact(int ku, int kv, int du, int dv) const {
  const int n = grid_size_;
  if (ku < 0 || ku >= n || kv < 0 || kv >= n || ku + du < 0 || ku + du >= n || kv + dv < 0 ||
      kv + dv >= n || du < -2 || du > 2 || dv < -2 || dv > 2)
    return false;  // no such spring: one end outside the grid, or not a neighbour
  return spring_torn_[spring_slot(index(ku, kv, n), du, dv)] == 0;
}

// Vertex normals of an N x N grid by central differences (model.md):
// n = normalize(d_u x d_v), d_u = p(min(ku+1,N-1),kv) - p(max(ku-1,0),kv), d_v likewise in kv.
void compute_vertex_normals(int n, std::span<const double> position, std::span<double> normal);

// The ground plane z = z_g, after the integrator (question 9), when parameters.ground_enabled:
// every particle that is not fixed and is below it is put back on it, loses its downward
// velocity and has its tangential velocity damped by (1 - mu_g dt).
void apply_ground_contact(const cloth_parameters& parameters, particle_system& particles);

}  // namespace clothlab
