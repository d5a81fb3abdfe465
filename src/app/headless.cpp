#include "headless.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cloth_parallel.hpp"
#include "energy.hpp"
#include "export.hpp"
#include "gl_context.hpp"
#include "gpu_cloth.hpp"
#include "gpu_cloth_compute.hpp"
#include "renderer.hpp"
#include "stability.hpp"
#include "sweep.hpp"

namespace clothlab {
namespace {

constexpr int exit_failure = 1;
constexpr int exit_usage = 2;
constexpr int exit_diverged = 3;

// The work a sweep may ask for (docs/limits.md): past it the command is refused with exit 2.
constexpr long max_sweep_steps_per_cell = 10'000'000;
constexpr double max_sweep_steps = 1e9;            // summed over the cells
constexpr double max_sweep_particle_steps = 1e10;  // steps times moving and fixed particles

// SIGINT, SIGTERM, SIGHUP (issue 12): the handler only records the signal; the step loop sees
// it after the step in progress, writes nothing more, closes the files (whole lines, renamed
// into place) and exits with 128 + the signal's number (130, 143, 129). A second signal while
// the first is being handled ends the program at once, as without the handler.
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void on_stop_signal(int signal_number) {
  if (stop_signal != 0) {
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
    return;
  }
  stop_signal = signal_number;
}

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP})
    sigaction(signal_number, &action, nullptr);
}

const char* signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
  }
  return "a signal";
}

// A progress line on standard error for long runs, on a terminal only (nothing in a pipe or a
// file, so that scripts and tests see the usual output): at most once a second, rewritten in
// place, cleared at the end.
class progress_line {
 public:
  // The clock is read every `stride` calls to update().
  progress_line(const char* unit, long total, long stride)
      : unit_(unit),
        total_(total),
        stride_(std::max(stride, 1L)),
        enabled_(::isatty(STDERR_FILENO) == 1),
        last_(std::chrono::steady_clock::now()) {}
  progress_line(const progress_line&) = delete;
  progress_line& operator=(const progress_line&) = delete;
  ~progress_line() { clear(); }

  void update(long done) {
    if (!enabled_ || done % stride_ != 0)
      return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::seconds(1))
      return;
    last_ = now;
    const double percent = total_ > 0 ? 100.0 * double(done) / double(total_) : 100.0;
    std::fprintf(stderr, "\rclothlab: %s %ld of %ld (%.1f %%)", unit_, done, total_, percent);
    std::fflush(stderr);
    shown_ = true;
  }

  void clear() {
    if (shown_)
      std::fputs("\r\033[K", stderr);  // back to the start of the line, erased
    shown_ = false;
  }

 private:
  const char* unit_;
  long total_;
  long stride_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_;
};

// How many steps apart the progress line reads the clock: about 65 536 particle updates, often
// enough for once a second whatever the cost of a step, rarely enough to cost nothing.
long clock_stride(std::size_t particles) {
  return std::max(1L, 65536L / static_cast<long>(std::max<std::size_t>(particles, 1)));
}

// Every output file of a run, each written to a temporary file and renamed into place at the
// end (output_file, export.hpp): whole or not at all. Opened before the run, so that a path
// that cannot be written fails at once rather than after a long run.
class run_outputs {
 public:
  explicit run_outputs(const options& o) : o_(o), states_(nullptr, &std::fclose) {}

  // Prepares every file asked for; false with a message naming the option and the file.
  bool open(std::string& error) {
    const struct {
      const char* option;
      const std::string& path;
      output_file& file;
      output_file::writer kind;
    } files[] = {{"--csv", o_.csv_path, csv_file_, output_file::writer::stream},
                 {"--energy-csv", o_.energy_csv_path, energy_file_, output_file::writer::stream},
                 {"--obj", o_.obj_path, obj_file_, output_file::writer::file_name},
                 {"--png", o_.png_path, png_file_, output_file::writer::file_name}};
    for (const auto& f : files) {
      if (!f.path.empty() && !f.file.open(f.path, f.kind, error)) {
        error = std::string(f.option) + " " + f.path + ": cannot write: " + error;
        return false;
      }
    }
    if (!o_.csv_path.empty()) {
      states_.reset(std::fopen(csv_file_.write_path().c_str(), "w"));
      if (!states_) {
        error = "--csv " + o_.csv_path + ": cannot write: " + std::strerror(errno);
        return false;
      }
      write_csv_header(states_.get());
    }
    if (!o_.energy_csv_path.empty()) {
      energies_.open(energy_file_.write_path());
      if (!energies_) {
        error = "--energy-csv " + o_.energy_csv_path + ": cannot write: " + std::strerror(errno);
        return false;
      }
      write_energy_csv_header(energies_);
    }
    return true;
  }

