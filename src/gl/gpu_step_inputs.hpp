// The inputs of one step that both GPU paths of the cloth (gpu_cloth, gpu_cloth_compute) build
// from the CPU cloth: the spring masks, the rest and tear lengths of the three families, and the
// step's uniforms.
//
// The spring mask (tearing, an addition): an N x N GL_R32UI texture (on the compute path a
// storage buffer, one word per particle) whose texel (ku, kv) has bit i set while a spring joins
// the particle to its neighbour neighbour_offsets[i] (inside the grid, not torn). The tear pass
// writes it into the other copy of a ping-pong pair. A spring's two ends compute its length from
// the same two floats (|p_i - p_j| = |p_j - p_i| bitwise), so they agree on whether it tore.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/grid_neighbours.hpp"  // neighbour_offsets: the spring mask's bits
#include "core/spring_mesh.hpp"
#include "gl/gl.hpp"
#include "gl/shader.hpp"

namespace clothlab {

// The spring mask of the cloth (see above), one word per particle k = ku + N kv, into `masks`.
void spring_masks(const spring_mesh& cloth, std::vector<std::uint32_t>& masks);
// Removes from the cloth the springs that the mask says are torn (both paths' read_state).
void remove_torn_springs(std::span<const std::uint32_t> masks, spring_mesh& cloth);

// (1 + strain) L0 of the three families, the lengths beyond which their springs tear.
// L0 of the structural, shear and bending springs (h, h√2 and 2h), the GPU's uniforms: the
// distances in the initial flat cloth from s(0, 0) to s(1, 0), s(1, 1) and s(2, 0).
std::array<float, 3> family_rest_lengths(const spring_mesh& cloth);
std::array<float, 3> tear_lengths(double strain, const std::array<float, 3>& rest_length);

// The tear pass's uniform tear_length ((1 + strain) L0 of each family, tear_lengths), sent to
// its program only when it changes.
class tear_uniform {
 public:
  void forget() { sent_ = {}; }  // after the program is linked again
  // Sets it on tear_program (which is then in use) unless the program already holds it.
  void set(const shader_program& tear_program, double strain,
           const std::array<float, 3>& rest_length);

 private:
  std::array<float, 3> sent_{};
};

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

}  // namespace clothlab
