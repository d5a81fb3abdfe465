// The stability explorer: a map of stable and diverged runs over a grid of time steps
// dt against stiffnesses K (or grid sizes N), for one stage and one integrator, with the
// theoretical limit of every cell (stability.hpp) to draw over it.
#pragma once

#include <atomic>
#include <mutex>
#include <ostream>
#include <span>
#include <thread>
#include <vector>

#include "core/parameters.hpp"

// WebAssembly built without -pthread (the browser build) can start no thread: the map's cells
// are computed between frames instead (background_sweep::advance).
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
#define CLOTHLAB_NO_THREADS 1
#endif

namespace clothlab {

// What varies along the second axis of the map.
enum class sweep_axis {
  stiffness,  // K: the spring and chain's K; the cloth's K_struct, K_shear and K_bend scaled
              // together so that their ratios stay those of the base parameters
  grid_size   // N: the cloth's grid size, or the chain's number of masses
};

struct sweep_settings {
  stage_kind stage = stage_kind::spring;
  // The base parameters of each stage; the chosen stage's (its integrator, damping, ...) are
  // used, with dt and K (or N) replaced cell by cell.
  single_spring_parameters spring;
  coupled_springs_parameters coupled;
  cloth_parameters cloth;
  sweep_axis axis = sweep_axis::stiffness;
  std::vector<double> time_steps;   // dt of each column, s
  std::vector<double> stiffnesses;  // K of each row, N/m (axis stiffness)
  std::vector<int> grid_sizes;      // N of each row (axis grid_size; not for the spring stage)
  double simulated_time = 2.0;      // s: how long each cell runs unless it diverges first
  int worker_count = 0;             // threads: 0 means hardware_concurrency, never more than it
};

struct sweep_cell {
  double time_step = 0.0;  // dt, s
  double stiffness = 0.0;  // K, N/m (the cloth's K_struct)
  int grid_size = 1;       // the cloth's N, the chain's n, 1 for the single spring
  integrator_kind integrator = integrator_kind::semi_implicit;
  bool computed = false;         // false until the cell has run (or when cancelled)
  bool diverged = false;         // divergence_check failed at some step
  long step = 0;                 // the step at which it diverged, else the number of steps run
  double time_step_limit = 0.0;  // s: the theoretical limit for this cell (stability.hpp)
};

// Shared with a running sweep: read progress, ask it to stop.
struct sweep_progress {
  std::atomic<int> cells_done{0};
  std::atomic<int> cells_total{0};
  std::atomic<bool> cancel{false};  // set to stop: the cells not yet run stay not computed
};

// The cells, row by row (each K or N), each row along time_steps, with their limits filled in.
// Throws std::invalid_argument for an empty axis, dt <= 0, or a grid_size axis on the spring.
std::vector<sweep_cell> make_sweep_cells(const sweep_settings& settings);

// Runs every cell of the map on up to worker_count threads and returns the cells. Blocking;
// progress (optional) is updated after every cell and its cancel flag is honoured within
// 16 steps.
std::vector<sweep_cell> run_sweep(const sweep_settings& settings,
                                  sweep_progress* progress = nullptr);

// The steps a cell of time step dt runs: ceil(simulated_time / dt), at least 1. Computed in
// double and saturated at LONG_MAX, so that no dt (1e-300 included) overflows the count; the
// command line refuses sweeps past its bounds before they start (docs/limits.md).
long sweep_steps_per_cell(double simulated_time, double time_step);

// Runs one cell (dt, K or N already set) and fills computed, diverged and step.
void run_sweep_cell(const sweep_settings& settings, sweep_cell& cell,
                    const std::atomic<bool>* cancel = nullptr);

// CSV with the header `dt,K,N,integrator,diverged,step` (diverged is 0 or 1), one line per
// computed cell, numbers as %.17g.
void write_sweep_csv(std::ostream& out, std::span<const sweep_cell> cells);

// A sweep on a background thread, for the window: start, poll, draw snapshot(), cancel.
class background_sweep {
 public:
  background_sweep() = default;
  background_sweep(const background_sweep&) = delete;
  background_sweep& operator=(const background_sweep&) = delete;
  ~background_sweep();  // cancels and waits

  void start(const sweep_settings& settings);  // cancels and waits for a running one first
  void cancel();                               // asks to stop and waits
  // Where there are no threads (the browser build, CLOTHLAB_NO_THREADS): computes the next
  // cells on the calling thread, at least one, until about `seconds` of wall-clock time have
  // passed; the window calls it once a frame. Elsewhere the workers compute the cells and this
  // does nothing.
  void advance(double seconds);
  bool running() const { return running_.load(); }
  double fraction_done() const;              // 0 to 1
  std::vector<sweep_cell> snapshot() const;  // the cells so far (computed ones filled in)

 private:
  void wait();

  sweep_progress progress_;
  std::atomic<bool> running_{false};
  mutable std::mutex cells_mutex_;  // guards cells_ between the workers and snapshot()
  std::vector<sweep_cell> cells_;
  std::thread coordinator_;  // runs the sweep, which starts its own workers
  sweep_settings settings_;  // without threads: the sweep that advance() goes on with
  std::size_t next_cell_ = 0;
};

}  // namespace clothlab