  // Writes step `step` when it is one of the steps written. False, writing nothing, when a
  // number to write is not finite: `reason` says which.
  template <class Stage>
  bool record(long step, double time_step, const Stage& stage, std::string& reason) {
    if (step % o_.csv_every != 0 && step != o_.steps)
      return true;
    const double t = double(step) * time_step;  // t = s dt (model.md)
    energy_breakdown energy;
    if (energies_.is_open()) {
      energy = compute_energy(stage);
      const std::pair<const char*, double> terms[] = {{"kinetic", energy.kinetic},
                                                      {"gravity", energy.gravity},
                                                      {"spring", energy.spring},
                                                      {"total", energy.total}};
      for (const auto& [name, value] : terms) {
        if (!std::isfinite(value)) {
          char text[96];
          std::snprintf(text, sizeof text, "the %s energy %g J is not finite", name, value);
          reason = text;
          return false;
        }
      }
    }
    if (states_)
      write_csv_step(states_.get(), step, t, stage.particles());
    if (energies_.is_open())
      write_energy_csv_row(energies_, step, t, energy);
    return true;
  }

  // The OBJ of the final cloth (its normals computed); false with a message.
  bool write_obj_file(const spring_mesh& cloth, std::string& error) {
    if (o_.obj_path.empty())
      return true;
    const auto intact = [&cloth](int ku, int kv, bool upper) {
      return cloth.triangle_intact(ku, kv, upper);
    };
    if (!write_obj(obj_file_.write_path(), cloth.grid_size(), cloth.particles(), cloth.normals(),
                   intact)) {
      error = "--obj " + o_.obj_path + ": cannot write: " + std::strerror(errno);
      obj_file_.discard();
      return false;
    }
    return commit(obj_file_, "--obj", error);
  }

  // Where the PNG writer writes, and the check of what it wrote: stb's writer does not report
  // a failed write, so the file is read back and must be a whole PNG.
  const std::string& png_write_path() const { return png_file_.write_path(); }
  bool commit_png(std::string& error) {
    if (!png_file_is_whole(png_file_.write_path())) {
      error = "--png " + o_.png_path + ": error while writing (the image is incomplete)";
      png_file_.discard();
      return false;
    }
    return commit(png_file_, "--png", error);
  }

  // Closes the CSVs and renames them into place (keep), or removes them (!keep). False with a
  // message naming the file when a write, the flush or the close failed: the file is removed.
  bool close(bool keep, std::string& error) {
    bool ok = true;
    if (states_) {
      bool written = std::ferror(states_.get()) == 0;
      written = std::fclose(states_.release()) == 0 && written;
      if (!written) {
        error = "--csv " + o_.csv_path + ": error while writing: " + std::strerror(errno);
        csv_file_.discard();
        ok = false;
      }
    }
    if (energies_.is_open()) {
      energies_.close();
      if (!energies_) {
        error = "--energy-csv " + o_.energy_csv_path + ": error while writing";
        energy_file_.discard();
        ok = false;
      }
    }
    if (!keep || !ok) {
      csv_file_.discard();
      energy_file_.discard();
      return ok;
    }
    if (!o_.csv_path.empty())
      ok = commit(csv_file_, "--csv", error) && ok;
    if (!o_.energy_csv_path.empty())
      ok = commit(energy_file_, "--energy-csv", error) && ok;
    return ok;
  }

 private:
  bool commit(output_file& file, const char* option, std::string& error) {
    std::string why;
    if (file.commit(why))
      return true;
    error = std::string(option) + " " + file.target() + ": cannot write: " + why;
    return false;
  }

  const options& o_;
  output_file csv_file_, energy_file_, obj_file_, png_file_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> states_;
  std::ofstream energies_;
};

