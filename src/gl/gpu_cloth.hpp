// Handout section 5, questions 11 to 13: the cloth of spring_mesh simulated on the GPU with
// fragment shaders, in single precision, by exactly the model of docs/model.md.
//
// The spring mask (tearing, an addition): an N x N GL_R32UI texture whose texel (ku, kv) has bit
// i set while a spring joins the particle to its neighbour neighbour_offsets[i] (inside the grid,
// not torn). The tear pass writes it into the other copy of a ping-pong pair. A spring's two ends
// compute its length from the same two floats (|p_i - p_j| = |p_j - p_i| bitwise), so they agree
// on whether it tore.
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
#include "gl/shader.hpp"

namespace clothlab {

// The 12 neighbours a particle can be joined to (handout figure 6), in the order of the spring
// mask's bits and of the shaders' neighbours[] tables: (du, dv, family), family 0 structural,
// 1 shear, 2 bending.
inline constexpr int neighbour_count = 12;
inline constexpr std::array<std::array<int, 3>, neighbour_count> neighbour_offsets = {
    {{1, 0, 0},
     {-1, 0, 0},
     {0, 1, 0},
     {0, -1, 0},  // structural, h
     {1, 1, 1},
     {-1, -1, 1},
     {1, -1, 1},
     {-1, 1, 1},  // shear, h√2
     {2, 0, 2},
     {-2, 0, 2},
     {0, 2, 2},
     {0, -2, 2}}};  // bending, 2h

// The spring mask of the cloth (see above), one word per particle k = ku + N kv, into `masks`.
void spring_masks(const spring_mesh& cloth, std::vector<std::uint32_t>& masks);
// Removes from the cloth the springs that the mask says are torn (both paths' read_state).
void remove_torn_springs(std::span<const std::uint32_t> masks, spring_mesh& cloth);
// Both paths' read_particle(k): throws std::logic_error before a load (grid_size 0) and
// std::out_of_range when k is outside the N x N grid, naming `who`.
void check_particle_index(const char* who, int grid_size, std::size_t k);

// (1 + strain) L0 of the three families, the lengths beyond which their springs tear.
// L0 of the structural, shear and bending springs (h, h√2 and 2h), the GPU's uniforms: the
// distances in the initial flat cloth from s(0, 0) to s(1, 0), s(1, 1) and s(2, 0).
std::array<float, 3> family_rest_lengths(const spring_mesh& cloth);
std::array<float, 3> tear_lengths(double strain, const std::array<float, 3>& rest_length);

// The uniforms of one step of the model (shaders/gpu_step.frag, gpu_compute_step.comp): their
// locations, looked up once, and the values last sent, so that a batch sends nothing when the
// parameters have not changed since the last one.
class step_uniforms {
 public:
  // Looks the locations up in `program` (after it is linked); forgets the values sent.
  void locate(const shader_program& program);
  // Sets the uniforms for the cloth parameters p (effective: question 10's scaling applied) on
  // the program in use, the one located, unless they are those it already holds.
  void set(const cloth_parameters& p, int grid_size, const std::array<float, 3>& rest_length);

 private:
  struct values {
    int grid_size = 0;
    std::array<float, 3> stiffness{}, rest_length{};
    float time_step = 0, damping = 0, mass = 0, gravity = 0;
    int explicit_euler = 0;
    float wind_strength = 0;
    std::array<float, 3> wind_direction{};
    int drag_enabled = 0;
    std::array<int, 2> drag_texel{};
    std::array<float, 3> drag_target{};
    float drag_stiffness = 0;
    int sphere_enabled = 0;
    std::array<float, 3> sphere_centre{};
    float sphere_radius = 0, sphere_friction = 0;
    int ground_enabled = 0;
    float ground_height = 0, ground_friction = 0;
    bool operator==(const values&) const = default;
  };
  struct locations {
    GLint grid_size = -1, stiffness = -1, rest_length = -1, time_step = -1, damping = -1, mass = -1,
          gravity = -1, explicit_euler = -1, wind_strength = -1, wind_direction = -1,
          drag_enabled = -1, drag_texel = -1, drag_target = -1, drag_stiffness = -1,
          sphere_enabled = -1, sphere_centre = -1, sphere_radius = -1, sphere_friction = -1,
          ground_enabled = -1, ground_height = -1, ground_friction = -1;
  };
  locations at_;
  values sent_;
  bool sent_once_ = false;
};

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

  // The GPU path integrates with semi-implicit and explicit Euler (model.md) only. True when it
  // can run p's integrator; otherwise false with error naming the integrator.
  static bool supports_integrator(integrator_kind integrator, std::string& error);
  // Everything of p that the GPU paths run: their integrators, the drag, the sphere and
  // tearing; not self-collision (false, with error naming the option).
  static bool supports(const cloth_parameters& p, std::string& error);

  // Uploads the CPU cloth's CURRENT state (positions, velocities, pinned flags, the rest lengths
  // of its three spring families, its torn springs), so that a run can switch from CPU to GPU at
  // any step. Can be called again to load another state or size. On failure (grid too large,
  // GL_RGBA32F not renderable, a shader file missing or not compiling) returns false with a
  // full-sentence error and leaves the gpu_cloth unloaded.
  bool load(const spring_mesh& cloth, std::string& error);
  bool is_loaded() const { return grid_size_ != 0; }

  // One step of model.md with p's dynamics (dt, mu, m, g0, integrator), stiffnesses, wind and
  // ground. p's grid_size, side_length and pins are not read: they change the cloth only through
  // spring_mesh::load_model and a new load(). Throws std::logic_error before a successful load,
  // std::invalid_argument for an integrator that supports_integrator refuses.
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
  GLuint normal_texture() const { return normal_; }
  GLuint spring_mask_texture() const { return spring_mask_[mask_read_]; }  // GL_R32UI

 private:
  void release();
  void compute_normals();  // pass 2: normal_ from position_[read_]

  int grid_size_ = 0;
  std::array<float, 3> rest_length_{};  // L0 of the structural, shear, bending springs: h, h√2, 2h
  shader_program step_program_;
  shader_program normal_program_;
  shader_program tear_program_;              // pass 3, tearing
  shader_program check_program_;             // the divergence check (run)
  step_uniforms step_uniforms_;              // step_program_'s
  std::array<float, 3> sent_tear_length_{};  // the tear pass's last uniform value
  float sent_speed_bound_ = -1.0f;           // the check pass's
  std::vector<GLuint> queries_;              // one occlusion query per step of a checked batch
  GLuint empty_vertex_array_ = 0;            // the full-screen triangle needs no vertex data
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
};

}  // namespace clothlab
