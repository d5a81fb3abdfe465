// The fast CPU path of the cloth (--backend cpu-parallel, issue 9): the model of spring_mesh
// (docs/model.md), in double precision, on flat arrays of structure-of-arrays layout, threaded
// with OpenMP over the rows of the grid and written so that the compiler vectorises the inner
// loops (sqrt included: this file is compiled with -fno-math-errno). Not part of the lab: the
// student's readable spring_mesh::compute_force and apply_force are the reference, and
// tests/core/cloth_parallel_test.cpp checks that the two agree.
//
// One step, two passes over the particles:
//   1. forces: every particle sums the springs to its (up to) 12 neighbours (each spring is
//      evaluated from both of its ends, as in compute_force), the wind with the normals of the
//      positions at the start of the step, and the drag;
//   2. integration (semi-implicit or explicit Euler), then the sphere and the ground contacts.
// It runs the two Euler integrators, the pins, the wind, the ground, the drag and the sphere;
// the stability lab's other integrators, self-collision and tearing are the readable path's
// alone (supports() says so).
#pragma once

#include <string>
#include <vector>

#include "parameters.hpp"
#include "spring_mesh.hpp"

namespace clothlab {

class cloth_parallel {
 public:
  // threads: the number of threads of each pass (0: OpenMP's default, all cores).
  explicit cloth_parallel(int threads = 0) : threads_(threads) {}

  // Everything of p that this path runs; otherwise false with error naming the option.
  static bool supports(const cloth_parameters& p, std::string& error);

  // Takes the current state of a cloth (positions, velocities, pins, rest lengths, N), so that a
  // run can switch paths at any step.
  void load(const spring_mesh& cloth);
  // One step of length p.dynamics.time_step (the resolution scaling of question 10 applied to
  // the loaded N). Throws std::invalid_argument when !supports(p).
  void step(const cloth_parameters& p);
  // `count` steps; with speed_bound > 0 (m/s) each step is checked: returns the first step of
  // the batch (1..count) after which a particle is not finite or faster than the bound (the run
  // stops there), 0 when none.
  int run(const cloth_parameters& p, int count, double speed_bound = 0.0);
  // Writes the positions and velocities into the cloth (loaded from it, or of the same N).
  void read_state(spring_mesh& cloth) const;

  int grid_size() const { return n_; }
  int threads() const;  // the threads a pass uses

 private:
  bool diverged(double speed_bound) const;  // a position or velocity not finite, or too fast
  void compute_normals();
  void compute_forces(const cloth_parameters& p);
  void integrate(const cloth_parameters& p);

  int threads_ = 0;
  int n_ = 0;
  // L0 of every spring, once, indexed by its lower end k: su_ to (ku+1, kv), sv_ to (ku, kv+1),
  // d1_ to (ku+1, kv+1), d2_ to (ku-1, kv+1), bu_ to (ku+2, kv), bv_ to (ku, kv+2). The same
  // distances as the readable path's, so that both round alike.
  std::vector<double> su_, sv_, d1_, d2_, bu_, bv_;
  double rest_length(std::size_t k, int du, int dv) const;  // any of the 12, by its two ends
  std::vector<double> x_, y_, z_;                           // p, m
  std::vector<double> vx_, vy_, vz_;                        // v, m/s
  std::vector<double> fx_, fy_, fz_;                        // F, N, of the current step
  bool normals_set_ = false;                                // nx_... hold normals (else zeros)
  std::vector<double> nx_, ny_, nz_;                        // unit normals (only with wind)
  std::vector<double> moving_;  // 1 for a moving particle, 0 for a pinned one
};

}  // namespace clothlab