// After every step, and for the initial state (step 0): a non-finite value or a runaway speed
// stops the run (exit 3), with where the time step stands against the stage's stability limit
// (questions 4 and 10).
template <class Stage>
bool diverged(const options& o, const Stage& stage, long step, double time_step,
              progress_line& progress) {
  const divergence_status status = divergence_check(stage);
  if (!status.diverged)
    return false;
  progress.clear();  // the message starts its own line
  const stability_estimate estimate = estimate_stability(stage);
  std::fprintf(stderr,
               "clothlab: the %s simulation diverged at step %ld (t = %g s): %s; dt omega_max = "
               "%.3g (%s)\n",
               std::string(stage_name(o.stage)).c_str(), step, double(step) * time_step,
               status.reason.c_str(), time_step * estimate.omega_max, estimate.explanation.c_str());
  return true;
}

// What follows each step s (s = 0: the initial state): the divergence check, the output, the
// progress line and the stop signals. 0 to go on, else the exit status.
template <class Stage>
int after_step(const options& o, const Stage& stage, long step, double time_step, run_outputs& out,
               progress_line& progress) {
  if (diverged(o, stage, step, time_step, progress))
    return exit_diverged;
  std::string reason;
  if (!out.record(step, time_step, stage, reason)) {
    progress.clear();
    std::fprintf(stderr, "clothlab: the %s simulation diverged at step %ld (t = %g s): %s\n",
                 std::string(stage_name(o.stage)).c_str(), step, double(step) * time_step,
                 reason.c_str());
    return exit_diverged;
  }
  progress.update(step);
  if (stop_signal != 0) {
    progress.clear();
    std::fprintf(stderr,
                 "clothlab: interrupted by %s after step %ld of %ld (t = %g s); the CSV files "
                 "hold the steps written up to it\n",
                 signal_name(stop_signal), step, o.steps, double(step) * time_step);
    return 128 + stop_signal;
  }
  return 0;
}

