#include "app/sweep_command.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/run_control.hpp"
#include "core/export.hpp"
#include "core/i18n.hpp"
#include "core/stability.hpp"
#include "core/sweep.hpp"

namespace clothlab {
namespace {

// The work a sweep may ask for (docs/limits.md): past it the command is refused with exit 2.
constexpr long max_sweep_steps_per_cell = 10'000'000;
constexpr double max_sweep_steps = 1e9;            // summed over the cells
constexpr double max_sweep_particle_steps = 1e10;  // steps times moving and fixed particles
// A cell's set-up (its cloth built, its stability limit estimated) counts as this many steps of
// its particles: measured 7 at N = 1024 (docs/limits.md), rounded up.
constexpr long cell_setup_steps = 10;

// n values spaced evenly on a log scale from `from` to `to`.
std::vector<double> log_spaced(double from, double to, int n) {
  std::vector<double> values;
  for (int i = 0; i < n; ++i)
    values.push_back(from * std::pow(to / from, double(i) / (n - 1)));
  return values;
}

// The particles (moving and fixed) of one sweep row: the spring's 2, the chain's n + 1, the
// cloth's N^2.
double particles_of_row(stage_kind stage, int grid_size) {
  switch (stage) {
    case stage_kind::spring:
      return 2;
    case stage_kind::coupled:
      return grid_size + 1.0;
    case stage_kind::cloth:
      return double(grid_size) * grid_size;
  }
  return 1;
}

// The sweep's work against the bounds (docs/limits.md); false after the one line of exit 2.
bool sweep_within_bounds(const options& o, const sweep_settings& settings) {
  const std::string option = o.sweep_time_steps.empty() ? "--sweep-time" : "--sweep-dt";
  std::vector<int> rows;
  if (settings.axis == sweep_axis::grid_size) {
    rows = settings.grid_sizes;
  } else {
    const int base = o.stage == stage_kind::cloth ? o.cloth.grid_size : o.coupled.mass_count;
    rows.assign(settings.stiffnesses.size(), base);
  }
  // An XPBD step visits every spring `iterations` times in each of its substeps: as many
  // steps of the other schemes.
  const dynamics_parameters& d = o.stage == stage_kind::spring    ? o.spring.dynamics
                                 : o.stage == stage_kind::coupled ? o.coupled.dynamics
                                                                  : o.cloth.dynamics;
  const double work_per_step =
      d.integrator == integrator_kind::xpbd ? double(d.xpbd.substeps) * d.xpbd.iterations : 1.0;
  double steps = 0, particle_steps = 0;
  for (double dt : settings.time_steps) {
    const long per_cell = sweep_steps_per_cell(settings.simulated_time, dt);
    if (per_cell > max_sweep_steps_per_cell) {
      report(tr("%s: a cell of dt = %g s would take %.3g steps (%g s / dt), more "
                "than the limit %ld; choose a larger dt or a shorter --sweep-time"),
             option.c_str(), dt, settings.simulated_time / dt, settings.simulated_time,
             max_sweep_steps_per_cell);
      return false;
    }
    for (int n : rows) {
      steps += double(per_cell);
      particle_steps +=
          (double(per_cell) * work_per_step + cell_setup_steps) * particles_of_row(o.stage, n);
    }
  }
  const std::size_t cells = settings.time_steps.size() * rows.size();
  if (steps > max_sweep_steps || particle_steps > max_sweep_particle_steps) {
    report(
        tr("%s: the sweep's %zu cells would take %.3g steps (%.3g particle steps, each cell's "
           "set-up counted), more than the limit %.3g (%.3g particle steps); choose fewer cells, "
           "a larger dt or a shorter --sweep-time"),
        option.c_str(), cells, steps, particle_steps, max_sweep_steps, max_sweep_particle_steps);
    return false;
  }
  return true;
}

}  // namespace

// --sweep: the stability map. Unless given, dt spans the theoretical limit of the base
// parameters (from a fifth of it to twice it) and K spans a quarter to four times the base K.
int run_sweep_map(const options& o) {
  sweep_settings settings;
  settings.stage = o.stage;
  settings.spring = o.spring;
  settings.coupled = o.coupled;
  settings.cloth = o.cloth;
  settings.simulated_time = o.sweep_time;
  double base_dt = 0, base_k = 0, limit = 0;
  switch (o.stage) {
    case stage_kind::spring:
      base_dt = o.spring.dynamics.time_step;
      base_k = o.spring.stiffness;
      limit = estimate_stability(single_spring(o.spring)).time_step_limit;
      break;
    case stage_kind::coupled:
      base_dt = o.coupled.dynamics.time_step;
      base_k = o.coupled.stiffness;
      limit = estimate_stability(coupled_springs(o.coupled)).time_step_limit;
      break;
    case stage_kind::cloth:
      base_dt = o.cloth.dynamics.time_step;
      base_k = o.cloth.structural_stiffness;
      limit = estimate_stability(spring_mesh(o.cloth)).time_step_limit;
      break;
  }
  settings.time_steps = o.sweep_time_steps;
  if (settings.time_steps.empty()) {
    const bool finite_limit = std::isfinite(limit) && limit > 0;
    settings.time_steps = finite_limit ? log_spaced(limit / 5, 2 * limit, 12)
                                       : log_spaced(base_dt / 10, base_dt * 10, 12);
  }
  if (!o.sweep_grid_sizes.empty()) {
    settings.axis = sweep_axis::grid_size;
    settings.grid_sizes = o.sweep_grid_sizes;
  } else {
    settings.axis = sweep_axis::stiffness;
    settings.stiffnesses = o.sweep_stiffnesses;
    if (settings.stiffnesses.empty()) {
      settings.stiffnesses = log_spaced(std::max(base_k, 1e-3) / 4, std::max(base_k, 1e-3) * 4, 9);
    }
  }
  if (!sweep_within_bounds(o, settings))
    return exit_usage;

  output_file file;
  std::string error;
  if (!file.open(o.sweep_path, output_file::writer::stream, error)) {
    report(tr("--sweep %s: cannot write: %s"), o.sweep_path.c_str(), error.c_str());
    return exit_failure;
  }
  std::ofstream stream(file.write_path());
  if (!stream) {
    report(tr("--sweep %s: cannot write: %s"), o.sweep_path.c_str(), std::strerror(errno));
    return exit_failure;
  }

  // Writes the computed cells and puts the CSV in place; 0 or exit 1 after its message.
  const auto write_cells = [&](const std::vector<sweep_cell>& done) {
    write_sweep_csv(stream, done);
    errno = 0;
    stream.close();
    if (!stream) {
      report(tr("--sweep %s: error while writing: %s"), o.sweep_path.c_str(),
             std::strerror(errno != 0 ? errno : EIO));
      return exit_failure;
    }
    if (!file.commit(error)) {
      report(tr("--sweep %s: cannot write: %s"), o.sweep_path.c_str(), error.c_str());
      return exit_failure;
    }
    return 0;
  };
  const auto interrupted = [&](const std::vector<sweep_cell>& done) {
    const long computed = std::count_if(done.begin(), done.end(),
                                        [](const sweep_cell& cell) { return cell.computed; });
    if (const int status = write_cells(done); status != 0)
      return status;
    report(tr("interrupted by %s after %ld of %zu sweep cells; %s holds those cells"),
           signal_name(stop_signal), computed, done.size(), o.sweep_path.c_str());
    return 128 + stop_signal;
  };

  // The cells run on worker threads (background_sweep); this one shows the progress and
  // watches for a stop signal. A cell of a large cloth cannot stop at once (its set-up takes a
  // second at N = 1024, and it checks the cancel flag every 16 steps): stop_grace after the
  // signal the cells done so far are written and the process ends, the cells in progress lost.
  background_sweep sweep;
  std::atomic<bool> started{false};  // the cells made (their limits estimated) and running
  std::string refused;  // what make_sweep_cells refused (the command line refuses it first)
  std::thread starter([&] {
    try {
      sweep.start(settings);
    } catch (const std::invalid_argument& e) {
      refused = e.what();
    }
    started = true;
  });
  {
    const long total = long(settings.time_steps.size()) *
                       long(std::max(settings.stiffnesses.size(), settings.grid_sizes.size()));
    progress_line line(N_("sweep cell"), total, 1);
    std::chrono::steady_clock::time_point deadline{};
    while (!started.load() || sweep.running()) {
      if (stop_signal != 0 && deadline == std::chrono::steady_clock::time_point{})
        deadline = std::chrono::steady_clock::now() + stop_grace;
      if (stop_signal != 0 && std::chrono::steady_clock::now() > deadline) {
        line.clear();
        const int status =
            interrupted(started.load() ? sweep.snapshot() : std::vector<sweep_cell>{});
        std::fflush(stderr);
        std::_Exit(status);  // the workers are still in their cells
      }
      line.update(long(std::lround(sweep.fraction_done() * double(total))));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    starter.join();
  }
  if (!refused.empty()) {
    report(tr("--sweep %s: %s"), o.sweep_path.c_str(), refused.c_str());
    return exit_usage;  // the temporary file is removed with `file`
  }
  const std::vector<sweep_cell> cells = sweep.snapshot();
  if (stop_signal != 0)
    return interrupted(cells);
  if (const int status = write_cells(cells); status != 0)
    return status;

  // The map on standard output: one row per K (or N), one column per dt; '.' stable,
  // 'X' diverged, and '|' where dt first passes the cell's theoretical limit.
  const std::size_t columns = settings.time_steps.size();
  std::printf(tr("stability map (%s, %s): rows %s, columns dt from %.3g to %.3g s\n"),
              std::string(stage_name(o.stage)).c_str(),
              std::string(integrator_name(cells.front().integrator)).c_str(),
              settings.axis == sweep_axis::stiffness ? "K" : "N", settings.time_steps.front(),
              settings.time_steps.back());
  for (std::size_t row = 0; row * columns < cells.size(); ++row) {
    const sweep_cell& first = cells[row * columns];
    if (settings.axis == sweep_axis::stiffness) {
      std::printf("  K %10.4g  ", first.stiffness);
    } else {
      std::printf("  N %10d  ", first.grid_size);
    }
    bool limit_marked = false;
    for (std::size_t c = 0; c < columns; ++c) {
      const sweep_cell& cell = cells[row * columns + c];
      if (!limit_marked && cell.time_step > cell.time_step_limit) {
        std::putchar('|');
        limit_marked = true;
      }
      std::putchar(cell.diverged ? 'X' : '.');
    }
    std::putchar('\n');
  }
  std::printf(
      tr("  ('.' stable, 'X' diverged within %g s, '|' the theoretical limit; cells in %s)\n"),
      o.sweep_time, o.sweep_path.c_str());
  return 0;
}

}  // namespace clothlab
