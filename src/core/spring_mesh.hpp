// Stage 3 (handout section 4, questions 6 to 10 and 13): the N x N cloth.
// Particle (ku, kv) has index k = ku + N kv; its coordinate c is at 3k + c of the flat arrays.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "core/contacts.hpp"
#include "core/integrator.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring.hpp"

namespace clothlab {

// The three kinds of springs of the handout's figure 6, each with its own stiffness.
enum class spring_family { structural, shear, bending };
inline constexpr std::array<spring_family, 3> all_spring_families = {
    spring_family::structural, spring_family::shear, spring_family::bending};

class spring_mesh {
 public:
  cloth_parameters parameters;  // edited live; grid_size, side_length and pins need load_model

  explicit spring_mesh(const cloth_parameters& p = {});

  // Initialisation: the flat N x N grid at rest at z = 0, its springs and its pins.
  void load_model();
  // Force computation (question 8): for every vertex s(ku, kv), the forces of its structural,
  // shear and bending springs and the wind (question 13), from the current positions, into
  // particles().force. Gravity is not a force here: apply_force adds g to the acceleration.
  void compute_force();
  // The same forces at any positions (flat, 3k + c), for the integrators with several stages;
  // the wind uses the normals of those positions.
  void compute_force(std::span<const double> position, std::span<double> force);
  // Numerical integration (question 6): the handout's explicit Euler, in its code's order
  // (semi-implicit, the default) or its equation 6's (explicit); the stability lab's schemes
  // otherwise. Fixed vertices never move.
  void apply_force();
  // The constraints after the integration, in the order of docs/model.md: the sphere, the
  // ground (question 9), self-collision, tearing (each off unless its parameter says so).
  void apply_constraints();
  // One step, as the lab names its parts: forces, integration, constraints.
  void step() {
    compute_force();
    apply_force();
    apply_constraints();
  }

  // Recomputes normals() from the current positions. A step computes them only when the wind
  // needs them: call it before using normals() (exporting the state, for instance).
  void compute_normals();

  int grid_size() const { return grid_size_; }  // N of the last load_model
  static std::size_t index(int ku, int kv, int n) {
    return static_cast<std::size_t>(ku) + static_cast<std::size_t>(n) * kv;
  }

  const particle_system& particles() const { return particles_; }
  particle_system& particles() { return particles_; }  // to carry a state in (GPU -> CPU)
  std::span<const double> normals() const { return normals_; }
  std::span<const spring> springs(spring_family family) const {
    return springs_[static_cast<int>(family)];
  }
  // Tearing (an addition): removes every spring longer than (1 + strain) L0, for the rest of the
  // run (until load_model); returns how many. apply_force calls it when tear_strain > 0.
  std::size_t tear_springs(double strain);
  // Removes, for the rest of the run (until load_model), every spring s of every family for
  // which torn(family, s) is true; returns how many. tear_springs uses it, and so does
  // cloth_parallel::read_state to hand back the springs torn on the cpu-parallel path.
  template <class Predicate>
  std::size_t remove_springs(Predicate torn) {
    std::size_t removed = 0;
    for (spring_family family : all_spring_families) {
      std::vector<spring>& list = springs_[static_cast<int>(family)];
      const auto first_torn = std::stable_partition(
          list.begin(), list.end(), [&](const spring& s) { return !torn(family, s); });
      for (auto it = first_torn; it != list.end(); ++it)
        set_spring_torn(*it);
      removed += static_cast<std::size_t>(list.end() - first_torn);
      list.erase(first_torn, list.end());
    }
    return removed;
  }
  // Removes, as tearing does, every spring s for which torn(s) is true; returns how many. For
  // carrying a torn state in from another path (the GPU's, gpu_cloth::read_state).
  template <typename Predicate>
  std::size_t remove_springs_if(Predicate torn);
  // Whether a triangle of the drawn mesh still has its three springs: each cell (ku, kv) is split
  // along its diagonal (ku, kv)-(ku+1, kv+1) into the lower triangle (ku, kv), (ku+1, kv),
  // (ku+1, kv+1) and the upper one (ku, kv), (ku+1, kv+1), (ku, kv+1). 0 <= ku, kv < N - 1.
  bool triangle_intact(int ku, int kv, bool upper) const;
  // Whether the spring from s(ku, kv) to s(ku + du, kv + dv) has not torn (tearing is an
  // addition of clothlab, off by default: then every spring is intact). Both vertices must be
  // inside the grid and |du|, |dv| <= 2: otherwise it throws std::out_of_range, naming them
  // (which springs exist at the border is question 8's to decide).
  bool spring_intact(int ku, int kv, int du, int dv) const {
    const int n = grid_size_;
    if (ku < 0 || ku >= n || kv < 0 || kv >= n || ku + du < 0 || ku + du >= n || kv + dv < 0 ||
        kv + dv >= n || du < -2 || du > 2 || dv < -2 || dv > 2)
      throw_not_a_neighbour(ku, kv, du, dv);
    return spring_torn_[spring_slot(index(ku, kv, n), du, dv)] == 0;
  }
  // The initial position x0 of every particle, flat (3k + c): the flat cloth at rest, whose
  // distances are the rest lengths (model.md).
  std::span<const double> rest_positions() const { return rest_position_; }
  // The parameters the simulation uses: effective_cloth_parameters(parameters) for the N of the
  // last load_model, i.e. parameters themselves in the per_particle scaling (question 10).
  cloth_parameters effective_parameters() const;
  // K of a family as the simulation uses it (effective_parameters()).
  double stiffness(spring_family family) const;
  // The three families with their stiffness, in spring_family order.
  std::array<spring_set, 3> spring_sets() const;
  // The integrator's state, e.g. integrator().implicit_solver().last_iterations() (CG).
  const time_integrator& integrator() const { return integrator_; }