// Renders the final state into the off-screen context with the stage's fixed camera and writes
// the PNG. `draw` receives the renderer and the view and draws the state.
template <class Draw>
int write_png(const options& o, run_outputs& out, Draw&& draw) {
  std::string error;
  renderer scene_renderer;
  if (!scene_renderer.init(error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    return exit_failure;
  }
  draw(scene_renderer, camera::default_for(o.stage));
  if (!save_framebuffer_png(out.png_write_path(), o.width, o.height, error)) {
    std::fprintf(stderr, "clothlab: --png %s: %s\n", o.png_path.c_str(), error.c_str());
    return exit_failure;
  }
  if (!out.commit_png(error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    return exit_failure;
  }
  return 0;
}

template <class Stage>
int write_cpu_png(const options& o, run_outputs& out, const Stage& stage) {
  return write_png(o, out, [&](renderer& r, const camera& view) {
    r.draw(stage, view, render_settings{}, o.width, o.height);
  });
}

// The CPU path, the same for the three stages: step 0 is the initial state, checked and
// written like every other, then one step at a time: forces, integration, constraints (inside
// stage.step()), divergence check, output.
template <class Stage>
int run_cpu(const options& o, Stage& stage, run_outputs& out, double time_step) {
  progress_line progress("step", o.steps, clock_stride(stage.particles().size()));
  for (long s = 0; s <= o.steps; ++s) {
    if (s > 0)
      stage.step();
    if (const int status = after_step(o, stage, s, time_step, out, progress); status != 0)
      return status;
  }
  return 0;
}

// The cloth's other paths (cpu-parallel, gpu, gpu-compute): the state stays on the path and is
// read back into the CPU cloth only at the steps whose rows are written (--csv, --energy-csv:
// every --csv-every steps) and at the last one. Every step is checked for divergence on the
// path itself (path.run), so that exit 3 still names the step. Batches end at those steps, and
// at least every max_batch steps for the progress line and the stop signals.
template <class Path>
int run_batched(const options& o, spring_mesh& cloth, Path& path, run_outputs& out,
                const char* path_name) {
  constexpr long max_batch = 256;
  const double dt = cloth.parameters.dynamics.time_step;
  const double speed_bound = divergence_speed_bound(cloth);
  const bool rows = !o.csv_path.empty() || !o.energy_csv_path.empty();
  progress_line progress("step", o.steps, clock_stride(cloth.particles().size()));
  if (const int status = after_step(o, cloth, 0, dt, out, progress); status != 0)
    return status;
  for (long s = 0; s < o.steps;) {
    long next = std::min(o.steps, s + max_batch);
    if (rows)
      next = std::min(next, (s / o.csv_every + 1) * o.csv_every);
    const int diverged_after = path.run(cloth.parameters, static_cast<int>(next - s), speed_bound);
    if (diverged_after != 0) {
      const long step = s + diverged_after;
      progress.clear();
      std::fprintf(stderr,
                   "clothlab: the cloth simulation diverged at step %ld (t = %g s): a particle's "
                   "position or velocity is not finite, or its speed exceeds %g m/s (checked on "
                   "the %s path)\n",
                   step, double(step) * dt, speed_bound, path_name);
      return exit_diverged;
    }
    s = next;
    if (s == o.steps || (rows && s % o.csv_every == 0))
      path.read_state(cloth);
    if (const int status = after_step(o, cloth, s, dt, out, progress); status != 0)
      return status;
  }
  return 0;
}

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
  double steps = 0, particle_steps = 0;
  for (double dt : settings.time_steps) {
    const long per_cell = sweep_steps_per_cell(settings.simulated_time, dt);
    if (per_cell > max_sweep_steps_per_cell) {
      std::fprintf(stderr,
                   "clothlab: %s: a cell of dt = %g s would take %.3g steps (%g s / dt), more "
                   "than the limit %ld; choose a larger dt or a shorter --sweep-time\n",
                   option.c_str(), dt, settings.simulated_time / dt, settings.simulated_time,
                   max_sweep_steps_per_cell);
      return false;
    }
    for (int n : rows) {
      steps += double(per_cell);
      particle_steps += double(per_cell) * particles_of_row(o.stage, n);
    }
  }
  const std::size_t cells = settings.time_steps.size() * rows.size();
  if (steps > max_sweep_steps || particle_steps > max_sweep_particle_steps) {
    std::fprintf(stderr,
                 "clothlab: %s: the sweep's %zu cells would take %.3g steps (%.3g particle "
                 "steps), more than the limit %.3g (%.3g particle steps); choose fewer cells, a "
                 "larger dt or a shorter --sweep-time\n",
                 option.c_str(), cells, steps, particle_steps, max_sweep_steps,
                 max_sweep_particle_steps);
    return false;
  }
  return true;
}

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
    std::fprintf(stderr, "clothlab: --sweep %s: cannot write: %s\n", o.sweep_path.c_str(),
                 error.c_str());
    return exit_failure;
  }
  std::ofstream stream(file.write_path());
  if (!stream) {
    std::fprintf(stderr, "clothlab: --sweep %s: cannot write: %s\n", o.sweep_path.c_str(),
                 std::strerror(errno));
    return exit_failure;
  }

  // The cells run on worker threads; this one shows the progress and passes a stop signal on
  // as the sweep's cancel flag (the cells not yet run are left out of the CSV).
  sweep_progress progress;
  std::vector<sweep_cell> cells;
  std::atomic<bool> finished{false};
  std::thread worker([&] {
    cells = run_sweep(settings, &progress);
    finished = true;
  });
  {
    const long total = long(settings.time_steps.size()) *
                       long(std::max(settings.stiffnesses.size(), settings.grid_sizes.size()));
    progress_line line("sweep cell", total, 1);
    while (!finished.load()) {
      if (stop_signal != 0)
        progress.cancel = true;
      line.update(progress.cells_done.load());
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    worker.join();
  }
  write_sweep_csv(stream, cells);
  stream.close();
  if (!stream) {
    std::fprintf(stderr, "clothlab: --sweep %s: error while writing\n", o.sweep_path.c_str());
    return exit_failure;
  }
  if (!file.commit(error)) {
    std::fprintf(stderr, "clothlab: --sweep %s: cannot write: %s\n", o.sweep_path.c_str(),
                 error.c_str());
    return exit_failure;
  }
  if (stop_signal != 0) {
    std::fprintf(stderr,
                 "clothlab: interrupted by %s after %d of %d sweep cells; %s holds those cells\n",
                 signal_name(stop_signal), progress.cells_done.load(), progress.cells_total.load(),
                 o.sweep_path.c_str());
    return 128 + stop_signal;
  }

  // The map on standard output: one row per K (or N), one column per dt; '.' stable,
  // 'X' diverged, and '|' where dt first passes the cell's theoretical limit.
  const std::size_t columns = settings.time_steps.size();
  std::printf("stability map (%s, %s): rows %s, columns dt from %.3g to %.3g s\n",
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
  std::printf("  ('.' stable, 'X' diverged within %g s, '|' the theoretical limit; cells in %s)\n",
              o.sweep_time, o.sweep_path.c_str());
  return 0;
}

// Runs the chosen stage (and writes its PNG and OBJ); the exit status.
int run_stage(const options& o, run_outputs& out) {
  switch (o.stage) {
    case stage_kind::spring: {
      single_spring stage(o.spring);
      const int status = run_cpu(o, stage, out, o.spring.dynamics.time_step);
      return status == 0 && !o.png_path.empty() ? write_cpu_png(o, out, stage) : status;
    }
    case stage_kind::coupled: {
      coupled_springs stage(o.coupled);
      const int status = run_cpu(o, stage, out, o.coupled.dynamics.time_step);
      return status == 0 && !o.png_path.empty() ? write_cpu_png(o, out, stage) : status;
    }
    case stage_kind::cloth: {
      spring_mesh cloth(o.cloth);
      std::string error;
      int status = 0;
      bool drawn = false;  // the fragment path draws its PNG from its own textures
      switch (o.backend) {
        case backend_kind::cpu:
          status = run_cpu(o, cloth, out, o.cloth.dynamics.time_step);
          break;
        case backend_kind::cpu_parallel: {
          cloth_parallel path(o.threads);
          path.load(cloth);
          status = run_batched(o, cloth, path, out, "cpu-parallel");
          break;
        }
        case backend_kind::gpu: {
          gpu_cloth path;
          if (!path.load(cloth, error)) {
            std::fprintf(stderr, "clothlab: %s\n", error.c_str());
            return exit_failure;
          }
          status = run_batched(o, cloth, path, out, "gpu");
          if (status == 0 && !o.png_path.empty()) {
            drawn = true;
            status = write_png(o, out, [&](renderer& r, const camera& view) {
              r.draw_from_textures(path.position_texture(), path.normal_texture(), cloth, view,
                                   render_settings{}, o.width, o.height, 0,
                                   path.spring_mask_texture());
            });
          }
          break;
        }
        case backend_kind::gpu_compute: {
          gpu_cloth_compute path;
          if (!path.load(cloth, error)) {
            std::fprintf(stderr, "clothlab: --backend gpu-compute: %s\n", error.c_str());
            return exit_failure;
          }
          status = run_batched(o, cloth, path, out, "gpu-compute");
          break;
        }
      }
      if (status != 0)
        return status;
      cloth.compute_normals();  // of the final positions
      if (!out.write_obj_file(cloth, error)) {
        std::fprintf(stderr, "clothlab: %s\n", error.c_str());
        return exit_failure;
      }
      return !drawn && !o.png_path.empty() ? write_cpu_png(o, out, cloth) : 0;
    }
  }
  return exit_failure;
}

}  // namespace

