#include "window/scene.hpp"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "core/stability.hpp"
#include "gl/gl.hpp"
#include "gl/render_geometry.hpp"  // chain_mass_radius, drawn_mass_radius
#include "window/framing.hpp"      // chain_view

namespace clothlab {

namespace {

// Real time on the GPU path: the GPU runs the submitted steps later than the CPU submits them,
// so the frame's wall-clock budget is checked after a glFinish, once every this many steps
// (a finish after every step would measure the synchronisation more than the steps).
constexpr int gpu_steps_between_budget_checks = 8;
// In the browser, where threads are not, the stability map computes its cells between frames:
// this long a frame (at least a cell), so that the page stays responsive while it fills in.
constexpr double map_seconds_per_frame = 0.012;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

scene::scene(const options& start)
    : paths_(start.cloth),
      spring_stage(start.spring),
      chain_stage(start.coupled),
      cloth_stage(paths_.cloth),
      spring_one_dimensional_start(start.spring_1d_start),
      view(camera::default_for(start.stage)),
      stage_(start.stage) {}

scene::~scene() = default;

bool scene::init_renderer(std::string& error) {
  if (const GLubyte* name = glGetString(GL_RENDERER); name != nullptr)
    renderer_name_ = reinterpret_cast<const char*>(name);
  paths_.check_compute_offered();
  return renderer_.init(error);
}

// Question 11: positions and velocities are the cloth's (on the GPU path, read back from its
// textures once per frame); normals are read from the GPU's normal texture, or computed on the
// CPU as the CPU path does (central differences, model.md).
const state_images& scene::state_textures() {
  const long step = status_[static_cast<int>(stage_kind::cloth)].step;
  const bool from_gpu = cloth_on_gpu();
  const int n = cloth_stage.grid_size();
  if (step == state_images_step_ && from_gpu == state_images_from_gpu_ &&
      state_images_.grid_size() == n)
    return state_images_;
  const particle_system& particles = cloth_stage.particles();
  const auto texels = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  normal_scratch_.resize(3 * texels);
  if (from_gpu) {
    paths_.read_normals(texel_scratch_);
    for (std::size_t k = 0; k < texels; ++k) {
      for (std::size_t c = 0; c < 3; ++c)
        normal_scratch_[3 * k + c] = texel_scratch_[4 * k + c];
    }
  } else {
    compute_vertex_normals(n, particles.position, normal_scratch_);
  }
  state_images_.update(n, particles.position, particles.velocity, normal_scratch_);
  state_images_step_ = step;
  state_images_from_gpu_ = from_gpu;
  return state_images_;
}

// ---- Initialisation ---------------------------------------------------------------------

// Stage 1, with the 1D start of question 2 when asked: only the component of v1 along the
// spring (p1 - p0) is kept.
void scene::load_spring_stage() {
  spring_stage.load_model();
  if (!spring_one_dimensional_start)
    return;
  particle_system& particles = spring_stage.particles();
  const glm::dvec3 axis = particles.get_position(1) - particles.get_position(0);
  const glm::dvec3 v = particles.get_velocity(1);
  particles.set_velocity(1, glm::dot(v, axis) / glm::dot(axis, axis) * axis);
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

// ---- The cloth's path: CPU or GPU (questions 11 and 12) ---------------------------------

// Uploads cloth_stage's current state to a GPU path.
bool scene::load_gpu_path(cloth_backend target, std::string& why) {
  return gpu_can_run(target, why) && paths_.load(target, why);
}

void scene::read_gpu_state() {
  if (!on_gpu(paths_.backend()))
    return;
  paths_.read_state();
  state_fresh_ = true;
}

void scene::switch_cloth_backend(cloth_backend target) {
  const cloth_backend from = backend();
  if (target == from)
    return;
  const long step = status_[static_cast<int>(stage_kind::cloth)].step;
  std::string why;
  if (on_gpu(target) && !gpu_can_run(target, why)) {
    backend_message_ = std::string("The cloth stays on the ") + backend_name(from) + ": " + why;
    std::printf("clothlab-window: %s\n", backend_message_.c_str());
    std::fflush(stdout);
    return;
  }
  // The new path takes the cloth's current state (positions, velocities, pins, rest lengths):
  // read back from the GPU path it is on, if any.
  read_gpu_state();
  if (!paths_.load(target, why)) {  // the cloth is then on the CPU path
    backend_message_ = "The cloth went to the CPU: " + why;
    std::printf("clothlab-window: %s\n", backend_message_.c_str());
    std::fflush(stdout);
    return;
  }
  restart_rate_window();  // the stepping rate shown is the new path's
  backend_message_ = std::string("cloth: ") + backend_name(from) + " -> " + backend_name(target) +
                     " at step " + std::to_string(step);
  std::printf("clothlab-window: %s\n", backend_message_.c_str());
  std::fflush(stdout);
}

void scene::toggle_cloth_backend() {
  switch (backend()) {
    case cloth_backend::cpu:
    case cloth_backend::cpu_parallel:
      switch_cloth_backend(cloth_backend::gpu);
      return;
    case cloth_backend::gpu:
      if (std::string why; compute_offered(why))
        switch_cloth_backend(cloth_backend::gpu_compute);
      else
        switch_cloth_backend(cloth_backend::cpu);
      return;
    case cloth_backend::gpu_compute:
      switch_cloth_backend(cloth_backend::cpu);
      return;
  }
}

void scene::fall_back_to_cpu(const std::string& reason) {
  const cloth_backend from = backend();
  read_gpu_state();
  std::string none;
  paths_.load(cloth_backend::cpu, none);  // loads nothing: the CPU cloth holds the state now
  backend_message_ = std::string("cloth: ") + backend_name(from) + " -> CPU at step " +
                     std::to_string(status_[static_cast<int>(stage_kind::cloth)].step) + ": " +
                     reason;
  std::printf("clothlab-window: %s\n", backend_message_.c_str());
  std::fflush(stdout);
}

// After load_model of the cloth: the GPU path takes the new initial state (a new N, S or pins).
void scene::reload_gpu_cloth() {
  if (backend() == cloth_backend::cpu)
    return;
  std::string why;
  if (!load_gpu_path(backend(), why)) {
    std::string none;
    paths_.load(cloth_backend::cpu, none);  // the cloth goes on from its new state on the CPU
    backend_message_ = "The cloth went back to the CPU: " + why;
    std::printf("clothlab-window: %s\n", backend_message_.c_str());
    std::fflush(stdout);
  }
}

// Question 12: the same number of steps of every path, from the current state, on copies
// (cloth_paths::measure), said in one line.
void scene::measure_backends(int steps) {
  comparison_ = paths_.measure(steps);
  const std::string& why = comparison_.gpu_error;
  const std::string& compute_why = comparison_.compute_error;
  std::printf(
      "clothlab-window: N = %d, %d steps: CPU %.0f steps/s, GPU %.0f steps/s%s%s, GPU compute "
      "%.0f steps/s%s%s\n",
      comparison_.grid_size, steps, comparison_.cpu_steps_per_second,
      comparison_.gpu_steps_per_second, why.empty() ? "" : ": ", why.c_str(),
      comparison_.compute_steps_per_second, compute_why.empty() ? "" : ": ", compute_why.c_str());
  std::fflush(stdout);
}

// ---- The mouse on the cloth (issue 10) -----------------------------------------------------

pick_ray scene::ray_at(double x, double y) const {
  const double ndc_x = 2.0 * (x - viewport_left_) / viewport_width_ - 1.0;
  const double ndc_y = 1.0 - 2.0 * y / viewport_height_;
  const float aspect = static_cast<float>(viewport_width_) / static_cast<float>(viewport_height_);
  return ray_through(view, aspect, ndc_x, ndc_y);
}

double scene::radians_per_pixel() const {
  return static_cast<double>(view.field_of_view) / viewport_height_;
}

std::optional<glm::dvec2> scene::framebuffer_point(const glm::dvec3& point) const {
  const float aspect = static_cast<float>(viewport_width_) / static_cast<float>(viewport_height_);
  const glm::dvec4 clip =
      glm::dmat4(view.projection(aspect)) * glm::dmat4(view.view()) * glm::dvec4(point, 1.0);
  if (clip.w <= 0.0)
    return std::nullopt;
  return glm::dvec2(viewport_left_ + (clip.x / clip.w + 1.0) / 2.0 * viewport_width_,
                    (1.0 - clip.y / clip.w) / 2.0 * viewport_height_);
}

mass_drag_parameters* scene::mass_drag() {
  return const_cast<mass_drag_parameters*>(std::as_const(*this).mass_drag());
}

const mass_drag_parameters* scene::mass_drag() const {
  return stage_ == stage_kind::spring    ? &spring_stage.parameters.drag
         : stage_ == stage_kind::coupled ? &chain_stage.parameters.drag
                                         : nullptr;
}

const particle_system& scene::mass_particles() const {
  return stage_ == stage_kind::spring ? spring_stage.particles() : chain_stage.particles();
}

bool scene::grabbing() const {
  if (const mass_drag_parameters* drag = mass_drag())
    return drag->enabled;
  return cloth_stage.parameters.drag.enabled;
}

glm::dvec3 scene::drag_target() const {
  if (const mass_drag_parameters* drag = mass_drag())
    return drag->target;
  return cloth_stage.parameters.drag.target;
}

bool scene::grab_particle(const pick_ray& ray, double max_angle) {
  if (status().diverged)
    return false;
  if (mass_drag_parameters* drag = mass_drag()) {  // stages 1 and 2: a mass
    const particle_system& particles = mass_particles();
    // The spheres as drawn: at least a few pixels wide, however far the view.
    const float metres_per_pixel = view.metres_per_pixel(static_cast<float>(viewport_height_));
    const std::optional<std::size_t> picked =
        pick_mass(particles, ray, drawn_mass_radius(chain_mass_radius, metres_per_pixel),
                  drawn_mass_radius(chain_fixed_point_radius, metres_per_pixel), max_angle);
    if (!picked)
      return false;
    const std::string stage = std::string(stage_name(stage_));
    if (particles.is_fixed[*picked]) {
      std::printf("clothlab-window: p%zu of the %s stage is fixed: it cannot be dragged\n", *picked,
                  stage.c_str());
      std::fflush(stdout);
      return false;
    }
    const glm::dvec3 position = particles.get_position(*picked);
    drag->enabled = true;
    drag->mass = static_cast<int>(*picked);
    drag->target = position;
    grab_plane_point_ = position;
    std::printf("clothlab-window: grabbed mass %zu of the %s stage at (%.3f, %.3f, %.3f)\n",
                *picked, stage.c_str(), position.x, position.y, position.z);
    std::fflush(stdout);
    return true;
  }
  if (cloth_on_gpu())
    read_gpu_state();  // the positions the user sees, once, at the press
  const std::optional<std::size_t> picked = pick_particle(cloth_stage, ray, max_angle);
  if (!picked)
    return false;
  const int n = cloth_stage.grid_size();
  const int ku = static_cast<int>(*picked % static_cast<std::size_t>(n));
  const int kv = static_cast<int>(*picked / static_cast<std::size_t>(n));
  const glm::dvec3 position = cloth_stage.particles().get_position(*picked);
  if (cloth_stage.particles().is_fixed[*picked]) {
    std::printf("clothlab-window: particle (%d, %d) is pinned: it cannot be dragged\n", ku, kv);
    std::fflush(stdout);
    return false;
  }
  drag_parameters& drag = cloth_stage.parameters.drag;
  drag.enabled = true;
  drag.ku = ku;
  drag.kv = kv;
  drag.target = position;
  grab_plane_point_ = position;
  std::printf("clothlab-window: grabbed particle (%d, %d) at (%.3f, %.3f, %.3f)\n", ku, kv,
              position.x, position.y, position.z);
  std::fflush(stdout);
  return true;
}

void scene::drag_grabbed(const pick_ray& ray) {
  if (!grabbing())
    return;
  const glm::dvec3 target = point_on_plane(ray, grab_plane_point_, viewing_direction(view));
  if (mass_drag_parameters* drag = mass_drag())
    drag->target = target;
  else
    cloth_stage.parameters.drag.target = target;
}

void scene::release_grab() {
  if (!grabbing())
    return;
  const glm::dvec3 position = grabbed_position();
  if (mass_drag_parameters* drag = mass_drag()) {
    drag->enabled = false;
    std::printf(
        "clothlab-window: released mass %d of the %s stage at (%.3f, %.3f, %.3f), target (%.3f, "
        "%.3f, %.3f)\n",
        drag->mass, std::string(stage_name(stage_)).c_str(), position.x, position.y, position.z,
        drag->target.x, drag->target.y, drag->target.z);
    std::fflush(stdout);
    return;
  }
  drag_parameters& drag = cloth_stage.parameters.drag;
  drag.enabled = false;
  const std::size_t springs = cloth_spring_count();  // fewer than at the start when it tore
  std::printf(
      "clothlab-window: released particle (%d, %d) at (%.3f, %.3f, %.3f), target (%.3f, %.3f, "
      "%.3f), %zu springs\n",
      drag.ku, drag.kv, position.x, position.y, position.z, drag.target.x, drag.target.y,
      drag.target.z, springs);
  std::fflush(stdout);
}

glm::dvec3 scene::grabbed_position() {
  if (const mass_drag_parameters* mass = mass_drag()) {
    const particle_system& particles = mass_particles();
    return particles.get_position(
        std::min(static_cast<std::size_t>(std::max(mass->mass, 0)), particles.size() - 1));
  }
  const drag_parameters& drag = cloth_stage.parameters.drag;
  const int n = cloth_stage.grid_size();
  const std::size_t k =
      spring_mesh::index(std::clamp(drag.ku, 0, n - 1), std::clamp(drag.kv, 0, n - 1), n);
  return paths_.position(k);  // on a GPU path, one texel read back
}

void scene::start_sphere_move(const pick_ray& ray) {
  const sphere_parameters& sphere = cloth_stage.parameters.sphere;
  sphere_plane_point_ = sphere.centre;
  sphere_grab_offset_ = point_on_plane(ray, sphere.centre, viewing_direction(view)) - sphere.centre;
}

void scene::move_sphere(const pick_ray& ray) {
  cloth_stage.parameters.sphere.centre =
      point_on_plane(ray, sphere_plane_point_, viewing_direction(view)) - sphere_grab_offset_;
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
    // panel): what the GPU does not run (gpu_cloth::supports) sends the cloth back to the CPU.
    if (std::string why; !gpu_cloth::supports(cloth_stage.parameters, why))
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
          check = {true, "a particle not finite or faster than " +
                             std::to_string(paths_.speed_bound()) + " m/s (checked on the GPU)"};
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
  measure_rates(done, stepping_seconds);
  if (stage_ == stage_kind::cloth && done > 0)
    report_first_tear();
}

// The springs of the cloth as cloth_stage has them (on a GPU path, as of the last read-back).
std::size_t scene::cloth_spring_count() const {
  std::size_t springs = 0;
  for (const spring_family family : all_spring_families)
    springs += cloth_stage.springs(family).size();
  return springs;
}

// The first tear of a cloth, said once until it is whole again (reset, rebuild): on the CPU path
// at the frame it happens, on the GPU paths at the read-back that brings it.
void scene::report_first_tear() {
  // The springs of the whole N x N cloth (model.md): structural 2 N (N - 1), shear
  // 2 (N - 1)^2, bending 2 N (N - 2).
  const auto n = static_cast<std::size_t>(std::max(cloth_stage.grid_size(), 2));
  const std::size_t whole = 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n - 2);
  const std::size_t springs = cloth_spring_count();
  if (springs >= whole) {
    tear_reported_ = false;
    return;
  }
  if (tear_reported_)
    return;
  tear_reported_ = true;
  std::printf(
      "clothlab-window: the cloth began to tear by step %ld (t = %.3f s): %zu of %zu "
      "springs left\n",
      status().step, status().time, springs, whole);
  std::fflush(stdout);
}

// One step: force computation, then numerical integration (question 3), then the divergence
// check (question 4): an explosion stops the run instead of drawing NaNs. The check also stops
// a run whose speeds pass far beyond anything a stable run reaches (stability.hpp), so that
// the explosion is caught before the numbers overflow. (The GPU paths: simulate.)
void scene::step_current_stage() {
  // Each phase timed for the frame anatomy (questions 1 and 3), around the student's functions.
  auto [time_step, check] = with_current_stage([this](auto& stage) {
    const clock::time_point start = clock::now();
    stage.compute_force();  // forces from the positions at the start of the step
    const clock::time_point forces_done = clock::now();
    stage.apply_force();  // numerical integration (pins: fixed vertices are never moved)
    const clock::time_point integrated = clock::now();
    stage.apply_constraints();  // the cloth's sphere, ground, self-collision, tearing
    const clock::time_point constrained = clock::now();
    divergence_status found = divergence_check(stage);
    const clock::time_point checked = clock::now();
    anatomy_.compute_force_seconds += std::chrono::duration<double>(forces_done - start).count();
    anatomy_.apply_force_seconds += std::chrono::duration<double>(integrated - forces_done).count();
    anatomy_.constraints_seconds += std::chrono::duration<double>(constrained - integrated).count();
    anatomy_.check_seconds += std::chrono::duration<double>(checked - constrained).count();
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
}

void scene::report_divergence(divergence_status check) {
  run_status& status = current_status();
  if (check.diverged) {
    status.diverged = true;
    status.divergence_reason = std::move(check.reason);
    // Where dt stood against the stability limit (question 4), with the parameters that diverged.
    const stability_estimate estimate =
        with_current_stage([](const auto& stage) { return estimate_stability(stage); });
    char advice[64];
    std::snprintf(advice, sizeof advice,
                  "dt omega_max = %.3g: ", current_time_step() * estimate.omega_max);
    status.divergence_advice = advice + estimate.explanation;
    std::printf("clothlab-window: the %s stage diverged at step %ld (t = %g s): %s; %s\n",
                std::string(stage_name(stage_)).c_str(), status.step, status.time,
                status.divergence_reason.c_str(), status.divergence_advice.c_str());
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
    std::printf("clothlab-window: the %s stage fell out of view at t = %.2f s\n",
                std::string(stage_name(stage_)).c_str(), status().time);
    std::fflush(stdout);
  }
}

// Question 4: kinetic + gravitational + spring energy. Without damping the exact motion keeps it
// constant; explicit Euler makes it grow, the symplectic schemes keep it oscillating about its
// initial value, implicit Euler makes it decay.
void scene::record_energy() {
  if (status().diverged)
    return;
  constexpr std::size_t frames_kept = 600;
  energy_ = with_current_stage([](const auto& stage) { return compute_energy(stage); });
  const double values[4] = {energy_.kinetic, energy_.gravity, energy_.spring, energy_.total};
  for (std::size_t i = 0; i < energy_history_.size(); ++i) {
    std::vector<float>& history = energy_history_[i];
    if (history.size() == frames_kept)
      history.erase(history.begin());
    history.push_back(static_cast<float>(values[i]));
  }
  if (energy_times_.size() == frames_kept)
    energy_times_.erase(energy_times_.begin());
  energy_times_.push_back(static_cast<float>(status().time));
}

void scene::restart_energy_history() {
  for (std::vector<float>& history : energy_history_)
    history.clear();
  energy_times_.clear();
  record_energy();
  record_spring_motion();
}

// Question 2's plot: a sample of the spring after every step (spring_motion.hpp), so that its
// curve is the simulation's, whatever the frame rate.
void scene::record_spring_motion() {
  if (stage_ == stage_kind::spring && !status().diverged)
    spring_motion_.record(spring_stage, status().time, status().step);
}

void scene::restart_rate_window() {
  steps_in_rate_window_ = 0;
  frames_in_rate_window_ = 0;
  stepping_seconds_in_rate_window_ = 0.0;
  measured_stepping_rate_ = 0.0;
  rate_window_start_ = clock::now();
}

void scene::measure_rates(int steps, double stepping_seconds) {
  steps_in_rate_window_ += steps;
  frames_in_rate_window_ += 1;
  stepping_seconds_in_rate_window_ += stepping_seconds;
  const double seconds = seconds_since(rate_window_start_);
  if (seconds >= 0.5) {
    measured_steps_per_second_ = static_cast<double>(steps_in_rate_window_) / seconds;
    measured_frames_per_second_ = static_cast<double>(frames_in_rate_window_) / seconds;
    measured_stepping_rate_ =
        stepping_seconds_in_rate_window_ > 0.0
            ? static_cast<double>(steps_in_rate_window_) / stepping_seconds_in_rate_window_
            : 0.0;
    steps_in_rate_window_ = 0;
    frames_in_rate_window_ = 0;
    stepping_seconds_in_rate_window_ = 0.0;
    rate_window_start_ = clock::now();
  }
}

}  // namespace clothlab
