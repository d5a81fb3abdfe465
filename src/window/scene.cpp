#include "window/scene.hpp"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "core/i18n.hpp"
#include "core/stability.hpp"
#include "core/wall_clock.hpp"
#include "gl/gl.hpp"
#include "window/framing.hpp"  // chain_view

namespace clothlab {

// The stage as the window's messages name it ("the cloth stage diverged at step ...").
const char* stage_in_words(stage_kind stage) {
  switch (stage) {
    case stage_kind::spring:
      return tr("the spring stage");
    case stage_kind::coupled:
      return tr("the coupled stage");
    case stage_kind::cloth:
      break;
  }
  return tr("the cloth stage");
}

namespace {

// Real time on the GPU path: the GPU runs the submitted steps later than the CPU submits them,
// so the frame's wall-clock budget is checked after a glFinish, once every this many steps
// (a finish after every step would measure the synchronisation more than the steps).
constexpr int gpu_steps_between_budget_checks = 8;
// In the browser, where threads are not, the stability map computes its cells between frames:
// this long a frame (at least a cell), so that the page stays responsive while it fills in.
constexpr double map_seconds_per_frame = 0.012;

}  // namespace

scene::scene(stage_kind stage, const single_spring_parameters& spring,
             const coupled_springs_parameters& chain, const cloth_parameters& cloth)
    : paths_(cloth),
      spring_stage(spring),
      chain_stage(chain),
      cloth_stage(paths_.cloth),
      view(camera::default_for(stage)),
      stage_(stage) {}

scene::~scene() = default;

bool scene::init_renderer(std::string& error) {
  if (const GLubyte* name = glGetString(GL_RENDERER); name != nullptr)
    renderer_name_ = reinterpret_cast<const char*>(name);
  paths_.check_compute_offered();
  return renderer_.init(error);
}

// ---- Initialisation ---------------------------------------------------------------------

// Stage 1, with the 1D start of question 2 when asked.
void scene::load_spring_stage() {
  spring_stage.load_model();
  if (spring_one_dimensional_start)
    keep_velocity_along_spring(spring_stage);
}

void scene::load_model() {
  // Timed stage by stage for the frame anatomy (questions 1 and 3).
  clock::time_point start = clock::now();
  load_spring_stage();
  load_seconds_[static_cast<int>(stage_kind::spring)] = seconds_since(start);
  start = clock::now();
  chain_stage.load_model();
  load_seconds_[static_cast<int>(stage_kind::coupled)] = seconds_since(start);
  start = clock::now();
  cloth_stage.load_model();
  load_seconds_[static_cast<int>(stage_kind::cloth)] = seconds_since(start);
  status_ = {};
  view = framed_view();
  start_hold_seconds_left_ = control.start_hold_seconds;
  start_hold_frames_left_ = control.start_hold_frames;
  reload_gpu_cloth();
  unsimulated_seconds_ = 0.0;
  restart_energy_history();
}

void scene::reset() {
  const clock::time_point start = clock::now();
  if (stage_ == stage_kind::spring)
    load_spring_stage();
  else
    with_current_stage([](auto& stage) { stage.load_model(); });
  load_seconds_[static_cast<int>(stage_)] = seconds_since(start);
  if (stage_ == stage_kind::coupled)
    view = framed_view();  // the chain may have another length
  current_status() = {};
  if (stage_ == stage_kind::cloth)
    reload_gpu_cloth();  // the reset keeps the path
  unsimulated_seconds_ = 0.0;
  restart_energy_history();
}

camera scene::framed_view() const {
  if (stage_ != stage_kind::coupled)
    return camera::default_for(stage_);
  return chain_view(chain_stage);
}

void scene::select_stage(stage_kind stage) {
  release_grab();  // a drag ends with its stage's
  stage_ = stage;
  view = framed_view();
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
  // The frame anatomy of this frame, filled in as its phases run.
  anatomy_ = {.stage = stage_,
              .on_gpu = cloth_on_gpu(),
              .gpu_compute = cloth_on_gpu() && backend() == cloth_backend::gpu_compute,
              .load_seconds = load_seconds_[static_cast<int>(stage_)],
              .frame = anatomy_.frame + 1};
  state_fresh_ = false;
  stability_explorer.advance(map_seconds_per_frame);  // the browser's map (no threads)
  if (backend() != cloth_backend::cpu) {
    // The integrator, tearing or self-collision can change while the cloth is on the GPU (the
    // panel): what its path does not run (cloth_paths::runs) sends the cloth back to the CPU.
    if (std::string why; !cloth_paths::runs(backend(), cloth_stage.parameters, why))
      fall_back_to_cpu(why);
  }
  const int steps = steps_for_this_frame(frame_seconds);
  const double budget = control.mode == time_mode::real_time
                            ? control.max_simulation_seconds_per_frame
                            : std::numeric_limits<double>::infinity();
  simulate(steps, budget);
  if (steps > 0 && (!cloth_on_gpu() || state_fresh_))  // on the GPU: when it was read back
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
  if (start_hold_frames_left_ > 0 || start_hold_seconds_left_ > 0.0) {
    // The initial state in sight for a moment at start (the first frames are the slowest).
    start_hold_seconds_left_ = std::max(start_hold_seconds_left_ - frame_seconds, 0.0);
    start_hold_frames_left_ = std::max(start_hold_frames_left_ - 1, 0);
    status.start_hold_left = std::max(start_hold_seconds_left_, 0.05);
    if (start_hold_frames_left_ > 0 || start_hold_seconds_left_ > 0.0)
      return 0;
    status.start_hold_left = 0.0;
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
// On the GPU paths the steps go in batches, each checked for divergence on the GPU itself, and
// are timed between two glFinish, so that the GPU's work is counted, not only its submission.
void scene::simulate(int steps, double wall_clock_budget) {
  const bool on_gpu = cloth_on_gpu();
  if (on_gpu)
    paths_.finish();  // the previous frame's drawing is not counted as stepping
  const clock::time_point start = clock::now();
  const auto over_budget = [&] {
    if (!std::isfinite(wall_clock_budget))
      return false;
    if (on_gpu)
      paths_.finish();
    return seconds_since(start) > wall_clock_budget;
  };
  int done = 0;
  while (done < steps && !current_status().diverged) {
    if (on_gpu) {
      const int batch = std::min(gpu_steps_between_budget_checks, steps - done);
      // Each step checked on the GPU: the first step after which a particle diverged, or 0.
      const int diverged_after = paths_.run(batch);
      const int taken = diverged_after != 0 ? diverged_after : batch;
      for (int i = 0; i < taken; ++i)
        count_step(cloth_stage.parameters.dynamics.time_step);
      done += taken;
      if (diverged_after != 0) {
        read_gpu_state();  // the state at the end of the batch, to say what went wrong
        divergence_status check = divergence_check(cloth_stage);
        if (!check.diverged)
          check = {true, format(tr("a particle not finite or faster than %g m/s (checked on the "
                                   "GPU)"),
                                paths_.speed_bound())};
        report_divergence(std::move(check));
        break;
      }
    } else {
      step_current_stage();
      ++done;
    }
    if (done < steps && over_budget()) {
      current_status().behind_real_time = true;
      unsimulated_seconds_ = 0.0;  // the backlog is dropped, as when the step cap is hit
      break;
    }
  }
  if (on_gpu)
    paths_.finish();
  const double stepping_seconds = seconds_since(start);
  anatomy_.steps = done;
  if (on_gpu)
    anatomy_.gpu_steps_seconds = stepping_seconds;
  // The state comes back only for what the panel shows, at a bounded rate; and, while the cloth
  // can tear, for the springs overlay, whose lines are the springs of cloth_stage.
  const bool overlay_needs_state = display.show_springs && cloth_stage.parameters.tear_strain > 0.0;
  if (on_gpu && done > 0 && (panel_needs_state || overlay_needs_state) && !state_fresh_ &&
      paths_.seconds_since_readback() >= 1.0 / max_readbacks_per_second)
    read_gpu_state();
  rates_.add_frame(done, stepping_seconds);
  // The first tear: on the CPU path at the frame it happens, on the GPU paths at the read-back
  // that brings it.
  if (stage_ == stage_kind::cloth && done > 0)
    tear_report_.check(cloth_stage, status().step, status().time);
}

// One step: force computation, then numerical integration (question 3), then the divergence
// check (question 4): an explosion stops the run instead of drawing NaNs. The check also stops
// a run whose speeds pass far beyond anything a stable run reaches (stability.hpp), so that
// the explosion is caught before the numbers overflow. (The GPU paths: simulate.)
// Each phase is timed for the frame anatomy (questions 1 and 3), around the stage's step.
void scene::step_current_stage() {
  const auto timed = [this](step_phase phase, auto&& run) {
    const clock::time_point start = clock::now();
    run();
    anatomy_.seconds_of(phase) += seconds_since(start);
  };
  auto [time_step, check] = with_current_stage([&](auto& stage) {
    stage.step(timed);
    const clock::time_point start = clock::now();
    divergence_status found = divergence_check(stage);
    anatomy_.check_seconds += seconds_since(start);
    return std::pair{stage.parameters.dynamics.time_step, std::move(found)};
  });
  count_step(time_step);
  report_divergence(std::move(check));
  record_spring_motion();
}

void scene::count_step(double time_step) {
  run_status& status = current_status();
  ++status.step;
  status.time += time_step;
  ++steps_taken_;
  count_grab_stillness(time_step);
}

// While a grab is held, each whole simulated second since its target last moved is said once:
// what the window tests wait for before they judge where the grabbed mass or particle went
// (under load the window runs far fewer steps a second of wall time).
void scene::count_grab_stillness(double time_step) {
  if (!grabbing())
    return;
  const glm::dvec3 target = drag_target();
  if (target != grab_target_) {
    grab_target_ = target;
    grab_still_seconds_ = 0.0;
    return;
  }
  const double before = grab_still_seconds_;
  grab_still_seconds_ += time_step;
  if (std::floor(grab_still_seconds_) > std::floor(before)) {
    // (not translated: read by the window tests)
    std::printf("clothlab-window: the grab's target has been still for %.0f s of simulated time\n",
                std::floor(grab_still_seconds_));
    std::fflush(stdout);
  }
}

void scene::report_divergence(divergence_status check) {
  run_status& status = current_status();
  if (check.diverged) {
    status.diverged = true;
    status.divergence_reason = std::move(check.reason);
    // Where dt stood against the stability limit (question 4), with the parameters that diverged.
    const stability_estimate estimate =
        with_current_stage([](const auto& stage) { return estimate_stability(stage); });
    status.divergence_advice =
        format(tr("dt omega_max = %.3g: %s"), current_time_step() * estimate.omega_max,
               estimate.explanation.c_str());
    std::printf(tr("clothlab-window: %s\n"),
                format(tr("%s diverged at step %ld (t = %g s): %s; %s"), stage_in_words(stage_),
                       status.step, status.time, status.divergence_reason.c_str(),
                       status.divergence_advice.c_str())
                    .c_str());
    std::fflush(stdout);
  }
}

// Display: the renderer reads the state and never changes it. It draws straight into the
// window's framebuffer, in the part right of the panel (viewport and scissor at x = left).
void scene::draw(int left, int width, int height) {
  viewport_left_ = left;
  viewport_width_ = std::max(width, 1);
  viewport_height_ = std::max(height, 1);
  // Under the panel (drawn over it, nearly opaque): the scene's background colour.
  glViewport(0, 0, left + width, height);
  if (left > 0) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, left, height);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
  }
  check_in_view();
  const clock::time_point draw_start = clock::now();
  draw_stage(left, width, height);
  anatomy_.draw_seconds = seconds_since(draw_start);
  if (stage_ == stage_kind::cloth && backend() == cloth_backend::cpu && !status().diverged) {
    anatomy_.normals_seconds = renderer_.last_normals_seconds();  // (part of the drawing's time)
    anatomy_.draw_seconds -= anatomy_.normals_seconds;
  }
}

void scene::finish_frame_anatomy(double poll_and_panel_seconds, double panel_and_swap_seconds,
                                 double frame_seconds) {
  anatomy_.poll_and_panel_seconds = poll_and_panel_seconds;
  anatomy_.panel_and_swap_seconds = panel_and_swap_seconds;
  anatomy_.frame_seconds = frame_seconds;
  last_anatomy_ = anatomy_;
}

void scene::draw_stage(int left, int width, int height) {
  if (status().diverged) {
    // Nothing finite to draw: an empty scene (the renderer's background); the panel says why.
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    return;
  }
  switch (stage_) {
    case stage_kind::spring:
      renderer_.draw(spring_stage, view, display, width, height, left);
      break;
    case stage_kind::coupled:
      renderer_.draw(chain_stage, view, display, width, height, left);
      break;
    case stage_kind::cloth:
      if (on_gpu(backend())) {
        // Question 11: the flat grid's vertex shader fetches positions and normals from the GPU
        // path's textures (the compute path's buffers, copied on the GPU into textures laid out
        // the same way).
        const cloth_textures drawn = paths_.textures();
        renderer_.draw_from_textures(drawn.position, drawn.normal, cloth_stage, view, display,
                                     width, height, left, drawn.spring_mask);
        break;
      }
      renderer_.draw(cloth_stage, view, display, width, height, left);
      break;
  }
}

// Whether the stage fell below the view (the student's copy, before questions 6 to 9: the cloth
// falls freely), said once in the output when it happens; the panel says it over the scene. On
// the GPU paths, from the positions of the last read-back.
void scene::check_in_view() {
  const bool was_out = fell_out_of_view_;
  const float aspect = static_cast<float>(viewport_width_) / static_cast<float>(viewport_height_);
  fell_out_of_view_ = !status().diverged && with_current_stage([&](const auto& stage) {
    return fell_below_view(view, aspect, stage.particles().position);
  });
  if (fell_out_of_view_ && !was_out) {
    std::printf(tr("clothlab-window: %s\n"), format(tr("%s fell out of view at t = %.2f s"),
                                                    stage_in_words(stage_), status().time)
                                                 .c_str());
    std::fflush(stdout);
  }
}

// Question 4: kinetic + gravitational + spring energy. Without damping the exact motion keeps it
// constant; explicit Euler makes it grow, the symplectic schemes keep it oscillating about its
// initial value, implicit Euler makes it decay.
void scene::record_energy() {
  if (status().diverged)
    return;
  energy_history_.record(
      with_current_stage([](const auto& stage) { return compute_energy(stage); }), status().time);
}

void scene::restart_energy_history() {
  energy_history_.clear();
  record_energy();
  record_spring_motion();
}

// Question 2's plot: a sample of the spring after every step (spring_motion.hpp), so that its
// curve is the simulation's, whatever the frame rate.
void scene::record_spring_motion() {
  if (stage_ == stage_kind::spring && !status().diverged)
    spring_motion_.record(spring_stage, status().time, status().step);
}

}  // namespace clothlab