bool needs_opengl(const options& o) {
  return o.sweep_path.empty() && (o.backend == backend_kind::gpu ||
                                  o.backend == backend_kind::gpu_compute || !o.png_path.empty());
}

int run_headless(const options& o) {
  install_stop_handlers();
  if (!o.sweep_path.empty())
    return run_sweep_map(o);

  run_outputs out(o);
  std::string error;
  if (!out.open(error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    out.close(false, error);
    return exit_failure;
  }

  // One off-screen context serves the GPU path and the PNG.
  std::unique_ptr<gl_context> context;
  if (needs_opengl(o)) {
    context = create_offscreen_context(o.width, o.height, error);
    if (!context) {
      std::fprintf(stderr, "clothlab: no OpenGL context: %s\n", error.c_str());
      out.close(false, error);
      return exit_failure;
    }
#if defined(CLOTHLAB_GL_EGL)
    const char* through = "EGL";
#else
    const char* through = "OSMesa";
#endif
    std::printf("clothlab: OpenGL: %s, through %s\n", context->description().c_str(), through);
  }

  int status = run_stage(o, out);
  // The CSVs are kept when the run got somewhere: done, diverged (every step before it),
  // interrupted (every step up to it), or a later failure of the OBJ or the PNG.
  if (!out.close(true, error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    if (status == 0 || status == exit_diverged)
      status = exit_failure;
  }
  if (status == 0 && stop_signal != 0) {
    std::fprintf(stderr, "clothlab: interrupted by %s after the last step; the files are whole\n",
                 signal_name(stop_signal));
    status = 128 + stop_signal;
  }
  return status;
}

}  // namespace clothlab
