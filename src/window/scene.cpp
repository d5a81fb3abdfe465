#include "scene.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "gl.hpp"
#include "stability.hpp"

namespace clothlab {

scene::scene(const options& start)
    : spring_stage(start.spring),
      chain_stage(start.coupled),
      cloth_stage(start.cloth),
      view(camera::default_for(start.stage)),
      stage_(start.stage) {}

bool scene::init_renderer(std::string& error) {
  return renderer_.init(error);
}

// ---- Initialisation ---------------------------------------------------------------------

void scene::load_model() {
  spring_stage.load_model();
  chain_stage.load_model();
  cloth_stage.load_model();
  status_ = {};
  unsimulated_seconds_ = 0.0;
  restart_energy_history();
}

void scene::reset() {
  with_current_stage([](auto& stage) { stage.load_model(); });
  current_status() = {};
  unsimulated_seconds_ = 0.0;
  restart_energy_history();
}

void scene::select_stage(stage_kind stage) {
  stage_ = stage;
  view = camera::default_for(stage);
  unsimulated_seconds_ = 0.0;
  restart_energy_history();
}

double scene::current_time_step() const {
  switch (stage_) {
    case stage_kind::spring:
      return spring_stage.parameters.dynamics.time_step;
    case stage_kind::coupled:
      return chain_stage.parameters.dynamics.time_step;
    case stage_kind::cloth:
      break;
  }
  return cloth_stage.parameters.dynamics.time_step;
}

void scene::single_step() {
  control.running = false;
  single_step_requested_ = true;
}

// ---- Every frame: simulation, then display ----------------------------------------------

void scene::draw_scene(double frame_seconds, int left, int width, int height) {
  const int steps = steps_for_this_frame(frame_seconds);
  const double budget = control.mode == time_mode::real_time
                            ? control.max_simulation_seconds_per_frame
                            : std::numeric_limits<double>::infinity();
  simulate(steps, budget);
  if (steps > 0)
    record_energy();
  draw(left, width, height);
}

// The controlled rate of question 1: how many steps of length dt this frame advances.
int scene::steps_for_this_frame(double frame_seconds) {
  run_status& status = current_status();
  status.behind_real_time = false;
  if (status.diverged) {
    single_step_requested_ = false;
    return 0;  // nothing more to simulate until reset()
  }
  if (single_step_requested_) {
    single_step_requested_ = false;
    return 1;
  }
  if (!control.running) {
    unsimulated_seconds_ = 0.0;
    return 0;
  }
  switch (control.mode) {
    case time_mode::steps_per_frame:
      return control.steps_per_frame;
    case time_mode::real_time: {
      // Simulated time follows the wall clock: every step advances dt, so the steps due are the
      // whole number of dt in the time not simulated yet; the remainder waits for the next frame.
      const double dt = current_time_step();
      unsimulated_seconds_ += frame_seconds * control.real_time_speed;
      const double due = std::floor(unsimulated_seconds_ / dt);
      if (due > control.max_steps_per_frame) {
        // Too slow for real time: do what the cap allows and let the rest go, so that the
        // backlog cannot grow from frame to frame (the simulation runs slower than real time).
        status.behind_real_time = true;
        unsimulated_seconds_ = 0.0;
        return control.max_steps_per_frame;
      }
      unsimulated_seconds_ -= due * dt;
      return static_cast<int>(due);
    }
  }
  return 0;
}

// Runs the steps, unless the stage diverges or the wall-clock budget is spent first.
void scene::simulate(int steps, double wall_clock_budget) {
  const clock::time_point start = clock::now();
  int done = 0;
  while (done < steps && !current_status().diverged) {
    step_current_stage();
    ++done;
    const bool over_budget =
        std::chrono::duration<double>(clock::now() - start).count() > wall_clock_budget;
    if (over_budget && done < steps) {
      current_status().behind_real_time = true;
      unsimulated_seconds_ = 0.0;  // the backlog is dropped, as when the step cap is hit
      break;
    }
  }
  measure_rates(done);
}

// One step: force computation, then numerical integration (question 3), then the divergence
// check (question 4): an explosion stops the run instead of drawing NaNs. The check also stops
// a run whose speeds pass far beyond anything a stable run reaches (stability.hpp), so that
// the explosion is caught before the numbers overflow.
void scene::step_current_stage() {
  // Where the cloth's GPU path (questions 11 and 12) is to step instead: for the cloth stage
  // with the GPU backend, gpu_cloth::step(cloth_stage.parameters) replaces the two calls below,
  // and gpu_cloth::read_state(cloth_stage) brings the state back for the check.
  auto [time_step, check] = with_current_stage([](auto& stage) {
    stage.compute_force();  // forces from the positions at the start of the step
    stage.apply_force();    // integrator (and, for the cloth, the ground contact)
    return std::pair{stage.parameters.dynamics.time_step, divergence_check(stage)};
  });
  run_status& status = current_status();
  ++status.step;
  status.time += time_step;
  if (check.diverged) {
    status.diverged = true;
    status.divergence_reason = std::move(check.reason);
    std::printf("clothlab-window: the %s stage diverged at step %ld (t = %g s): %s\n",
                std::string(stage_name(stage_)).c_str(), status.step, status.time,
                status.divergence_reason.c_str());
    std::fflush(stdout);
  }
}

// Display: the renderer reads the state and never changes it.
void scene::draw(int left, int width, int height) {
  const bool offset = left > 0 && framebuffer_.bind(width, height);
  if (!offset) {
    width += left;  // the whole window
    left = 0;
  }
  if (status().diverged) {
    // Nothing finite to draw: an empty scene (the renderer's background); the panel says why.
    glViewport(0, 0, width, height);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  } else {
    switch (stage_) {
      case stage_kind::spring:
        renderer_.draw(spring_stage, view, display, width, height);
        break;
      case stage_kind::coupled:
        renderer_.draw(chain_stage, view, display, width, height);
        break;
      case stage_kind::cloth:
        // Where the GPU path is to be drawn instead: renderer::draw_from_textures with the
        // gpu_cloth's position and normal textures (no copy back to the CPU).
        cloth_stage.compute_normals();  // the normals of the positions being drawn
        renderer_.draw(cloth_stage, view, display, width, height);
        break;
    }
  }
  if (offset)
    framebuffer_.copy_to_window(left);
}

// Question 4: kinetic + gravitational + spring energy. Without damping the exact motion keeps it
// constant; explicit Euler makes it grow, the symplectic schemes keep it oscillating about its
// initial value, implicit Euler makes it decay.
void scene::record_energy() {
  if (status().diverged)
    return;
  constexpr std::size_t frames_kept = 600;
  energy_ = with_current_stage([](const auto& stage) { return compute_energy(stage); });
  if (energy_history_.size() == frames_kept)
    energy_history_.erase(energy_history_.begin());
  energy_history_.push_back(static_cast<float>(energy_.total));
}

void scene::restart_energy_history() {
  energy_history_.clear();
  record_energy();
}

void scene::measure_rates(int steps) {
  steps_in_rate_window_ += steps;
  frames_in_rate_window_ += 1;
  const double seconds = std::chrono::duration<double>(clock::now() - rate_window_start_).count();
  if (seconds >= 0.5) {
    measured_steps_per_second_ = static_cast<double>(steps_in_rate_window_) / seconds;
    measured_frames_per_second_ = static_cast<double>(frames_in_rate_window_) / seconds;
    steps_in_rate_window_ = 0;
    frames_in_rate_window_ = 0;
    rate_window_start_ = clock::now();
  }
}

}  // namespace clothlab
