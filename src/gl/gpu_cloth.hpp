// Handout section 5, questions 11 to 13: the cloth of spring_mesh simulated on the GPU with
// fragment shaders, in single precision, by exactly the model of docs/model.md.
//
// BEGIN TEACHER: question 11 asks the student to find this structure by reading the code
// Question 11, the structure. The state lives in N x N GL_RGBA32F textures, one texel per
// particle: texel (ku, kv) holds particle k = ku + N kv (the CPU's index).
//   position texture  xyz: p (m)      w: 1 if the particle is pinned (never moves), else 0
//   velocity texture  xyz: v (m/s)    w: 0
//   normal texture    xyz: n (unit)   w: 0, the normal of the CURRENT positions
// The shaders are fragment shaders: the CPU draws one triangle covering an N x N viewport, so
// that the fragment shader runs once per texel, i.e. once per particle, and writes that
// particle's new values. The cloth drawn on screen is a flat N x N grid sent once by the CPU; its
// vertex shader fetches each vertex's position and normal from these textures
// (renderer::draw_from_textures).
//
// One step, two full-screen passes (shaders/):
//   1. gpu_step.frag (questions 12, 13): reads position, velocity and normal; sums the forces of
//      the particle's own up to 12 springs (structural, shear, bending) and the wind, then runs
//      the integrator and the ground contact; writes the new position and the new velocity
//      (two render targets) into the other copy of each: positions and velocities ping-pong.
//   2. gpu_normal.frag: the normals of the new positions (central differences), so that the
//      renderer and the next step's wind see the normals of the current positions.
// Both use gpu_full_screen.vert.
// END TEACHER
//
// Every call needs the GL context current in which load() was called; destroy the gpu_cloth
// before that context. step() and read_state() leave the GL state they change (framebuffer
// bindings, viewport, program, textures, blending...) as they found it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "gl.hpp"
#include "shader.hpp"
#include "spring_mesh.hpp"

namespace clothlab {

// Sets the uniforms of one step of the model (shaders/gpu_step.frag, gpu_compute_step.comp) for
// the cloth parameters p (effective: question 10's scaling applied), on the program in use.
void set_step_uniforms(const shader_program& program, const cloth_parameters& p, int grid_size,
                       const std::array<float, 3>& rest_length);

class gpu_cloth {
 public:
  gpu_cloth() = default;
  ~gpu_cloth();
  gpu_cloth(const gpu_cloth&) = delete;
  gpu_cloth& operator=(const gpu_cloth&) = delete;

  // True when an N x N cloth fits the context's limits (GL_MAX_TEXTURE_SIZE,
  // GL_MAX_VIEWPORT_DIMS); otherwise false with error naming N and the limit.
  static bool check_grid_size(int grid_size, std::string& error);

  // The GPU path integrates with semi-implicit and explicit Euler (model.md) only. True when it
  // can run p's integrator; otherwise false with error naming the integrator.
  static bool supports_integrator(integrator_kind integrator, std::string& error);
  // Everything of p that the GPU path runs: its integrator, the drag and the sphere; not
  // tearing or self-collision (false, with error naming the option).
  static bool supports(const cloth_parameters& p, std::string& error);

  // Uploads the CPU cloth's CURRENT state (positions, velocities, pinned flags, the rest lengths
  // of its three spring families), so that a run can switch from CPU to GPU at any step. Can be
  // called again to load another state or size. On failure (grid too large, GL_RGBA32F not
  // renderable, a shader file missing or not compiling) returns false with a full-sentence error
  // and leaves the gpu_cloth unloaded.
  bool load(const spring_mesh& cloth, std::string& error);
  bool is_loaded() const { return grid_size_ != 0; }

  // One step of model.md with p's dynamics (dt, mu, m, g0, integrator), stiffnesses, wind and
  // ground. p's grid_size, side_length and pins are not read: they change the cloth only through
  // spring_mesh::load_model and a new load(). Throws std::logic_error before a successful load,
  // std::invalid_argument for an integrator that supports_integrator refuses.
  void step(const cloth_parameters& p);
  // `count` steps as one batch: the caller's GL state saved and the uniforms set once. With
  // speed_bound > 0 (m/s) every step is also checked on the GPU, without reading the state
  // back: an occlusion query counts the particles that are not finite or faster than the bound
  // (shaders/gpu_check.frag). Returns the first step of the batch (1..count) after which a
  // particle diverged, 0 when none did (or without the check). The state then is that of the
  // end of the batch.
  int run(const cloth_parameters& p, int count, double speed_bound = 0.0);

  // Runs `count` steps and returns the mean wall-clock seconds per step, with glFinish before
  // and after, so that the GPU's work is counted, not only its submission.
  double time_steps(const cloth_parameters& p, int count);

  // Copies the current positions and velocities (floats, widened to doubles) into
  // cloth.particles(), for --csv, --obj, --png and the GPU -> CPU switch (call
  // cloth.compute_normals() where its normals are needed). cloth must have this grid size (throws
  // std::invalid_argument otherwise).
  void read_state(spring_mesh& cloth) const;

  int grid_size() const { return grid_size_; }  // N of the last successful load, 0 before
  // The textures of the current state (they change at every step: ask after stepping).
  GLuint position_texture() const { return position_[read_]; }
  GLuint normal_texture() const { return normal_; }

 private:
  void release();
  void compute_normals();  // pass 2: normal_ from position_[read_]

  int grid_size_ = 0;
  std::array<float, 3> rest_length_{};  // L0 of the structural, shear, bending springs: h, h√2, 2h
  shader_program step_program_;
  shader_program normal_program_;
  shader_program check_program_;   // the divergence check (run)
  std::vector<GLuint> queries_;    // one occlusion query per step of a checked batch
  GLuint empty_vertex_array_ = 0;  // the full-screen triangle needs no vertex data

  // Ping-pong: copy read_ holds the current state, copy write_ receives the next one; they swap
  // after every step. framebuffer_[i] renders into position_[i] (attachment 0) and velocity_[i]
  // (attachment 1).
  int read_ = 0;
  int write_ = 1;
  std::array<GLuint, 2> position_{};
  std::array<GLuint, 2> velocity_{};
  std::array<GLuint, 2> framebuffer_{};
  mutable std::vector<float> readback_;  // read_state's RGBA texels, reused
  // The normals are computed from the positions alone, never from themselves: one copy suffices.
  GLuint normal_ = 0;
  GLuint normal_framebuffer_ = 0;
};

}  // namespace clothlab
