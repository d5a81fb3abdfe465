#include <cstdio>
#include <string>

#include "core/i18n.hpp"
#include "window/scene.hpp"

namespace clothlab {

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
    backend_message_ =
        format(tr("The cloth stays on the %s: %s"), tr(backend_name(from)), why.c_str());
    std::printf(tr("clothlab-window: %s\n"), backend_message_.c_str());
    std::fflush(stdout);
    return;
  }
  // The new path takes the cloth's current state (positions, velocities, pins, rest lengths):
  // read back from the GPU path it is on, if any.
  read_gpu_state();
  if (!paths_.load(target, why)) {  // the cloth is then on the CPU path
    backend_message_ = format(tr("The cloth went to the CPU: %s"), why.c_str());
    std::printf(tr("clothlab-window: %s\n"), backend_message_.c_str());
    std::fflush(stdout);
    return;
  }
  rates_.restart();  // the stepping rate shown is the new path's
  backend_message_ = format(tr("cloth: %s -> %s at step %ld"), tr(backend_name(from)),
                            tr(backend_name(target)), step);
  std::printf(tr("clothlab-window: %s\n"), backend_message_.c_str());
  std::fflush(stdout);
}

cloth_backend scene::next_cloth_backend() const {
  std::string why;
  switch (backend()) {
    case cloth_backend::cpu:
    case cloth_backend::cpu_parallel:
      // XPBD skips the fragment path, which runs the mass-spring integrators only.
      if (!cloth_paths::runs(cloth_backend::gpu, cloth_stage.parameters, why) &&
          cloth_paths::runs(cloth_backend::gpu_compute, cloth_stage.parameters, why) &&
          compute_offered(why))
        return cloth_backend::gpu_compute;
      return cloth_backend::gpu;
    case cloth_backend::gpu:
      return compute_offered(why) ? cloth_backend::gpu_compute : cloth_backend::cpu;
    case cloth_backend::gpu_compute:
      return cloth_backend::cpu;
  }
  return cloth_backend::cpu;
}

void scene::toggle_cloth_backend() {
  switch_cloth_backend(next_cloth_backend());
}

void scene::fall_back_to_cpu(const std::string& reason) {
  const cloth_backend from = backend();
  read_gpu_state();
  std::string none;
  paths_.load(cloth_backend::cpu, none);  // loads nothing: the CPU cloth holds the state now
  backend_message_ = format(tr("cloth: %s -> CPU at step %ld: %s"), tr(backend_name(from)),
                            status_[static_cast<int>(stage_kind::cloth)].step, reason.c_str());
  std::printf(tr("clothlab-window: %s\n"), backend_message_.c_str());
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
    backend_message_ = format(tr("The cloth went back to the CPU: %s"), why.c_str());
    std::printf(tr("clothlab-window: %s\n"), backend_message_.c_str());
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
      tr("clothlab-window: N = %d, %d steps: CPU %.0f steps/s, GPU %.0f steps/s%s%s, GPU compute "
         "%.0f steps/s%s%s\n"),
      comparison_.grid_size, steps, comparison_.cpu_steps_per_second,
      comparison_.gpu_steps_per_second, why.empty() ? "" : ": ", why.c_str(),
      comparison_.compute_steps_per_second, compute_why.empty() ? "" : ": ", compute_why.c_str());
  std::fflush(stdout);
}

}  // namespace clothlab
