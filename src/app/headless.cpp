#include "app/headless.hpp"

#include <cstdio>
#include <memory>
#include <mutex>
#include <string>

#include "app/data_files.hpp"
#include "app/png_output.hpp"
#include "app/run_control.hpp"
#include "app/run_outputs.hpp"
#include "app/stage_runs.hpp"
#include "app/stop_watchdog.hpp"
#include "app/sweep_command.hpp"
#include "core/cpu_cloth_paths.hpp"
#include "core/i18n.hpp"
#include "gl/cloth_paths.hpp"
#include "gl/gl_context.hpp"

namespace clothlab {
namespace {

// Steps the cloth on --backend's path: the readable step on the CPU path, batches on the others
// (loaded first: a path that cannot take the cloth fails the run).
int step_cloth(const options& o, cpu_cloth_paths& paths, run_outputs& out) {
  if (o.backend == cloth_backend::cpu)
    return run_cpu(o, paths.cloth, out);
  std::string error;
  if (!paths.load(o.backend, error)) {
    if (o.backend == cloth_backend::gpu_compute)
      report(tr("--backend gpu-compute: %s"), error.c_str());
    else
      report("%s", error.c_str());
    return exit_failure;
  }
  return run_batched(o, paths, out);
}

// Once the cloth has stopped: the OBJ (with the normals of the final positions), then the PNG
// drawn from the CPU cloth unless it is drawn already.
int write_cloth_files(const options& o, spring_mesh& cloth, run_outputs& out, bool drawn) {
  cloth.compute_normals();
  std::string error;
  if (!out.write_obj_file(cloth, error)) {
    report("%s", error.c_str());
    return exit_failure;
  }
  return !drawn && !o.png_path.empty() ? write_png(o, out, cloth) : 0;
}

// Runs the chosen stage (and writes its PNG and OBJ); the exit status. The CPU paths run without
// OpenGL (cpu_cloth_paths); only a GPU path and --png use the off-screen context.
int run_stage(const options& o, run_outputs& out) {
  switch (o.stage) {
    case stage_kind::spring: {
      single_spring stage(o.spring);
      if (o.spring_1d_start)
        keep_velocity_along_spring(stage);
      const int status = run_cpu(o, stage, out);
      return status == 0 && !o.png_path.empty() ? write_png(o, out, stage) : status;
    }
    case stage_kind::coupled: {
      coupled_springs stage(o.coupled);
      const int status = run_cpu(o, stage, out);
      return status == 0 && !o.png_path.empty() ? write_png(o, out, stage) : status;
    }
    case stage_kind::cloth:
      if (on_gpu(o.backend)) {
        cloth_paths paths(o.cloth, o.threads);
        int status = step_cloth(o, paths, out);
        // The fragment path draws its PNG from its own textures; the others from the CPU cloth.
        const bool drawn = status == 0 && o.backend == cloth_backend::gpu && !o.png_path.empty();
        if (drawn)
          status = write_png(o, out, paths);
        return status == 0 ? write_cloth_files(o, paths.cloth, out, drawn) : status;
      }
      {
        cpu_cloth_paths paths(o.cloth, o.threads);
        const int status = step_cloth(o, paths, out);
        return status == 0 ? write_cloth_files(o, paths.cloth, out, false) : status;
      }
  }
  return exit_failure;
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
      report(tr("no OpenGL context: %s"), error.c_str());
      std::lock_guard lock(stopping.outputs);
      stopping.taken = true;
      out.close(false, false, error);
      return exit_failure;
    }
    std::printf(tr("clothlab: OpenGL: %s, %s\n"), context->description().c_str(),
                context->origin().c_str());
  }

  int status = run_stage(o, out);
  // The files are put in place with the stop signals held back: a signal that comes from here
  // on is too late to change what is written (docs/limits.md).
  block_stop_signals(true);
  std::lock_guard lock(stopping.outputs);
  stopping.taken = true;
  if (status == 0 && stop_signal != 0) {
    report(tr("interrupted by %s after the last step; the CSV files hold every step, the OBJ and "
              "the PNG are not written"),
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
