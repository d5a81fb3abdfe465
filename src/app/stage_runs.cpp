#include "app/stage_runs.hpp"

#include <algorithm>
#include <exception>
#include <mutex>
#include <string>
#include <type_traits>

#include "app/run_control.hpp"
#include "app/step_error.hpp"
#include "app/stop_watchdog.hpp"
#include "core/i18n.hpp"
#include "core/stability.hpp"

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
  report(tr("the %s simulation diverged at step %ld (t = %g s): %s; dt omega_max = "
            "%.3g (%s)"),
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
  std::lock_guard lock(stopping.outputs);
  std::string reason;
  const run_outputs::recorded written = out.record(step, time_step, stage, reason);
  if (written == run_outputs::recorded::not_finite) {
    progress.clear();
    report(tr("the %s simulation diverged at step %ld (t = %g s): %s"),
           std::string(stage_name(o.stage)).c_str(), step, double(step) * time_step,
           reason.c_str());
    return exit_diverged;
  }
  if (written == run_outputs::recorded::interrupted) {
    stopping.taken = true;
    progress.clear();
    report(tr("interrupted by %s while step %ld of %ld was being written; the CSV files hold the "
              "steps written before it"),
           signal_name(stop_signal), step, o.steps);
    return 128 + stop_signal;
  }
  stopping.last_step = step;
  progress.update(step);
  if (stop_signal != 0) {
    stopping.taken = true;
    progress.clear();
    report(tr("interrupted by %s after step %ld of %ld (t = %g s); the CSV files hold the steps "
              "written up to it"),
           signal_name(stop_signal), step, o.steps, double(step) * time_step);
    return 128 + stop_signal;
  }
  return 0;
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
int run_steps(const options& o, Stage& stage, run_outputs& out, double time_step) {
  progress_line progress(N_("step"), o.steps, clock_stride(stage.particles().size()));
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
          keep_velocity_along_spring(fresh);  // as the run started
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

}  // namespace

int run_cpu(const options& o, single_spring& stage, run_outputs& out) {
  return run_steps(o, stage, out, o.spring.dynamics.time_step);
}

int run_cpu(const options& o, coupled_springs& stage, run_outputs& out) {
  return run_steps(o, stage, out, o.coupled.dynamics.time_step);
}

int run_cpu(const options& o, spring_mesh& stage, run_outputs& out) {
  return run_steps(o, stage, out, o.cloth.dynamics.time_step);
}

// The cloth's other paths (cpu-parallel, gpu, gpu-compute), loaded in `paths`: the state stays
// on the path and is read back into the CPU cloth only at the steps whose rows are written
// (--csv, --energy-csv: every --csv-every steps) and at the last one. Every step is checked for
// divergence on the path itself (cloth_paths::run), so that exit 3 still names the step. Batches
// end at those steps, and at least every max_batch steps for the progress line and the stop
// signals.
int run_batched(const options& o, cpu_cloth_paths& paths, run_outputs& out) {
  constexpr long max_batch = 256;
  const spring_mesh& cloth = paths.cloth;
  const double dt = cloth.parameters.dynamics.time_step;
  const bool rows = !o.csv_path.empty() || !o.energy_csv_path.empty();
  progress_line progress(N_("step"), o.steps, clock_stride(cloth.particles().size()));
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
      report(tr("the cloth simulation diverged at step %ld (t = %g s): a particle's "
                "position or velocity is not finite, or its speed exceeds %g m/s (checked on "
                "the %s path)"),
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

}  // namespace clothlab
