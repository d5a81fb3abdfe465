#include "app/headless.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "app/run_control.hpp"
#include "app/run_outputs.hpp"
#include "app/step_error.hpp"
#include "app/sweep_command.hpp"
#include "core/export.hpp"
#include "core/stability.hpp"
#include "gl/cloth_paths.hpp"
#include "gl/gl_context.hpp"
#include "gl/renderer.hpp"
#include "gl/shader.hpp"

namespace clothlab {
namespace {

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

// The class of a stage, as a student reads it in src/core/.
const char* stage_class_name(stage_kind stage) {
  switch (stage) {
    case stage_kind::spring:
      return "single_spring";
    case stage_kind::coupled:
      return "coupled_springs";
    case stage_kind::cloth:
      return "spring_mesh";
  }
  return "?";
}

// The CPU path, the same for the three stages: step 0 is the initial state, checked and
// written like every other, then one step at a time: forces, integration, constraints (inside
// stage.step()), divergence check, output.
template <class Stage>
int run_cpu(const options& o, Stage& stage, run_outputs& out, double time_step) {
  progress_line progress("step", o.steps, clock_stride(stage.particles().size()));
  for (long s = 0; s <= o.steps; ++s) {
    try {
      if (s > 0)
        stage.step();
    } catch (const std::exception& error) {
      // Exit 1 and one line naming the function that threw (found by replaying the run).
      progress.clear();
      Stage fresh(stage.parameters);
      if constexpr (std::is_same_v<Stage, single_spring>) {
        if (o.spring_1d_start)
          keep_velocity_along_spring(fresh);
      }
      const std::string function = part_that_throws(fresh, stage_class_name(o.stage), s);
      report("%s", step_error_line(function, s, time_step, error).c_str());
      return exit_failure;
    }
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

// Runs the chosen stage (and writes its PNG and OBJ); the exit status.
int run_stage(const options& o, run_outputs& out) {
  switch (o.stage) {
    case stage_kind::spring: {
      single_spring stage(o.spring);
      if (o.spring_1d_start)
        keep_velocity_along_spring(stage);
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

// Ends the run within a second of a stop signal whatever is in progress: a step of
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
    shaders("--backend gpu", {"gpu_full_screen.vert", "gpu_step.frag", "gpu_cloth_common.glsl",
                              "gpu_normal.frag", "gpu_tear.frag", "gpu_check.frag"});
  }
  if (o.stage == stage_kind::cloth && o.backend == cloth_backend::gpu_compute) {
    shaders("--backend gpu-compute", {"gpu_compute_step.comp", "gpu_cloth_common.glsl",
                                      "gpu_compute_normal.comp", "gpu_compute_tear.comp"});
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
    // The student copy has no compute path: its step shader would answer questions 6, 9, 12 and
    // 13 (docs/teaching.md).
    if (file.ends_with("gpu_compute_step.comp"))
      error += "; a student copy of the lab has no compute path: it is in the teacher's copy";
    return false;
  }
  return true;
}

}  // namespace

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
    std::printf("clothlab: OpenGL: %s, %s\n", context->description().c_str(),
                context->origin().c_str());
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
