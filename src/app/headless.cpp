#include "headless.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cloth_paths.hpp"
#include "energy.hpp"
#include "export.hpp"
#include "gl_context.hpp"
#include "renderer.hpp"
#include "shader.hpp"
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
// A cell's set-up (its cloth built, its stability limit estimated) counts as this many steps of
// its particles: measured 7 at N = 1024 (docs/limits.md), rounded up.
constexpr long cell_setup_steps = 10;

// SIGINT, SIGTERM, SIGHUP (issues 12 and 22): the handler only records the first signal; the
// step loop sees it after the step in progress, writes nothing more, closes the files (whole
// lines, renamed into place) and exits with 128 + the signal's number (130, 143, 129). A step
// that does not end within stop_grace of the signal is abandoned (stop_watchdog below). A
// second signal changes nothing: timeout(1) sends two, and the first already ends the run.
// (A lock-free atomic: written by the handler, read by the step loop and the watchdog's thread.)
std::atomic<int> stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_stop_signal(int signal_number) {
  int none = 0;
  stop_signal.compare_exchange_strong(none, signal_number);
}

constexpr int stop_signals[] = {SIGINT, SIGTERM, SIGHUP};

// How long after a stop signal the step in progress (or a sweep's cells) may go on before the
// run ends without it, and how long the watchdog then waits for a write in progress: the run
// ends within a second of the signal (docs/limits.md).
constexpr std::chrono::milliseconds stop_grace{300};

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

// One line on standard error, "clothlab: " and the text, its control characters escaped (a
// file name may hold a newline).
[[gnu::format(printf, 1, 2)]] void report(const char* format, ...) {
  char text[2048];
  std::va_list arguments;
  va_start(arguments, format);
  std::vsnprintf(text, sizeof text, format, arguments);
  va_end(arguments);
  std::fprintf(stderr, "clothlab: %s\n", one_line(text).c_str());
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

  enum class recorded { yes, not_finite, interrupted };

  // Writes step `step` when it is one of the steps written. Writes nothing and says why
  // (`reason`) when a number to write is not finite. A stop signal while a large step is being
  // written (1M lines at N = 1024 take a second and a half) takes its lines back out: the
  // CSV then ends with the step before.
  template <class Stage>
  recorded record(long step, double time_step, const Stage& stage, std::string& reason) {
    if (step % o_.csv_every != 0 && step != o_.steps)
      return recorded::yes;
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
          return recorded::not_finite;
        }
      }
    }
    if (states_) {
      constexpr std::size_t rows_between_checks = 16384;
      const std::size_t count = stage.particles().size();
      const long start = std::ftell(states_.get());
      for (std::size_t first = 0; first < count; first += rows_between_checks) {
        if (first > 0 && stop_signal != 0 && start >= 0) {
          std::fflush(states_.get());
          if (::ftruncate(::fileno(states_.get()), start) == 0 &&
              std::fseek(states_.get(), start, SEEK_SET) == 0)
            return recorded::interrupted;
        }
        write_csv_rows(states_.get(), step, t, stage.particles(), first,
                       std::min(count, first + rows_between_checks));
      }
    }
    if (energies_.is_open())
      write_energy_csv_row(energies_, step, t, energy);
    return recorded::yes;
  }

  // The OBJ of the final cloth (its normals computed), into its temporary file; false with a
  // message. It is put in place by close().
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
    return true;
  }

  // Where the PNG writer writes, and the check of what it wrote: stb's writer does not report
  // a failed write, so the file is read back and must be a whole PNG. Put in place by close().
  const std::string& png_write_path() const { return png_file_.write_path(); }
  bool check_png(std::string& error) {
    if (!png_file_is_whole(png_file_.write_path())) {
      error = "--png " + o_.png_path + ": error while writing (the image is incomplete)";
      png_file_.discard();
      return false;
    }
    return true;
  }

  // Closes the CSVs and puts them in place (keep_csvs), then the OBJ and the PNG (keep_images);
  // what is not kept is removed. False with a message naming the file when a write, the flush,
  // the close or the rename failed: that file is removed.
  bool close(bool keep_csvs, bool keep_images, std::string& error) {
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
      errno = 0;
      energies_.close();
      if (!energies_) {
        error = "--energy-csv " + o_.energy_csv_path + ": error while writing" +
                (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string());
        energy_file_.discard();
        ok = false;
      }
    }
    if (!keep_csvs || !ok) {
      csv_file_.discard();
      energy_file_.discard();
    } else {
      if (!o_.csv_path.empty())
        ok = commit(csv_file_, "--csv", error) && ok;
      if (!o_.energy_csv_path.empty())
        ok = commit(energy_file_, "--energy-csv", error) && ok;
    }
    if (!keep_images || !ok) {
      // Unlinked only: the step loop's thread may still read their names (stop_watchdog).
      obj_file_.remove_temporary();
      png_file_.remove_temporary();
    } else {
      if (!o_.obj_path.empty())
        ok = commit(obj_file_, "--obj", error) && ok;
      if (!o_.png_path.empty())
        ok = commit(png_file_, "--png", error) && ok;
    }
    return ok;
  }

  // Removes every temporary file, the streams left open (stop_watchdog, when a write holds
  // them).
  void discard() const {
    for (const output_file* file : {&csv_file_, &energy_file_, &obj_file_, &png_file_})
      file->remove_temporary();
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
  report(
      "the %s simulation diverged at step %ld (t = %g s): %s; dt omega_max = "
      "%.3g (%s)",
      std::string(stage_name(o.stage)).c_str(), step, double(step) * time_step,
      status.reason.c_str(), time_step * estimate.omega_max, estimate.explanation.c_str());
  return true;
}

