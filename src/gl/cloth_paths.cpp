#include "gl/cloth_paths.hpp"

#include <filesystem>
#include <stdexcept>
#include <utility>

#include "core/i18n.hpp"
#include "core/stability.hpp"
#include "core/wall_clock.hpp"
#include "core/xpbd.hpp"
#include "gl/gl_state_guard.hpp"
#include "gl/shader.hpp"  // shader_path

namespace clothlab {

cloth_paths::~cloth_paths() {
  if (compute_texture_size_ != 0) {
    const GLuint textures[] = {compute_textures_.position, compute_textures_.normal,
                               compute_textures_.spring_mask};
    glDeleteTextures(3, textures);
  }
}

void cloth_paths::check_compute_offered() {
  compute_unavailable_.clear();
  if (gpu_cloth_compute::available(compute_unavailable_) &&
      !std::filesystem::exists(shader_path("gpu_compute_step.comp")))
    compute_unavailable_ = format(tr("this copy of the lab has no compute path (%s is missing)"),
                                  shader_path("gpu_compute_step.comp").string().c_str());
}

bool cloth_paths::runs(cloth_backend target, const cloth_parameters& p, std::string& why) {
  if (p.dynamics.integrator == integrator_kind::xpbd && !xpbd_available()) {
    why = xpbd_unavailable_reason();
    return false;
  }
  switch (target) {
    case cloth_backend::cpu:
      return true;
    case cloth_backend::cpu_parallel:
      return cloth_parallel::supports(p, why);
    case cloth_backend::gpu:
      return gpu_cloth::supports(p, why);
    case cloth_backend::gpu_compute:
      return gpu_cloth_compute::supports(p, why);
  }
  return false;
}

bool cloth_paths::gpu_can_run(cloth_backend target, std::string& why) const {
  if (!runs(target, cloth.parameters, why))
    return false;
  if (target == cloth_backend::gpu_compute)
    return compute_offered(why);
  return gpu_cloth::check_grid_size(cloth.grid_size(), why);
}

bool cloth_paths::load(cloth_backend target, std::string& error) {
  if (!on_gpu(target))
    return cpu_cloth_paths::load(target, error);
  // Question 4's bound, from the cloth as loaded: a particle faster than it has diverged.
  speed_bound_ = divergence_speed_bound(cloth);
  const bool loaded =
      target == cloth_backend::gpu ? gpu_.load(cloth, error) : gpu_compute_.load(cloth, error);
  backend_ = loaded ? target : cloth_backend::cpu;
  return loaded;
}

void cloth_paths::read_state() {
  switch (backend_) {
    case cloth_backend::cpu:
    case cloth_backend::cpu_parallel:
      cpu_cloth_paths::read_state();
      return;
    case cloth_backend::gpu:
      gpu_.read_state(cloth);
      break;
    case cloth_backend::gpu_compute:
      gpu_compute_.read_state(cloth);
      break;
  }
  ++readbacks_;
  last_readback_ = std::chrono::steady_clock::now();
}

int cloth_paths::run(int count) {
  switch (backend_) {
    case cloth_backend::gpu:
      return gpu_.run(cloth.effective_parameters(), count, speed_bound_);
    case cloth_backend::gpu_compute:
      return gpu_compute_.run(cloth.effective_parameters(), count, speed_bound_);
    case cloth_backend::cpu:
    case cloth_backend::cpu_parallel:
      break;
  }
  return cpu_cloth_paths::run(count);
}

void cloth_paths::finish() const {
  if (on_gpu(backend_))
    glFinish();
}

glm::dvec3 cloth_paths::position(std::size_t k) {
  switch (backend_) {
    case cloth_backend::gpu:
      return gpu_.read_particle(k).position;
    case cloth_backend::gpu_compute:
      return gpu_compute_.read_particle(k).position;
    case cloth_backend::cpu:
    case cloth_backend::cpu_parallel:
      break;
  }
  return cpu_cloth_paths::position(k);
}

cloth_textures cloth_paths::textures() {
  if (backend_ == cloth_backend::gpu)
    return {gpu_.position_texture(), gpu_.normal_texture(), gpu_.spring_mask_texture()};
  if (backend_ == cloth_backend::gpu_compute) {
    copy_compute_state_to_textures();
    return compute_textures_;
  }
  return {};
}

void cloth_paths::read_normals(std::vector<float>& rgba) {
  const cloth_textures drawn = textures();
  const auto n = static_cast<std::size_t>(cloth.grid_size());
  rgba.resize(4 * n * n);
  // Read through a framebuffer (OpenGL ES has no glGetTexImage), the caller's one bound again.
  const saved_gl_state saved;
  GLuint framebuffer = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, drawn.normal, 0);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, static_cast<GLsizei>(n), static_cast<GLsizei>(n), GL_RGBA, GL_FLOAT,
               rgba.data());
  glDeleteFramebuffers(1, &framebuffer);
}

