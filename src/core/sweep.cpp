#include "core/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/coupled_springs.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"
#include "core/stability.hpp"

namespace clothlab {
namespace {

// The parameters of one cell: the base ones with dt and K (or N) replaced.
single_spring_parameters cell_parameters(const single_spring_parameters& base,
                                         const sweep_cell& cell) {
  single_spring_parameters p = base;
  p.dynamics.time_step = cell.time_step;
  p.stiffness = cell.stiffness;
  return p;
}

coupled_springs_parameters cell_parameters(const coupled_springs_parameters& base,
                                           const sweep_cell& cell) {
  coupled_springs_parameters p = base;
  p.dynamics.time_step = cell.time_step;
  p.stiffness = cell.stiffness;
  p.mass_count = cell.grid_size;
  return p;
}

cloth_parameters cell_parameters(const cloth_parameters& base, const sweep_cell& cell) {
  cloth_parameters p = base;
  p.dynamics.time_step = cell.time_step;
  p.grid_size = cell.grid_size;
  // K_struct = K, and K_shear, K_bend in the same ratio to it as in the base parameters.
  const double factor =
      base.structural_stiffness != 0.0 ? cell.stiffness / base.structural_stiffness : 1.0;
  p.structural_stiffness = cell.stiffness;
  p.shear_stiffness = base.shear_stiffness * factor;
  p.bending_stiffness = base.bending_stiffness * factor;
  return p;
}

// Runs a built stage for the cell's number of steps, checking divergence after each.
template <class Stage>
void run_stage(Stage& stage, double simulated_time, sweep_cell& cell,
               const std::atomic<bool>* cancel) {
  const long steps = sweep_steps_per_cell(simulated_time, cell.time_step);
  cell.time_step_limit = estimate_stability(stage).time_step_limit;
  for (long s = 1; s <= steps; ++s) {
    if (cancel != nullptr && s % 16 == 0 && cancel->load())
      return;  // not computed
    stage.step();
    if (divergence_check(stage).diverged) {
      cell.diverged = true;
      cell.step = s;
      cell.computed = true;
      return;
    }
  }
  cell.diverged = false;
  cell.step = steps;
  cell.computed = true;
}

integrator_kind base_integrator(const sweep_settings& settings) {
  switch (settings.stage) {
    case stage_kind::spring:
      return settings.spring.dynamics.integrator;
    case stage_kind::coupled:
      return settings.coupled.dynamics.integrator;
    case stage_kind::cloth:
      return settings.cloth.dynamics.integrator;
  }
  return integrator_kind::semi_implicit;
}

// Runs the cells on worker threads taking the next cell index in turn; done(i) after each.
void run_cells(const sweep_settings& settings, std::vector<sweep_cell>& cells,
               sweep_progress* progress,
               const std::function<void(std::size_t, const sweep_cell&)>& done) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  unsigned workers =
      settings.worker_count > 0 ? static_cast<unsigned>(settings.worker_count) : hardware;
  workers =
      std::min({workers, hardware, static_cast<unsigned>(std::max<std::size_t>(cells.size(), 1))});
  std::atomic<std::size_t> next{0};
  const std::atomic<bool>* cancel = progress != nullptr ? &progress->cancel : nullptr;
  auto work = [&] {
    for (std::size_t i = next++; i < cells.size(); i = next++) {
      if (cancel != nullptr && cancel->load())
        return;
      sweep_cell cell = cells[i];
      run_sweep_cell(settings, cell, cancel);
      if (!cell.computed)
        return;  // cancelled during the cell
      done(i, cell);
      if (progress != nullptr)
        ++progress->cells_done;
    }
  };
  std::vector<std::thread> threads;
  for (unsigned w = 1; w < workers; ++w)
    threads.emplace_back(work);
  work();  // this thread works too
  for (std::thread& t : threads)
    t.join();
}

}  // namespace

long sweep_steps_per_cell(double simulated_time, double time_step) {
  // (the 1e-9 keeps 2 s / 0.01 s at 200 steps where rounding gives 200.00000000000003)
  const double steps = std::ceil(simulated_time / time_step - 1e-9);
  if (!(steps >= 1.0))
    return 1;
  if (!(steps < static_cast<double>(std::numeric_limits<long>::max())))
    return std::numeric_limits<long>::max();  // also for an infinite count (dt = 1e-320)
  return static_cast<long>(steps);
}

