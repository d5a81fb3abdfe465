// The compute-shader GPU path of the cloth (--backend gpu-compute): the model of
// docs/model.md in single precision, like gpu_cloth, but in OpenGL 4.3 compute shaders over
// shader storage buffers (one vec4 per particle, particle k = ku + N kv at element k) instead of
// fragment shaders over textures: no rasterisation, no framebuffer. One step, one dispatch:
// shaders/gpu_compute_step.comp (forces, integrator, sphere, ground) from copy read_ into copy
// write_ of the positions and velocities, which then swap; before it, when the wind needs them,
// shaders/gpu_compute_normal.comp (the normals of the current positions, also computed when
// normal_buffer() is asked for); after it, when the cloth tears, shaders/gpu_compute_tear.comp
// (the springs the new positions overstretch leave the spring mask, a storage buffer of one word
// per particle, gpu_cloth.hpp). It runs what gpu_cloth runs, and XPBD (supports()).
// With --integrator xpbd (src/core/xpbd.hpp) a step is, after the normal pass when there is
// wind, `substeps` times: shaders/gpu_xpbd_predict.comp, then 12 colours of
// shaders/gpu_xpbd_solve.comp per iteration (a colour's springs share no particle: its
// invocations write disjoint particles), then shaders/gpu_xpbd_velocity.comp (after the last
// substep with the sphere, the ground and the divergence check), in place in the current copy.
// Needs a 4.3 context (the off-screen ones ask for it); load() refuses an older one by name.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/spring_mesh.hpp"
#include "gl/gl.hpp"
#include "gl/gpu_cloth.hpp"
#include "gl/shader.hpp"

namespace clothlab {

class gpu_cloth_compute {
 public:
  gpu_cloth_compute() = default;
  ~gpu_cloth_compute();
  gpu_cloth_compute(const gpu_cloth_compute&) = delete;
  gpu_cloth_compute& operator=(const gpu_cloth_compute&) = delete;

  // True when the current context has compute shaders (OpenGL 4.3); otherwise false with an
  // error naming the version it has.
  static bool available(std::string& error);
  // Everything of p that this path runs: gpu_cloth::supports' and XPBD; otherwise false with
  // error naming what it does not run.
  static bool supports(const cloth_parameters& p, std::string& error);

  // Uploads the cloth's current state (its torn springs included); false with a full-sentence error
  // when the context is older than 4.3 or a shader is missing or does not compile.
  bool load(const spring_mesh& cloth, std::string& error);
  bool is_loaded() const { return grid_size_ != 0; }
  // `count` steps, p as gpu_cloth::step's (the parameters at the loaded N; uniforms set once).
  // With speed_bound > 0 (m/s) every step is checked on the GPU (a counter per step of the
  // particles not finite or faster than the bound): returns the first step of the batch
  // (1..count) after which one was, 0 when none. Throws like gpu_cloth::step.
  int run(const cloth_parameters& p, int count = 1, double speed_bound = 0.0);
  // Copies the positions and velocities (widened to doubles) into cloth.particles() and
  // removes from cloth the springs torn on the GPU.
  void read_state(spring_mesh& cloth) const;
  // The current position and velocity of particle k = ku + N kv alone (the mouse grab's
  // read-back). Throws std::out_of_range for k outside the grid.
  particle_state read_particle(std::size_t k) const;
  int grid_size() const { return grid_size_; }
  // The buffers of the current state (one vec4 per particle, k = ku + N kv; positions' w: 1 if
  // pinned), e.g. for the window to copy into textures and draw without reading back.
  GLuint position_buffer() const { return position_[read_]; }
  // The normals of the current positions: computed here (one dispatch) unless a step's wind
  // needed them already; the steps compute them only for the wind.
  GLuint normal_buffer();
  GLuint spring_mask_buffer() const { return spring_mask_; }  // one uint per particle

 private:
  void release();
  // The normal pass: normal_ from position_[read_] (its program left in use).
  void compute_normals();
  // run's mass-spring steps (shaders/gpu_compute_step.comp), ping-pong.
  void run_mass_spring(const cloth_parameters& p, int count, bool check);
  // run's XPBD steps, in place in position_[read_] and velocity_[read_]; speed_bound as run's
  // (its counters bound).
  void run_xpbd(const cloth_parameters& p, int count, bool check);

  int grid_size_ = 0;
  std::array<float, 3> rest_length_{};
  shader_program step_program_;
  shader_program normal_program_;
  shader_program tear_program_;
  shader_program xpbd_predict_program_;  // XPBD's three passes
  shader_program xpbd_solve_program_;
  shader_program xpbd_velocity_program_;
  step_uniforms step_uniforms_;                 // step_program_'s
  std::array<step_uniforms, 3> xpbd_uniforms_;  // the XPBD passes', in the order above
  tear_uniform tear_uniform_;                   // tear_program_'s tear_length
  float sent_speed_bound_ = -1.0f;              // step_program_'s
  int read_ = 0;  // copy of positions/velocities holding the current state
  std::array<GLuint, 2> position_{};
  std::array<GLuint, 2> velocity_{};
  GLuint normal_ = 0;
  GLuint spring_mask_ = 0;  // one word per particle, updated in place by the tear pass
  // XPBD's: the motion of the substep so far, x - x_prev (vec4: kept apart from the positions,
  // which hold x_prev until the substep ends), the multipliers (6 floats a particle, one per
  // constraint from it as lower end) and F_ext of the step (vec4).
  GLuint xpbd_displacement_ = 0;
  GLuint xpbd_multiplier_ = 0;
  GLuint xpbd_external_force_ = 0;
  mutable std::vector<std::uint32_t> mask_readback_;
  bool normals_current_ = false;                // normal_ holds the normals of position_[read_]
  GLuint diverged_ = 0;                         // one counter per step of a checked batch
  GLsizeiptr diverged_capacity_ = 0;            // its size, bytes
  std::vector<std::uint32_t> diverged_counts_;  // their values, read back
  mutable std::vector<float> readback_;
};

}  // namespace clothlab
