// Handout section 5, questions 11 to 13: the cloth of spring_mesh simulated on the GPU with
// fragment shaders, in single precision, by exactly the model of docs/model.md.
//
// What both GPU paths share (the spring masks, the rest and tear lengths, the step's uniforms)
// is in gpu_step_inputs.hpp; the GL state guard in gl_state_guard.hpp.
//
// Every call needs the GL context current in which load() was called; destroy the gpu_cloth
// before that context. step() and read_state() leave the GL state they change (framebuffer
// bindings, viewport, program, textures, blending...) as they found it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/spring_mesh.hpp"
#include "gl/gl.hpp"
#include "gl/gpu_step_inputs.hpp"
#include "gl/shader.hpp"

namespace clothlab {

// Both paths' read_particle(k): throws std::logic_error before a load (grid_size 0) and
// std::out_of_range when k is outside the N x N grid, naming `who`.
void check_particle_index(const char* who, int grid_size, std::size_t k);

// One particle's state as a path holds it (single precision, widened): read_particle.
struct particle_state {
  glm::dvec3 position{0.0};  // m
  glm::dvec3 velocity{0.0};  // m/s
};

class gpu_cloth {
 public:
  gpu_cloth() = default;
  ~gpu_cloth();
  gpu_cloth(const gpu_cloth&) = delete;
  gpu_cloth& operator=(const gpu_cloth&) = delete;

  // True when an N x N cloth fits the context's limits (GL_MAX_TEXTURE_SIZE,
  // GL_MAX_VIEWPORT_DIMS); otherwise false with error naming N and the limit.
  static bool check_grid_size(int grid_size, std::string& error);

  // The fragment path integrates with semi-implicit and explicit Euler (model.md) only, the
  // mass-spring integrators of the handout (XPBD runs on the compute path). True when it can run
  // p's integrator; otherwise false with error naming the integrator.
  static bool supports_integrator(integrator_kind integrator, std::string& error);
  // Everything of p that the GPU paths run: their integrators, the drag, the sphere and
  // tearing; not self-collision (false, with error naming the option).
  static bool supports(const cloth_parameters& p, std::string& error);
  // The contacts of p that the GPU paths run: all but self-collision (false, with error naming
  // the option).
  static bool supports_contacts(const cloth_parameters& p, std::string& error);

  // Uploads the CPU cloth's CURRENT state (positions, velocities, pinned flags, the rest lengths
  // of its three spring families, its torn springs), so that a run can switch from CPU to GPU at
  // any step. Can be called again to load another state or size. On failure (grid too large,
  // GL_RGBA32F not renderable, a shader file missing or not compiling) returns false with a
  // full-sentence error and leaves the gpu_cloth unloaded.
  bool load(const spring_mesh& cloth, std::string& error);
  bool is_loaded() const { return grid_size_ != 0; }

  // One step of model.md with p's dynamics (dt, mu, m, g0, integrator), stiffnesses, wind and
  // ground, p being the parameters at the loaded N (spring_mesh::effective_parameters, question
  // 10: the caller resolves them). p's grid_size, side_length and pins are not read: they change
  // the cloth only through spring_mesh::load_model and a new load(). Throws std::logic_error
  // before a successful load, std::invalid_argument for an integrator that supports_integrator
  // refuses or for parameters not resolved (check_effective).
  void step(const cloth_parameters& p);
  // `count` steps as one batch: the caller's GL state saved and the uniforms set once. With
  // speed_bound > 0 (m/s) every step is also checked on the GPU, without reading the state
  // back: an occlusion query says whether any particle is not finite or faster than the bound
  // (shaders/gpu_check.frag). Returns the first step of the batch (1..count) after which a
  // particle diverged, 0 when none did (or without the check). The state then is that of the
  // end of the batch. In the web build (WebGL2) a query is read only in a later frame: a batch
  // returns `count` when an earlier batch's check found a diverged particle (see run).
  int run(const cloth_parameters& p, int count, double speed_bound = 0.0);

  // Runs `count` steps and returns the mean wall-clock seconds per step, with glFinish before
  // and after, so that the GPU's work is counted, not only its submission.
  double time_steps(const cloth_parameters& p, int count);

  // Copies the current positions and velocities (floats, widened to doubles) into
  // cloth.particles() and removes from cloth the springs torn on the GPU, for --csv, --obj,
  // --png and the GPU -> CPU switch (call cloth.compute_normals() where its normals are needed).
  // cloth must have this grid size (throws std::invalid_argument otherwise).
  void read_state(spring_mesh& cloth) const;
  // The current position and velocity of particle k = ku + N kv alone (one texel of each: the
  // mouse grab's read-back). Throws std::out_of_range for k outside the grid.
  particle_state read_particle(std::size_t k) const;

  int grid_size() const { return grid_size_; }  // N of the last successful load, 0 before
  // The textures of the current state (they change at every step: ask after stepping).
  GLuint position_texture() const { return position_[read_]; }
  // The normals of the current positions: computed here (one pass) unless a step's wind needed
  // them already; the steps compute them only for the wind.
  GLuint normal_texture();
  GLuint spring_mask_texture() const { return spring_mask_[mask_read_]; }  // GL_R32UI

 private:
  void release();
  // Pass 2: normal_ from position_[read_], in the passes' state (viewport, vertex array) set.
  void compute_normals();

  int grid_size_ = 0;
  std::array<float, 3> rest_length_{};  // L0 of the structural, shear, bending springs: h, h√2, 2h
  shader_program step_program_;
  shader_program normal_program_;
  shader_program tear_program_;     // pass 3, tearing
  shader_program check_program_;    // the divergence check (run)
  step_uniforms step_uniforms_;     // step_program_'s
  tear_uniform tear_uniform_;       // tear_program_'s tear_length
  float sent_speed_bound_ = -1.0f;  // the check pass's
  std::vector<GLuint> queries_;     // one occlusion query per step of a checked batch
  GLuint empty_vertex_array_ = 0;   // the full-screen triangle needs no vertex data
  // The web build's: how many queries_ an earlier batch issued that are not read yet (run).
  int pending_checks_ = 0;

  // Ping-pong: copy read_ holds the current state, copy write_ receives the next one; they swap
  // after every step. framebuffer_[i] renders into position_[i] (attachment 0) and velocity_[i]
  // (attachment 1).
  int read_ = 0;
  int write_ = 1;
  std::array<GLuint, 2> position_{};
  std::array<GLuint, 2> velocity_{};
  std::array<GLuint, 2> framebuffer_{};
  mutable std::vector<float> readback_;  // read_state's RGBA texels, reused
  // The spring mask, ping-pong: copy mask_read_ is the current one; mask_framebuffer_[i] renders
  // into spring_mask_[i]. Its own index: the tear pass runs only when the cloth tears.
  int mask_read_ = 0;
  std::array<GLuint, 2> spring_mask_{};
  std::array<GLuint, 2> mask_framebuffer_{};
  mutable std::vector<std::uint32_t> mask_readback_;
  // The normals are computed from the positions alone, never from themselves: one copy suffices.
  GLuint normal_ = 0;
  GLuint normal_framebuffer_ = 0;
  bool normals_current_ = false;  // normal_ holds the normals of position_[read_]
};

}  // namespace clothlab
