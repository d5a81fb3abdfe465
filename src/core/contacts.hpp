// Additions to the lab (docs/model.md, "Interaction and contacts"), applied by the cloth's step
// after the integrator in this order: sphere, ground (question 9, spring_mesh.hpp),
// self-collision, then tearing (spring_mesh::tear_springs). Not questions of the lab: the student
// copy keeps them as they are.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/parameters.hpp"
#include "core/particle_system.hpp"

namespace clothlab {

// The sphere (centre c, radius r, friction rate mu_s), for every particle that is not fixed: if
// |p - c| < r, with n = (p - c) / |p - c| (n = (0, 0, 1) when p = c): p = c + r n, the inward
// normal velocity is removed, v = v - min(v.n, 0) n, and the tangential velocity
// v_t = v - (v.n) n is damped, v_t *= (1 - mu_s dt).
void apply_sphere_contact(const sphere_parameters& sphere, double time_step,
                          particle_system& particles);

// Self-collision of an N x N cloth, thickness d: one Jacobi pass over every pair (i, j) that is
// not within two grid steps of each other (|ku_i - ku_j| > 2 or |kv_i - kv_j| > 2) and closer than
// d (0 < L < d). With u = (p_i - p_j) / L, c = (d - L) / 2 and w = (v_i - v_j).u, the pair adds
// +c u to p_i and -c u to p_j and, if w < 0, -(w/2) u to v_i and +(w/2) u to v_j; a fixed
// particle takes nothing and the other takes both halves. All corrections come from the state
// before the pass, are summed, then applied. The pairs are found with a uniform grid of cells of
// side d (a spatial hash), so that the work stays linear in the number of particles. Keeps its
// scratch arrays between calls: no allocation once the size is known.
// The distance d that self-collision keeps between particles: the thickness asked for
// (cloth_parameters::self_collision_thickness), clamped to the shortest rest length, the
// structural h = side / (N - 1). A larger d would reach grid neighbours that the springs already
// keep apart, and let one cell of the hash below hold a crowd of particles: the work per step
// would grow as (d / h)^3 particles per cell. Both CPU paths call apply() with it.
double self_collision_distance(const cloth_parameters& p);

class self_collision {
 public:
  // Returns the number of pairs closer than d.
  std::size_t apply(int grid_size, double thickness, particle_system& particles);

 private:
  std::vector<std::uint32_t> cell_start_;  // first slot of each hash bucket in sorted_
  std::vector<std::uint32_t> sorted_;      // particle indices, grouped by bucket
  std::vector<std::uint32_t> bucket_;      // the bucket of each particle
  std::vector<std::uint32_t> next_slot_;   // counting sort: next free slot of each bucket
  std::vector<double> position_delta_;     // summed corrections, 3k + c
  std::vector<double> velocity_delta_;
};

}  // namespace clothlab