 private:
  int grid_size_ = 0;
  double spacing_ = 0.0;  // h = S / (N - 1) of the last load_model, m
  particle_system particles_;
  std::vector<double> normals_;                 // n, unit, 3k + c
  std::array<std::vector<spring>, 3> springs_;  // indexed by spring_family
  std::vector<double> rest_position_;           // x0, the initial positions, 3k + c
  // 1 where the spring from vertex k to the vertex at (du, dv) from it (du, dv in [-2, 2]) has
  // torn, at spring_slot(k, du, dv); 0 elsewhere, where there is no such spring too (which
  // springs exist is question 8's to decide, and the spring lists').
  std::vector<std::uint8_t> spring_torn_;
  self_collision self_collision_;         // its scratch arrays, kept between steps
  void set_spring_torn(const spring& s);  // both ends' slots
  // spring_intact's std::out_of_range for a neighbour outside the grid (kept out of line).
  [[noreturn, gnu::cold]] void throw_not_a_neighbour(int ku, int kv, int du, int dv) const;
  static std::size_t spring_slot(std::size_t k, int du, int dv) {
    return 25 * k + static_cast<std::size_t>(5 * (dv + 2) + (du + 2));
  }
  std::vector<double> stage_normals_;  // normals of a scheme's intermediate state (wind)
  time_integrator integrator_;         // the scheme's scratch arrays, kept between steps

  // The force model of the current parameters (the wind from the normals of the positions
  // it is evaluated at); sets must outlive it.
  force_model forces(const std::array<spring_set, 3>& sets);
};

template <typename Predicate>
std::size_t spring_mesh::remove_springs_if(Predicate torn) {
  return remove_springs([&](spring_family, const spring& s) { return torn(s); });
}

// Vertex normals of an N x N grid by central differences (model.md):
// n = normalize(d_u x d_v), d_u = p(min(ku+1,N-1),kv) - p(max(ku-1,0),kv), d_v likewise in kv.
void compute_vertex_normals(int n, std::span<const double> position, std::span<double> normal);

// The ground plane z = z_g, after the integrator: every particle that is not fixed and is below
// it is put back on it, loses its downward velocity and has its tangential velocity damped by
// (1 - mu_g dt).
void apply_ground_contact(double ground_height, double ground_friction, double time_step,
                          particle_system& particles);

}  // namespace clothlab