// What the step loop and the stop watchdog share: the outputs are written by one of them at a
// time (the lock), and the watchdog leaves the run to the loop once the loop has seen the
// signal or is putting the files in place (taken).
struct stop_state {
  std::timed_mutex outputs;
  std::atomic<bool> taken{false};
  std::atomic<long> last_step{-1};  // the last step checked and written
};
stop_state stopping;

// What follows each step s (s = 0: the initial state): the divergence check, the output, the
// progress line and the stop signals. 0 to go on, else the exit status.
template <class Stage>
int after_step(const options& o, const Stage& stage, long step, double time_step, run_outputs& out,
               progress_line& progress) {
  if (diverged(o, stage, step, time_step, progress))
    return exit_diverged;
  std::lock_guard lock(stopping.outputs);
  std::string reason;
  const run_outputs::recorded written = out.record(step, time_step, stage, reason);
  if (written == run_outputs::recorded::not_finite) {
    progress.clear();
    report("the %s simulation diverged at step %ld (t = %g s): %s",
           std::string(stage_name(o.stage)).c_str(), step, double(step) * time_step,
           reason.c_str());
    return exit_diverged;
  }
  if (written == run_outputs::recorded::interrupted) {
    stopping.taken = true;
    progress.clear();
    report(
        "interrupted by %s while step %ld of %ld was being written; the CSV files hold the "
        "steps written before it",
        signal_name(stop_signal), step, o.steps);
    return 128 + stop_signal;
  }
  stopping.last_step = step;
  progress.update(step);
  if (stop_signal != 0) {
    stopping.taken = true;
    progress.clear();
    report(
        "interrupted by %s after step %ld of %ld (t = %g s); the CSV files hold the steps "
        "written up to it",
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
    report("%s", error.c_str());
    return exit_failure;
  }
  draw(scene_renderer, camera::default_for(o.stage));
  if (!save_framebuffer_png(out.png_write_path(), o.width, o.height, error)) {
    report("--png %s: %s", o.png_path.c_str(), error.c_str());
    return exit_failure;
  }
  if (!out.check_png(error)) {
    report("%s", error.c_str());
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

// The cloth's other paths (cpu-parallel, gpu, gpu-compute), loaded in `paths`: the state stays
// on the path and is read back into the CPU cloth only at the steps whose rows are written
// (--csv, --energy-csv: every --csv-every steps) and at the last one. Every step is checked for
// divergence on the path itself (cloth_paths::run), so that exit 3 still names the step. Batches
// end at those steps, and at least every max_batch steps for the progress line and the stop
// signals.
int run_batched(const options& o, cloth_paths& paths, run_outputs& out) {
  constexpr long max_batch = 256;
  const spring_mesh& cloth = paths.cloth;
  const double dt = cloth.parameters.dynamics.time_step;
  const bool rows = !o.csv_path.empty() || !o.energy_csv_path.empty();
  progress_line progress("step", o.steps, clock_stride(cloth.particles().size()));
  if (const int status = after_step(o, cloth, 0, dt, out, progress); status != 0)
    return status;
  for (long s = 0; s < o.steps;) {
    long next = std::min(o.steps, s + max_batch);
    if (rows)
      next = std::min(next, (s / o.csv_every + 1) * o.csv_every);
    const int diverged_after = paths.run(static_cast<int>(next - s));
    if (diverged_after != 0) {
      const long step = s + diverged_after;
      progress.clear();
      report(
          "the cloth simulation diverged at step %ld (t = %g s): a particle's "
          "position or velocity is not finite, or its speed exceeds %g m/s (checked on "
          "the %s path)",
          step, double(step) * dt, paths.speed_bound(), backend_option(paths.backend()));
      return exit_diverged;
    }
    s = next;
    if (s == o.steps || (rows && s % o.csv_every == 0))
      paths.read_state();
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
      report(
          "%s: a cell of dt = %g s would take %.3g steps (%g s / dt), more "
          "than the limit %ld; choose a larger dt or a shorter --sweep-time",
          option.c_str(), dt, settings.simulated_time / dt, settings.simulated_time,
          max_sweep_steps_per_cell);
      return false;
    }
    for (int n : rows) {
      steps += double(per_cell);
      particle_steps += double(per_cell + cell_setup_steps) * particles_of_row(o.stage, n);
    }
  }
  const std::size_t cells = settings.time_steps.size() * rows.size();
  if (steps > max_sweep_steps || particle_steps > max_sweep_particle_steps) {
    report(
        "%s: the sweep's %zu cells would take %.3g steps (%.3g particle steps, each cell's "
        "set-up counted), more than the limit %.3g (%.3g particle steps); choose fewer cells, "
        "a larger dt or a shorter --sweep-time",
        option.c_str(), cells, steps, particle_steps, max_sweep_steps, max_sweep_particle_steps);
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
    report("--sweep %s: cannot write: %s", o.sweep_path.c_str(), error.c_str());
    return exit_failure;
  }
  std::ofstream stream(file.write_path());
  if (!stream) {
    report("--sweep %s: cannot write: %s", o.sweep_path.c_str(), std::strerror(errno));
    return exit_failure;
  }

  // Writes the computed cells and puts the CSV in place; 0 or exit 1 after its message.
  const auto write_cells = [&](const std::vector<sweep_cell>& done) {
    write_sweep_csv(stream, done);
    errno = 0;
    stream.close();
    if (!stream) {
      report("--sweep %s: error while writing: %s", o.sweep_path.c_str(),
             std::strerror(errno != 0 ? errno : EIO));
      return exit_failure;
    }
    if (!file.commit(error)) {
      report("--sweep %s: cannot write: %s", o.sweep_path.c_str(), error.c_str());
      return exit_failure;
    }
    return 0;
  };
  const auto interrupted = [&](const std::vector<sweep_cell>& done) {
    const long computed = std::count_if(done.begin(), done.end(),
                                        [](const sweep_cell& cell) { return cell.computed; });
    if (const int status = write_cells(done); status != 0)
      return status;
    report("interrupted by %s after %ld of %zu sweep cells; %s holds those cells",
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
    progress_line line("sweep cell", total, 1);
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
    report("--sweep %s: %s", o.sweep_path.c_str(), refused.c_str());
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
      cloth_paths paths(o.cloth, o.threads);
      spring_mesh& cloth = paths.cloth;
      std::string error;
      int status = 0;
      if (o.backend == cloth_backend::cpu) {
        status = run_cpu(o, cloth, out, o.cloth.dynamics.time_step);
      } else if (!paths.load(o.backend, error)) {
        if (o.backend == cloth_backend::gpu_compute)
          report("--backend gpu-compute: %s", error.c_str());
        else
          report("%s", error.c_str());
        return exit_failure;
      } else {
        status = run_batched(o, paths, out);
      }
      // The fragment path draws its PNG from its own textures; the others from the CPU cloth.
      const bool drawn = status == 0 && o.backend == cloth_backend::gpu && !o.png_path.empty();
      if (drawn) {
        status = write_png(o, out, [&](renderer& r, const camera& view) {
          const cloth_textures textures = paths.textures();
          r.draw_from_textures(textures.position, textures.normal, cloth, view, render_settings{},
                               o.width, o.height, 0, textures.spring_mask);
        });
      }
      if (status != 0)
        return status;
      cloth.compute_normals();  // of the final positions
      if (!out.write_obj_file(cloth, error)) {
        report("%s", error.c_str());
        return exit_failure;
      }
      return !drawn && !o.png_path.empty() ? write_cpu_png(o, out, cloth) : 0;
    }
  }
  return exit_failure;
}

// Ends the run within a second of a stop signal whatever is in progress (issue 22): a step of
// a large cloth (the implicit scheme at N = 1024 takes a second), a batch of GPU steps, the PNG.
// stop_grace after the signal, if the step loop has not seen it, the watchdog takes the
// outputs (waiting at most stop_grace more for a write in progress to let them go), puts the CSVs
// in place with the steps written so far, removes the OBJ's and the PNG's temporary files, and ends
// the process with 128 + the signal's number. The step in progress is lost.
class stop_watchdog {
 public:
  stop_watchdog(const options& o, run_outputs& out)
      : thread_([this, &o, &out] { watch(o, out); }) {}
  stop_watchdog(const stop_watchdog&) = delete;
  stop_watchdog& operator=(const stop_watchdog&) = delete;
  ~stop_watchdog() {
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }

 private:
  // Sleeps 10 ms, or less when the run ends; true when it has ended.
  bool pause() {
    std::unique_lock lock(mutex_);
    return wake_.wait_for(lock, std::chrono::milliseconds(10), [this] { return done_; });
  }

  void watch(const options& o, run_outputs& out) {
    while (stop_signal == 0 || stopping.taken) {
      if (pause())
        return;
    }
    const auto deadline = std::chrono::steady_clock::now() + stop_grace;
    while (!stopping.taken && std::chrono::steady_clock::now() < deadline) {
      if (pause())
        return;
    }
    if (stopping.taken)
      return;
    std::unique_lock lock(stopping.outputs, std::defer_lock);
    const bool locked = lock.try_lock_for(stop_grace);
    if (locked && stopping.taken)
      return;  // the loop got there first
    const int signal_number = stop_signal;
    const long step = stopping.last_step;
    std::string error;
    if (locked && step < 0) {  // still setting up: as if the run had not started
      out.close(false, false, error);
      report("interrupted by %s before the run's first step was written; nothing written",
             signal_name(signal_number));
    } else if (locked && out.close(true, false, error)) {
      if (step == o.steps) {
        report(
            "interrupted by %s after the last step; the CSV files hold every step, the OBJ "
            "and the PNG are not written",
            signal_name(signal_number));
      } else {
        report(
            "interrupted by %s after step %ld of %ld (the steps after it had not ended %ld ms "
            "later); the CSV files hold the steps written up to it",
            signal_name(signal_number), step, o.steps, long(stop_grace.count()));
      }
    } else {
      if (locked)
        report("%s", error.c_str());
      report(
          "interrupted by %s after step %ld of %ld; the files were being written and none "
          "is kept",
          signal_name(signal_number), step, o.steps);
      out.discard();
    }
    std::fflush(stderr);
    std::_Exit(128 + signal_number);
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

// The data files (shaders, the cloth's texture) that the run will read, each checked before
// step 1 so that a missing one fails at once, before any output is opened (the files loaded by
// gpu_cloth.cpp, gpu_cloth_compute.cpp and renderer.cpp). False with a message naming the
// option that needs it.
bool data_files_present(const options& o, std::string& error) {
  std::vector<std::pair<std::string, std::string>> needed;  // (option, file)
  const auto shaders = [&](const std::string& option, std::initializer_list<const char*> names) {
    for (const char* name : names)
      needed.emplace_back(option, shader_path(name).string());
  };
  if (o.stage == stage_kind::cloth && o.backend == cloth_backend::gpu) {
    shaders("--backend gpu", {"gpu_full_screen.vert", "gpu_step.frag", "gpu_normal.frag",
                              "gpu_tear.frag", "gpu_check.frag"});
  }
  if (o.stage == stage_kind::cloth && o.backend == cloth_backend::gpu_compute) {
    shaders("--backend gpu-compute",
            {"gpu_compute_step.comp", "gpu_compute_normal.comp", "gpu_compute_tear.comp"});
  }
  if (!o.png_path.empty()) {
    const std::string option = "--png " + o.png_path;
    shaders(option,
            {"draw_background.vert", "draw_background.frag", "draw_ground.vert", "draw_ground.frag",
             "draw_flat.vert", "draw_flat.frag", "draw_cloth.vert", "draw_lit.frag",
             "draw_cloth_from_textures.vert", "draw_flat_from_texture.vert", "draw_spheres.vert",
             "draw_blob_shadow.vert", "draw_blob_shadow.frag"});
    needed.emplace_back(option, asset_path("cloth.png").string());
  }
  for (const auto& [option, file] : needed) {
    if (std::ifstream(file).good())
      continue;
    error = option + ": cannot read " + file + ": " + std::strerror(errno) +
            " (the data folder: CLOTHLAB_DATA_DIR, or the one found beside the program)";
    return false;
  }
  return true;
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigset_t handled;
  sigemptyset(&handled);
  for (int signal_number : stop_signals) {
    struct sigaction before {};
    sigaction(signal_number, nullptr, &before);
    if (before.sa_handler == SIG_IGN)
      continue;  // ignored by whoever started clothlab (nohup): it stays ignored
    sigaction(signal_number, &action, nullptr);
    sigaddset(&handled, signal_number);
  }
  // A signal blocked across exec (hand_over in main.cpp) arrives now, at its handler.
  sigprocmask(SIG_UNBLOCK, &handled, nullptr);
}

void block_stop_signals(bool block) {
  sigset_t set;
  sigemptyset(&set);
  for (int signal_number : stop_signals)
    sigaddset(&set, signal_number);
  sigprocmask(block ? SIG_BLOCK : SIG_UNBLOCK, &set, nullptr);
}

int interrupted_before_the_run() {
  if (stop_signal == 0)
    return 0;
  report("interrupted by %s before the run started; nothing written", signal_name(stop_signal));
  return 128 + stop_signal;
}

bool needs_opengl(const options& o) {
  return o.sweep_path.empty() && (o.backend == cloth_backend::gpu ||
                                  o.backend == cloth_backend::gpu_compute || !o.png_path.empty());
}

int run_headless(const options& o) {
  if (const int status = interrupted_before_the_run(); status != 0)
    return status;
  std::string error;
  if (!data_files_present(o, error)) {
    report("%s", error.c_str());
    return exit_failure;
  }
  if (!o.sweep_path.empty())
    return run_sweep_map(o);

  run_outputs out(o);
  if (!out.open(error)) {
    report("%s", error.c_str());
    out.close(false, false, error);
    return exit_failure;
  }
  stop_watchdog watchdog(o, out);

  // One off-screen context serves the GPU path and the PNG.
  std::unique_ptr<gl_context> context;
  if (needs_opengl(o)) {
    context = create_offscreen_context(o.width, o.height, error);
    if (!context) {
      report("no OpenGL context: %s", error.c_str());
      std::lock_guard lock(stopping.outputs);
      stopping.taken = true;
      out.close(false, false, error);
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
  // The files are put in place with the stop signals held back: a signal that comes from here
  // on is too late to change what is written (docs/limits.md).
  block_stop_signals(true);
  std::lock_guard lock(stopping.outputs);
  stopping.taken = true;
  if (status == 0 && stop_signal != 0) {
    report(
        "interrupted by %s after the last step; the CSV files hold every step, the OBJ and "
        "the PNG are not written",
        signal_name(stop_signal));
    status = 128 + stop_signal;
  }
  // The CSVs are kept when the run got somewhere: done, diverged (every step before it),
  // interrupted (every step up to it), or a later failure of the OBJ or the PNG; not when it
  // failed before its first step was written (a GPU path that cannot load).
  const bool started = stopping.last_step >= 0;
  if (!out.close(started || status != exit_failure, status == 0, error)) {
    report("%s", error.c_str());
    if (status == 0 || status == exit_diverged)
      status = exit_failure;
  }
  return status;
}

}  // namespace clothlab
