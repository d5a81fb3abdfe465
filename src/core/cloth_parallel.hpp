// The fast CPU path of the cloth (--backend cpu-parallel): the model of spring_mesh
// (docs/model.md), in double precision, on flat arrays of structure-of-arrays layout, threaded
// with OpenMP over the rows of the grid and written so that the compiler vectorises the inner
// loops (sqrt included: this file is compiled with -fno-math-errno; AVX2 or AVX-512 chosen at
// run time where the CPU has them, without contracting a * b + c into an FMA). Not part of the
// lab: the student's readable spring_mesh::compute_force and apply_force are the reference, and
// tests/core/cloth_parallel_test.cpp checks that the two agree bitwise.
//
// One step is one sweep over the rows of the grid, each thread taking a band of rows. For row
// kv, in this order:
//   1. springs: the force of every spring whose lower end (lower index k) is in row kv, once:
//      F = K (L0 - |p_k - p_j|) (p_k - p_j) / |p_k - p_j| on k, and exactly -F on j (|d| is the
//      same for d and -d). Kept in a ring of the last three rows, per thread;
//   2. update: every particle of row kv sums its (up to) 12 springs in the order of
//      compute_force (+F where it is the lower end, -F where it is the upper one), the wind and
//      the drag, then the integrator (semi-implicit or explicit Euler), the sphere and the
//      ground move it. Its new position goes to a second buffer, so that the springs of the
//      rows below, still to come, see the positions at the start of the step (the positions
//      are double-buffered).
// A thread starts two rows above its band, so that it has the springs of those rows without
// waiting for its neighbour (it computes them again: the same numbers). Then, after the sweep,
// self-collision (the readable path's self_collision, on a copy of the state in its layout) and
// tearing.
// With --integrator xpbd the step is XPBD's (xpbd.hpp; cloth_parallel_xpbd.cpp) instead of the
// sweep: the readable solver's arithmetic on its layout, each colour's constraints, which share
// no particle, solved by the threads at once, so that the two paths agree bitwise. The stability
// lab's other integrators are the readable path's alone (supports()).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/contacts.hpp"
#include "core/parameters.hpp"
#include "core/particle_system.hpp"
#include "core/spring_mesh.hpp"
#include "core/xpbd.hpp"

namespace clothlab {

class cloth_parallel {
 public:
  // threads: the number of threads of each pass (0: OpenMP's default, all cores).
  explicit cloth_parallel(int threads = 0) : threads_(threads) {}

  // Whether this path is built. It is not in the student copy (it would answer questions 6, 8,
  // 9 and 13) nor in the browser (no OpenMP): there every function below throws
  // std::invalid_argument(unavailable_reason()) (cloth_parallel_absent.cpp).
  static bool available();
  static const char* unavailable_reason();  // why not, where !available(); "" where it is
  // Everything of p that this path runs; otherwise false with error naming the option.
  static bool supports(const cloth_parameters& p, std::string& error);

  // Takes the current state of a cloth (positions, velocities, pins, rest lengths, the springs
  // already torn, N), so that a run can switch paths at any step. Allocates every array the
  // steps use.
  void load(const spring_mesh& cloth);
  // One step of length p.dynamics.time_step, with p the parameters at the loaded N
  // (spring_mesh::effective_parameters, question 10). Throws std::invalid_argument when
  // !supports(p) or p is not resolved (check_effective).
  void step(const cloth_parameters& p);
  // `count` steps; with speed_bound > 0 (m/s) each step is checked: returns the first step of
  // the batch (1..count) after which a particle is not finite or faster than the bound (the run
  // stops there), 0 when none.
  int run(const cloth_parameters& p, int count, double speed_bound = 0.0);
  // Writes the positions and velocities into the cloth (loaded from it, or of the same N), and
  // removes from it the springs torn on this path, so that what draws or exports the cloth
  // (spring_mesh::triangle_intact) sees them.
  void read_state(spring_mesh& cloth) const;

  int grid_size() const { return n_; }
  int threads() const;  // the threads a pass uses

 private:
  // The six kinds of springs, each indexed by its lower end k (the lower index): to
  // (ku+1, kv), (ku, kv+1), (ku+1, kv+1), (ku-1, kv+1), (ku+2, kv) and (ku, kv+2).
  static constexpr int kinds = 6;
  bool diverged(double speed_bound) const;  // a position or velocity not finite, or too fast
  void apply_self_collision(double thickness);
  void tear_springs(double strain);
  // The mass-spring step: the sweep over the rows above, into the other buffer, then swapped.
  void step_mass_spring(const cloth_parameters& p);
  // XPBD (cloth_parallel_xpbd.cpp): one step, from the state in x_, y_, z_ back into them.
  void step_xpbd(const cloth_parameters& p);
  // xpbd_constraints_ and xpbd_colour_start_ from the springs left (rest_length_ > 0).
  void list_xpbd_constraints();

  int threads_ = 0;
  int n_ = 0;
  // L0 of every spring, m, per kind, at its lower end: the same distances as the readable
  // path's (so that both round alike); 0 where there is no spring (outside the grid) or where it
  // has torn.
  std::array<std::vector<double>, kinds> rest_length_;
  // p, m: two buffers, the state at the start of the step and the one the step writes; each
  // N^2 long plus 2N zeros, so that the spring loop reads its far ends without a bound check.
  std::array<std::vector<double>, 2> x_, y_, z_;
  int current_ = 0;                   // the buffer that holds the state
  std::vector<double> vx_, vy_, vz_;  // v, m/s
  std::vector<double> moving_;        // 1 for a moving particle, 0 for a pinned one
  // Per thread: the spring forces of the last three rows (kind, coordinate, row), each row N
  // long with two zeros on each side (the springs that do not exist), then the normals and the
  // summed spring forces of the row being updated (3 + 3 rows of N).
  std::vector<std::vector<double>> scratch_;
  // Self-collision runs the readable path's code, on its layout (3k + c).
  particle_system contact_state_;
  self_collision self_collision_;
  // XPBD: its constraints colour by colour (colour c from xpbd_colour_start_[c] to [c + 1]),
  // listed again when springs tear; the state in the readable layout while it steps (3k + c), the
  // multipliers, the positions at the start of the substep, F_ext and the wind's normals.
  std::vector<xpbd_constraint> xpbd_constraints_;
  std::vector<std::size_t> xpbd_colour_start_;
  bool xpbd_constraints_listed_ = false;
  particle_system xpbd_state_;
  std::vector<double> xpbd_multiplier_, xpbd_previous_, xpbd_external_, xpbd_normals_;
};

}  // namespace clothlab