double cloth_paths::seconds_since_readback() const {
  return seconds_since(last_readback_);
}

// The compute path keeps particle k = ku + N kv at element k of its buffers, one vec4 each: the
// row-major layout of an N x N RGBA32F texture. A pixel-unpack copy fills the textures from the
// buffers without the data leaving the GPU.
void cloth_paths::copy_compute_state_to_textures() {
  const int n = gpu_compute_.grid_size();
  if (n == 0)
    return;
  const saved_gl_state saved;  // the caller's texture and unpack buffer bindings, restored
  if (compute_texture_size_ != n) {
    for (GLuint* texture : {&compute_textures_.position, &compute_textures_.normal}) {
      if (*texture == 0)
        glGenTextures(1, texture);
      glBindTexture(GL_TEXTURE_2D, *texture);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, n, n, 0, GL_RGBA, GL_FLOAT, nullptr);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    if (compute_textures_.spring_mask == 0)
      glGenTextures(1, &compute_textures_.spring_mask);
    glBindTexture(GL_TEXTURE_2D, compute_textures_.spring_mask);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, n, n, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    compute_texture_size_ = n;
  }
  const GLuint normal_buffer = gpu_compute_.normal_buffer();  // (computed if not yet)
#if !defined(CLOTHLAB_GL_WEB)  // (the web build has no compute path, nor OpenGL 4.3's barriers)
  glMemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT);  // after the compute shaders' writes
#endif
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  const std::pair<GLuint, GLuint> copies[] = {
      {gpu_compute_.position_buffer(), compute_textures_.position},
      {normal_buffer, compute_textures_.normal}};
  for (const auto& [buffer, texture] : copies) {
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, n, n, GL_RGBA, GL_FLOAT, nullptr);
  }
  // The spring masks (tearing), so that the drawing leaves out the torn triangles.
  if (gpu_compute_.spring_mask_buffer() != 0) {
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, gpu_compute_.spring_mask_buffer());
    glBindTexture(GL_TEXTURE_2D, compute_textures_.spring_mask);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, n, n, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  }
}

backend_comparison cloth_paths::measure(int steps) {
  read_state();  // the current state, whichever path holds it
  backend_comparison comparison;
  comparison.measured = true;
  comparison.grid_size = cloth.grid_size();
  comparison.steps = steps;

  spring_mesh cpu_copy = cloth;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i)
    cpu_copy.step();
  comparison.cpu_steps_per_second = steps / seconds_since(start);

  const cloth_parameters at_this_n = cloth.effective_parameters();  // question 10
  gpu_cloth gpu_copy;
  if (gpu_can_run(cloth_backend::gpu, comparison.gpu_error) &&
      gpu_copy.load(cloth, comparison.gpu_error))
    comparison.gpu_steps_per_second = 1.0 / gpu_copy.time_steps(at_this_n, steps);

  gpu_cloth_compute compute_copy;
  if (gpu_can_run(cloth_backend::gpu_compute, comparison.compute_error) &&
      compute_copy.load(cloth, comparison.compute_error)) {
    glFinish();
    const auto compute_start = std::chrono::steady_clock::now();
    compute_copy.run(at_this_n, steps);
    glFinish();
    comparison.compute_steps_per_second = steps / seconds_since(compute_start);
  }
  return comparison;
}

}  // namespace clothlab