std::vector<sweep_cell> make_sweep_cells(const sweep_settings& settings) {
  if (settings.time_steps.empty())
    throw std::invalid_argument("sweep: no time step given");
  for (double dt : settings.time_steps) {
    if (!(dt > 0.0))
      throw std::invalid_argument("sweep: time step dt=" + std::to_string(dt) + " must be > 0");
  }
  const integrator_kind integrator = base_integrator(settings);
  std::vector<sweep_cell> cells;
  auto add_row = [&](double stiffness, int grid_size) {
    for (double dt : settings.time_steps) {
      sweep_cell cell;
      cell.time_step = dt;
      cell.stiffness = stiffness;
      cell.grid_size = grid_size;
      cell.integrator = integrator;
      cells.push_back(cell);
    }
  };
  const int base_grid = settings.stage == stage_kind::cloth     ? settings.cloth.grid_size
                        : settings.stage == stage_kind::coupled ? settings.coupled.mass_count
                                                                : 1;
  const double base_stiffness = settings.stage == stage_kind::cloth
                                    ? settings.cloth.structural_stiffness
                                : settings.stage == stage_kind::coupled ? settings.coupled.stiffness
                                                                        : settings.spring.stiffness;
  if (settings.axis == sweep_axis::stiffness) {
    if (settings.stiffnesses.empty())
      throw std::invalid_argument("sweep: no stiffness K given");
    for (double k : settings.stiffnesses)
      add_row(k, base_grid);
  } else {
    if (settings.stage == stage_kind::spring)
      throw std::invalid_argument("sweep: the single spring has no grid size N to sweep");
    if (settings.grid_sizes.empty())
      throw std::invalid_argument("sweep: no grid size N given");
    for (int n : settings.grid_sizes) {
      const int smallest = settings.stage == stage_kind::cloth ? 2 : 1;
      if (n < smallest)
        throw std::invalid_argument("sweep: grid size N=" + std::to_string(n) +
                                    ": must be at least " + std::to_string(smallest));
      add_row(base_stiffness, n);
    }
  }
  return cells;
}

void run_sweep_cell(const sweep_settings& settings, sweep_cell& cell,
                    const std::atomic<bool>* cancel) {
  switch (settings.stage) {
    case stage_kind::spring: {
      single_spring stage(cell_parameters(settings.spring, cell));
      run_stage(stage, settings.simulated_time, cell, cancel);
      break;
    }
    case stage_kind::coupled: {
      coupled_springs stage(cell_parameters(settings.coupled, cell));
      run_stage(stage, settings.simulated_time, cell, cancel);
      break;
    }
    case stage_kind::cloth: {
      spring_mesh stage(cell_parameters(settings.cloth, cell));
      run_stage(stage, settings.simulated_time, cell, cancel);
      break;
    }
  }
}

std::vector<sweep_cell> run_sweep(const sweep_settings& settings, sweep_progress* progress) {
  std::vector<sweep_cell> cells = make_sweep_cells(settings);
  if (progress != nullptr) {
    progress->cells_done = 0;
    progress->cells_total = static_cast<int>(cells.size());
  }
  std::vector<sweep_cell> results = cells;
  run_cells(settings, cells, progress,
            [&](std::size_t i, const sweep_cell& cell) { results[i] = cell; });
  return results;
}

void write_sweep_csv(std::ostream& out, std::span<const sweep_cell> cells) {
  out << "dt,K,N,integrator,diverged,step\n";
  char line[160];
  for (const sweep_cell& cell : cells) {
    if (!cell.computed)
      continue;
    std::snprintf(line, sizeof line, "%.17g,%.17g,%d,%s,%d,%ld\n", cell.time_step, cell.stiffness,
                  cell.grid_size, std::string(integrator_name(cell.integrator)).c_str(),
                  cell.diverged ? 1 : 0, cell.step);
    out << line;
  }
}

background_sweep::~background_sweep() {
  cancel();
}

void background_sweep::start(const sweep_settings& settings) {
  cancel();
  std::vector<sweep_cell> cells = make_sweep_cells(settings);  // throws before anything starts
  {
    std::lock_guard lock(cells_mutex_);
    cells_ = cells;
  }
  progress_.cancel = false;
  progress_.cells_done = 0;
  progress_.cells_total = static_cast<int>(cells.size());
  running_ = true;
#if defined(CLOTHLAB_NO_THREADS)
  settings_ = settings;
  next_cell_ = 0;
  return;
#endif
  coordinator_ = std::thread([this, settings, cells]() mutable {
    run_cells(settings, cells, &progress_, [this](std::size_t i, const sweep_cell& cell) {
      std::lock_guard lock(cells_mutex_);
      cells_[i] = cell;
    });
    running_ = false;
  });
}

void background_sweep::advance([[maybe_unused]] double seconds) {
#if defined(CLOTHLAB_NO_THREADS)
  const auto start = std::chrono::steady_clock::now();
  while (running_ && !progress_.cancel) {
    if (next_cell_ >= cells_.size()) {
      running_ = false;
      return;
    }
    run_sweep_cell(settings_, cells_[next_cell_++], &progress_.cancel);
    ++progress_.cells_done;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= seconds)
      return;
  }
#endif
}

void background_sweep::cancel() {
  progress_.cancel = true;
  wait();
}

void background_sweep::wait() {
  if (coordinator_.joinable())
    coordinator_.join();
  running_ = false;
}

double background_sweep::fraction_done() const {
  const int total = progress_.cells_total.load();
  return total > 0 ? static_cast<double>(progress_.cells_done.load()) / total : 0.0;
}

std::vector<sweep_cell> background_sweep::snapshot() const {
  std::lock_guard lock(cells_mutex_);
  return cells_;
}

}  // namespace clothlab
