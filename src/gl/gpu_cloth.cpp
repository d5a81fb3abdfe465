#include "gl/gpu_cloth.hpp"
// BEGIN TEACHER: question 11 asks the student to find this structure by reading the code (it is
// written here, not in the header, so that the header compiles alike in the student copy and
// ccache shares the objects of every file that includes it)
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
// One step, two full-screen passes (shaders/), and a third when the cloth tears:
//   1. gpu_step.frag (questions 12, 13): reads position, velocity and normal; sums the forces of
//      the particle's own up to 12 springs (structural, shear, bending) and the wind, then runs
//      the integrator and the ground contact; writes the new position and the new velocity
//      (two render targets) into the other copy of each: positions and velocities ping-pong.
//   2. gpu_normal.frag: the normals of the new positions (central differences), so that the
//      renderer and the next step's wind see the normals of the current positions.
//   3. gpu_tear.frag (tearing, an addition, only with tear_strain > 0): the springs that the new
//      positions stretch beyond (1 + eps) L0 are removed from the spring mask.
// All use gpu_full_screen.vert.
// END TEACHER

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace clothlab {
namespace {

#if defined(CLOTHLAB_GL_WEB)
// WebGL2 has no polygon mode: triangles are always filled, there is nothing to save.
struct saved_polygon_mode {
  static void fill() {}
};
#else
// The polygon mode: a caller may be drawing in outline (GL_LINE); the passes fill.
class saved_polygon_mode {
 public:
  saved_polygon_mode() { glGetIntegerv(GL_POLYGON_MODE, mode_.data()); }
  ~saved_polygon_mode() { glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(mode_[0])); }
  saved_polygon_mode(const saved_polygon_mode&) = delete;
  saved_polygon_mode& operator=(const saved_polygon_mode&) = delete;
  static void fill() { glPolygonMode(GL_FRONT_AND_BACK, GL_FILL); }

 private:
  std::array<GLint, 2> mode_{GL_FILL, GL_FILL};
};
#endif

// The GL state that the GPU passes change, saved on construction and restored on destruction,
// so that the renderer's drawing around a step is not disturbed.
class saved_gl_state {
 public:
  saved_gl_state() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
    glGetIntegerv(GL_VIEWPORT, viewport_.data());
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
    for (GLuint unit = 0; unit < texture_units; ++unit) {
      glActiveTexture(GL_TEXTURE0 + unit);
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_[unit]);
    }
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pixel_pack_buffer_);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &pixel_unpack_buffer_);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);  // glReadPixels and glTexImage2D use client memory
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    for (std::size_t i = 0; i < capabilities.size(); ++i) {
      enabled_[i] = glIsEnabled(capabilities[i]);
    }
  }
  ~saved_gl_state() {
    for (std::size_t i = 0; i < capabilities.size(); ++i) {
      if (enabled_[i] == GL_TRUE) {
        glEnable(capabilities[i]);
      } else {
        glDisable(capabilities[i]);
      }
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pixel_pack_buffer_));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(pixel_unpack_buffer_));
    for (GLuint unit = 0; unit < texture_units; ++unit) {
      glActiveTexture(GL_TEXTURE0 + unit);
      glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(texture_[unit]));
    }
    glActiveTexture(static_cast<GLenum>(active_texture_));
    glBindVertexArray(static_cast<GLuint>(vertex_array_));
    glUseProgram(static_cast<GLuint>(program_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_framebuffer_));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_framebuffer_));
  }
  saved_gl_state(const saved_gl_state&) = delete;
  saved_gl_state& operator=(const saved_gl_state&) = delete;

  // For the passes: every fragment written as computed, no blending, culling or testing.
  static void set_pass_state() {
    for (GLenum capability : capabilities)
      glDisable(capability);
    saved_polygon_mode::fill();
  }

  static constexpr GLuint texture_units = 4;  // the passes read at most four textures

 private:
  static constexpr std::array<GLenum, 5> capabilities = {GL_BLEND, GL_CULL_FACE, GL_DEPTH_TEST,
                                                         GL_SCISSOR_TEST, GL_STENCIL_TEST};
  GLint draw_framebuffer_ = 0;
  GLint read_framebuffer_ = 0;
  std::array<GLint, 4> viewport_{};
  GLint program_ = 0;
  GLint vertex_array_ = 0;
  GLint active_texture_ = GL_TEXTURE0;
  std::array<GLint, texture_units> texture_{};
  [[maybe_unused]] saved_polygon_mode polygon_mode_;  // saved and restored by itself
  GLint pixel_pack_buffer_ = 0;
  GLint pixel_unpack_buffer_ = 0;
  std::array<GLboolean, capabilities.size()> enabled_{};
};

// An N x N texture read with texelFetch (nearest filtering, no mipmaps), filled from `data`.
GLuint create_grid_texture(int n, GLint internal_format, GLenum format, GLenum type,
                           const void* data) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, internal_format, n, n, 0, format, type, data);
  return texture;
}

// An N x N GL_RGBA32F texture holding `texels` (4 floats per texel, texel (ku, kv) at
// 4 (ku + N kv)).
GLuint create_state_texture(int n, const std::vector<float>& texels) {
  return create_grid_texture(n, GL_RGBA32F, GL_RGBA, GL_FLOAT, texels.data());
}

// The N x N GL_R32UI spring mask (gpu_cloth.hpp), texel (ku, kv) = masks[ku + N kv].
GLuint create_mask_texture(int n, const std::vector<std::uint32_t>& masks) {
  return create_grid_texture(n, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, masks.data());
}

// A framebuffer rendering into `targets` (attachment i = targets[i]); 0 and an error if the
// driver cannot render into them.
GLuint create_framebuffer(std::initializer_list<GLuint> targets, std::string& error) {
  GLuint framebuffer = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  std::vector<GLenum> draw_buffers;
  for (GLuint texture : targets) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(draw_buffers.size());
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, texture, 0);
    draw_buffers.push_back(attachment);
  }
  glDrawBuffers(static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char status_hex[16];
    std::snprintf(status_hex, sizeof status_hex, "0x%04X", status);
    error =
        "the GPU cloth needs to render into GL_RGBA32F and GL_R32UI textures, which this "
        "OpenGL driver refuses (framebuffer status " +
        std::string(status_hex) + ")";
    glDeleteFramebuffers(1, &framebuffer);
    return 0;
  }
  return framebuffer;
}

void bind_texture(GLuint unit, GLuint texture) {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, texture);
}

// Runs the bound program once per texel of the bound N x N framebuffer.
void draw_full_screen_pass(int n) {
  glViewport(0, 0, n, n);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Reads one texel (x, y) of attachment `attachment` of `framebuffer` into 4 floats, leaving the
// caller's read framebuffer and pixel pack buffer bound as they were.
void read_texel(GLuint framebuffer, GLenum attachment, int x, int y, float* rgba) {
  GLint read_framebuffer = 0, pixel_pack_buffer = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pixel_pack_buffer);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glReadBuffer(attachment);
  glReadPixels(x, y, 1, 1, GL_RGBA, GL_FLOAT, rgba);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_framebuffer));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pixel_pack_buffer));
}

#if defined(CLOTHLAB_GL_WEB)
// The web build's divergence check (gpu_cloth::run): whether one of the first `pending` queries,
// issued by an earlier batch, found a diverged particle. Reads them only once all their results
// are in, and then sets pending to 0; false while they are not.
bool read_pending_checks(const std::vector<GLuint>& queries, int& pending) {
  const auto count = static_cast<std::size_t>(pending);
  for (std::size_t s = 0; s < count; ++s) {
    GLuint available = GL_FALSE;
    glGetQueryObjectuiv(queries[s], GL_QUERY_RESULT_AVAILABLE, &available);
    if (available == GL_FALSE)
      return false;
  }
  bool diverged = false;
  for (std::size_t s = 0; s < count; ++s) {
    GLuint any_sample = 0;
    glGetQueryObjectuiv(queries[s], GL_QUERY_RESULT, &any_sample);
    diverged = diverged || any_sample != 0;
  }
  pending = 0;
  return diverged;
}
#endif

// The bit of the offset (du, dv) in a mask: its index in neighbour_offsets. Every spring joins
// neighbours of the table.
int neighbour_bit(int du, int dv) {
  for (int bit = 0; bit < neighbour_count; ++bit) {
    const auto& offset = neighbour_offsets[static_cast<std::size_t>(bit)];
    if (offset[0] == du && offset[1] == dv)
      return bit;
  }
  throw std::logic_error("neighbour_bit: (" + std::to_string(du) + ", " + std::to_string(dv) +
                         ") is not a neighbour of the spring table");
}

}  // namespace

void spring_masks(const spring_mesh& cloth, std::vector<std::uint32_t>& masks) {
  const auto n = static_cast<std::uint32_t>(cloth.grid_size());
  masks.assign(static_cast<std::size_t>(n) * n, 0u);
  // Each spring of the cloth's lists (the intact ones) sets its bit at both of its ends.
  for (spring_family family : all_spring_families) {
    for (const spring& s : cloth.springs(family)) {
      const int du = static_cast<int>(s.b % n) - static_cast<int>(s.a % n);
      const int dv = static_cast<int>(s.b / n) - static_cast<int>(s.a / n);
      masks[s.a] |= 1u << neighbour_bit(du, dv);
      masks[s.b] |= 1u << neighbour_bit(-du, -dv);
    }
  }
}

std::array<float, 3> family_rest_lengths(const spring_mesh& cloth) {
  const int n = cloth.grid_size();
  const std::span<const double> x0 = cloth.rest_positions();
  // |x0(0, 0) - x0(du, dv)| for the first spring of each family; N = 2 has no bending spring
  // (none of its texels uses that length).
  const auto distance = [&](int du, int dv) {
    const std::size_t b = 3 * spring_mesh::index(std::min(du, n - 1), dv, n);
    return static_cast<float>(
        glm::length(glm::dvec3(x0[0], x0[1], x0[2]) - glm::dvec3(x0[b], x0[b + 1], x0[b + 2])));
  };
  return {distance(1, 0), distance(1, 1), distance(2, 0)};
}

void remove_torn_springs(std::span<const std::uint32_t> masks, spring_mesh& cloth) {
  const auto n = static_cast<std::uint32_t>(cloth.grid_size());
  // The bit of the spring from a to b in a's mask (both ends agree: the GPU tears both at once).
  const auto bit_of = [n](const spring& s) {
    return neighbour_bit(static_cast<int>(s.b % n) - static_cast<int>(s.a % n),
                         static_cast<int>(s.b / n) - static_cast<int>(s.a / n));
  };
  cloth.remove_springs_if([&](const spring& s) {
    const int i = bit_of(s);
    return (masks[s.a] & (1u << i)) == 0u;
  });
}

std::array<float, 3> tear_lengths(double strain, const std::array<float, 3>& rest_length) {
  std::array<float, 3> lengths{};
  for (std::size_t family = 0; family < 3; ++family)
    lengths[family] = static_cast<float>((1.0 + strain) * rest_length[family]);
  return lengths;
}

void step_uniforms::locate(const shader_program& program) {
  const auto at = [&](const char* name) { return program.uniform(name); };
  at_ = {.grid_size = at("grid_size"),
         .stiffness = at("stiffness"),
         .rest_length = at("rest_length"),
         .time_step = at("time_step"),
         .damping = at("damping"),
         .mass = at("mass"),
         .gravity = at("gravity"),
         .explicit_euler = at("explicit_euler"),
         .wind_strength = at("wind_strength"),
         .wind_direction = at("wind_direction"),
         .drag_enabled = at("drag_enabled"),
         .drag_texel = at("drag_texel"),
         .drag_target = at("drag_target"),
         .drag_stiffness = at("drag_stiffness"),
         .sphere_enabled = at("sphere_enabled"),
         .sphere_centre = at("sphere_centre"),
         .sphere_radius = at("sphere_radius"),
         .sphere_friction = at("sphere_friction"),
         .ground_enabled = at("ground_enabled"),
         .ground_height = at("ground_height"),
         .ground_friction = at("ground_friction")};
  sent_once_ = false;
}

void step_uniforms::set(const cloth_parameters& p, int grid_size,
                        const std::array<float, 3>& rest_length) {
  const auto f = [](double x) { return static_cast<float>(x); };
  const auto f3 = [](const glm::dvec3& x) {
    return std::array<float, 3>{static_cast<float>(x.x), static_cast<float>(x.y),
                                static_cast<float>(x.z)};
  };
  const dynamics_parameters& d = p.dynamics;
  // u_w, unit. K_w = 0 means no wind at all, as on the CPU, whatever u_w (even a zero one).
  const glm::dvec3 wind_unit =
      p.wind_strength != 0.0 ? p.wind_direction / glm::length(p.wind_direction) : glm::dvec3(0.0);
  const bool drag = p.drag.enabled && p.drag.ku >= 0 && p.drag.ku < grid_size && p.drag.kv >= 0 &&
                    p.drag.kv < grid_size;
  const values v = {
      .grid_size = grid_size,
      .stiffness = {f(p.structural_stiffness), f(p.shear_stiffness), f(p.bending_stiffness)},
      .rest_length = rest_length,
      .time_step = f(d.time_step),
      .damping = f(d.damping),
      .mass = f(d.mass),
      .gravity = f(d.gravity),
      .explicit_euler = d.integrator == integrator_kind::explicit_euler,
      .wind_strength = f(p.wind_strength),
      .wind_direction = f3(wind_unit),
      .drag_enabled = drag,
      .drag_texel = {p.drag.ku, p.drag.kv},
      .drag_target = f3(p.drag.target),
      .drag_stiffness = f(p.drag.stiffness),
      .sphere_enabled = p.sphere.enabled,
      .sphere_centre = f3(p.sphere.centre),
      .sphere_radius = f(p.sphere.radius),
      .sphere_friction = f(p.sphere.friction),
      .ground_enabled = p.ground_enabled,
      .ground_height = f(p.ground_height),
      .ground_friction = f(p.ground_friction)};
  if (sent_once_ && v == sent_)
    return;  // the program still holds them
  glUniform1i(at_.grid_size, v.grid_size);
  glUniform3fv(at_.stiffness, 1, v.stiffness.data());
  glUniform3fv(at_.rest_length, 1, v.rest_length.data());
  glUniform1f(at_.time_step, v.time_step);
  glUniform1f(at_.damping, v.damping);
  glUniform1f(at_.mass, v.mass);
  glUniform1f(at_.gravity, v.gravity);
  glUniform1i(at_.explicit_euler, v.explicit_euler);
  glUniform1f(at_.wind_strength, v.wind_strength);
  glUniform3fv(at_.wind_direction, 1, v.wind_direction.data());
  glUniform1i(at_.drag_enabled, v.drag_enabled);
  glUniform2iv(at_.drag_texel, 1, v.drag_texel.data());
  glUniform3fv(at_.drag_target, 1, v.drag_target.data());
  glUniform1f(at_.drag_stiffness, v.drag_stiffness);
  glUniform1i(at_.sphere_enabled, v.sphere_enabled);
  glUniform3fv(at_.sphere_centre, 1, v.sphere_centre.data());
  glUniform1f(at_.sphere_radius, v.sphere_radius);
  glUniform1f(at_.sphere_friction, v.sphere_friction);
  glUniform1i(at_.ground_enabled, v.ground_enabled);
  glUniform1f(at_.ground_height, v.ground_height);
  glUniform1f(at_.ground_friction, v.ground_friction);
  sent_ = v;
  sent_once_ = true;
}

gpu_cloth::~gpu_cloth() {
  release();
  if (empty_vertex_array_ != 0)
    glDeleteVertexArrays(1, &empty_vertex_array_);
  if (!queries_.empty())
    glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
}

void gpu_cloth::release() {
  grid_size_ = 0;
  if (position_[0] == 0)
    return;  // nothing created (load creates the textures first)
  glDeleteFramebuffers(2, framebuffer_.data());
  glDeleteFramebuffers(2, mask_framebuffer_.data());
  glDeleteFramebuffers(1, &normal_framebuffer_);
  glDeleteTextures(2, position_.data());
  glDeleteTextures(2, velocity_.data());
  glDeleteTextures(2, spring_mask_.data());
  glDeleteTextures(1, &normal_);
  framebuffer_ = {};
  mask_framebuffer_ = {};
  position_ = {};
  velocity_ = {};
  spring_mask_ = {};
  normal_framebuffer_ = 0;
  normal_ = 0;
}

bool gpu_cloth::check_grid_size(int grid_size, std::string& error) {
  GLint max_texture_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size);
  std::array<GLint, 2> max_viewport{};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_viewport.data());
  const std::string n = "grid size N=" + std::to_string(grid_size);
  if (grid_size < 2) {
    error = n + ": must be at least 2";
    return false;
  }
  if (grid_size > max_texture_size) {
    error = n + ": too large for the GPU cloth, whose N x N textures are limited to " +
            std::to_string(max_texture_size) + " texels a side here (GL_MAX_TEXTURE_SIZE)";
    return false;
  }
  if (grid_size > max_viewport[0] || grid_size > max_viewport[1]) {
    error = n + ": too large for the GPU cloth, whose N x N passes are limited to " +
            std::to_string(max_viewport[0]) + " x " + std::to_string(max_viewport[1]) +
            " pixels here (GL_MAX_VIEWPORT_DIMS)";
    return false;
  }
  return true;
}

bool gpu_cloth::supports_integrator(integrator_kind integrator, std::string& error) {
  if (integrator == integrator_kind::semi_implicit ||
      integrator == integrator_kind::explicit_euler) {
    return true;
  }
  error = "integrator " + std::string(integrator_name(integrator)) +
          ": the GPU path runs semi-implicit or explicit only";
  return false;
}

bool gpu_cloth::supports(const cloth_parameters& p, std::string& error) {
  if (!supports_integrator(p.dynamics.integrator, error))
    return false;
  if (p.self_collision_thickness > 0.0) {
    error = "self-collision (--self-collision " + std::to_string(p.self_collision_thickness) +
            "): the GPU paths have no self-collision; run the cloth on the CPU";
    return false;
  }
  return true;
}

bool gpu_cloth::load(const spring_mesh& cloth, std::string& error) {
  release();
  const int n = cloth.grid_size();
  if (!check_grid_size(n, error))
    return false;
  saved_gl_state saved;  // the caller's GL state, restored on return
  if (step_program_.id() == 0) {
    if (!step_program_.load("gpu_full_screen.vert", "gpu_step.frag", error))
      return false;
    step_program_.use();  // the samplers' units, once: they never change
    glUniform1i(step_program_.uniform("position_texture"), 0);
    glUniform1i(step_program_.uniform("velocity_texture"), 1);
    glUniform1i(step_program_.uniform("normal_texture"), 2);
    glUniform1i(step_program_.uniform("spring_mask_texture"), 3);
    step_uniforms_.locate(step_program_);
  }
  if (normal_program_.id() == 0) {
    if (!normal_program_.load("gpu_full_screen.vert", "gpu_normal.frag", error))
      return false;
    normal_program_.use();
    glUniform1i(normal_program_.uniform("position_texture"), 0);
  }
  if (tear_program_.id() == 0) {
    if (!tear_program_.load("gpu_full_screen.vert", "gpu_tear.frag", error))
      return false;
    tear_program_.use();
    glUniform1i(tear_program_.uniform("position_texture"), 0);
    glUniform1i(tear_program_.uniform("spring_mask_texture"), 3);
    sent_tear_length_ = {};
  }
  if (check_program_.id() == 0) {
    if (!check_program_.load("gpu_full_screen.vert", "gpu_check.frag", error))
      return false;
    check_program_.use();
    glUniform1i(check_program_.uniform("position_texture"), 0);
    glUniform1i(check_program_.uniform("velocity_texture"), 1);
    sent_speed_bound_ = -1.0f;
  }
  if (empty_vertex_array_ == 0)
    glGenVertexArrays(1, &empty_vertex_array_);

  rest_length_ = family_rest_lengths(cloth);

  // The CPU state as texels: texel (ku, kv) = particle k = ku + N kv, 4 floats each.
  const particle_system& particles = cloth.particles();
  const std::size_t count = particles.size();
  std::vector<float> positions(4 * count);
  std::vector<float> velocities(4 * count);
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t c = 0; c < 3; ++c) {
      positions[4 * k + c] = static_cast<float>(particles.position[3 * k + c]);
      velocities[4 * k + c] = static_cast<float>(particles.velocity[3 * k + c]);
    }
    positions[4 * k + 3] = particles.is_fixed[k] ? 1.0f : 0.0f;  // w: pinned
    velocities[4 * k + 3] = 0.0f;
  }
  std::vector<std::uint32_t> masks;
  spring_masks(cloth, masks);  // the springs the CPU cloth still has

  for (std::size_t copy = 0; copy < 2; ++copy) {
    position_[copy] = create_state_texture(n, positions);
    velocity_[copy] = create_state_texture(n, velocities);
    spring_mask_[copy] = create_mask_texture(n, masks);
  }
  normal_ = create_state_texture(n, std::vector<float>(4 * count, 0.0f));
  for (std::size_t copy = 0; copy < 2; ++copy) {
    framebuffer_[copy] = create_framebuffer({position_[copy], velocity_[copy]}, error);
    mask_framebuffer_[copy] =
        framebuffer_[copy] == 0 ? 0 : create_framebuffer({spring_mask_[copy]}, error);
    if (mask_framebuffer_[copy] == 0) {
      release();
      return false;
    }
  }
  normal_framebuffer_ = create_framebuffer({normal_}, error);
  if (normal_framebuffer_ == 0) {
    release();
    return false;
  }
  read_ = 0;
  write_ = 1;
  mask_read_ = 0;
  pending_checks_ = 0;  // those of another state
  grid_size_ = n;
  normal_program_.use();
  glUniform1i(normal_program_.uniform("grid_size"), n);
  compute_normals();
  return true;
}

void gpu_cloth::compute_normals() {
  glBindFramebuffer(GL_FRAMEBUFFER, normal_framebuffer_);
  normal_program_.use();
  bind_texture(0, position_[read_]);
  glBindVertexArray(empty_vertex_array_);
  saved_gl_state::set_pass_state();
  draw_full_screen_pass(grid_size_);
}

void gpu_cloth::step(const cloth_parameters& p) {
  run(p, 1);
}

int gpu_cloth::run(const cloth_parameters& given, int count, double speed_bound) {
  // The mass and stiffnesses the simulation really uses (question 10's resolution mode), for
  // the grid that is loaded.
  cloth_parameters resolved = given;
  resolved.grid_size = grid_size_;
  const cloth_parameters p = effective_cloth_parameters(resolved);
  if (!is_loaded())
    throw std::logic_error("gpu_cloth::step called before a successful load");
  if (std::string error; !supports(p, error))
    throw std::invalid_argument("gpu_cloth::step: " + error);
  if (count < 1)
    return 0;
  // Once per batch: the caller's GL state saved, the uniforms that changed set (the samplers'
  // units and the normal pass's N were set by load).
  saved_gl_state saved;
  saved_gl_state::set_pass_state();
  glBindVertexArray(empty_vertex_array_);

  step_program_.use();
  step_uniforms_.set(p, grid_size_, rest_length_);
  const bool tear = p.tear_strain > 0.0;
  if (tear) {
    const std::array<float, 3> tear_length = tear_lengths(p.tear_strain, rest_length_);
    if (tear_length != sent_tear_length_) {
      tear_program_.use();
      glUniform3fv(tear_program_.uniform("tear_length"), 1, tear_length.data());
      sent_tear_length_ = tear_length;
    }
  }
  bool check = speed_bound > 0.0;
#if defined(CLOTHLAB_GL_WEB)
  // WebGL2 gives a query's result only once the browser's current task (this frame) has ended,
  // never to a program that waits for it. So on the web a batch's checks are read by a later
  // batch, which reports a divergence they found as after its own last step (a diverged cloth
  // stays so: a NaN stays a NaN); while they are pending, a batch is not checked. The desktop
  // reads each batch's own checks at its end.
  const bool earlier_batch_diverged = check && read_pending_checks(queries_, pending_checks_);
  check = check && pending_checks_ == 0 && !earlier_batch_diverged;
#endif
  if (check) {
    const auto bound = static_cast<float>(std::min(speed_bound, 1e30));
    if (bound != sent_speed_bound_) {
      check_program_.use();
      glUniform1f(check_program_.uniform("speed_bound"), bound);
      sent_speed_bound_ = bound;
    }
    while (queries_.size() < static_cast<std::size_t>(count)) {
      GLuint query = 0;
      glGenQueries(1, &query);
      queries_.push_back(query);
    }
  }

  for (int s = 0; s < count; ++s) {
    // Pass 1: forces, integrator and contacts, from copy read_ into copy write_.
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_[write_]);
    step_program_.use();
    bind_texture(0, position_[read_]);
    bind_texture(1, velocity_[read_]);
    bind_texture(2, normal_);  // the normals of the positions at the start of the step
    bind_texture(3, spring_mask_[mask_read_]);  // the springs not torn
    draw_full_screen_pass(grid_size_);

    // Ping-pong: the copy just written becomes the current state, the old one the next target.
    std::swap(read_, write_);

    // Pass 2: the normals of the new positions, for the renderer and the next step's wind.
    glBindFramebuffer(GL_FRAMEBUFFER, normal_framebuffer_);
    normal_program_.use();
    bind_texture(0, position_[read_]);
    draw_full_screen_pass(grid_size_);

    // Pass 3 (tearing, last in the step): the springs the new positions overstretch are
    // removed, from mask copy mask_read_ into the other one, which becomes the current one.
    if (tear) {
      glBindFramebuffer(GL_FRAMEBUFFER, mask_framebuffer_[1 - mask_read_]);
      tear_program_.use();
      bind_texture(0, position_[read_]);
      bind_texture(3, spring_mask_[mask_read_]);
      draw_full_screen_pass(grid_size_);
      mask_read_ = 1 - mask_read_;
    }

    // The divergence check of this step: a query says whether any fragment (particle) passed,
    // read after the batch. Nothing is written; the target is a float one, the type of the
    // shader's output (WebGL refuses a draw whose output and target types differ).
    if (check) {
      glBindFramebuffer(GL_FRAMEBUFFER, normal_framebuffer_);
      check_program_.use();
      bind_texture(0, position_[read_]);
      bind_texture(1, velocity_[read_]);
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glBeginQuery(GL_ANY_SAMPLES_PASSED, queries_[static_cast<std::size_t>(s)]);
      draw_full_screen_pass(grid_size_);
      glEndQuery(GL_ANY_SAMPLES_PASSED);
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
  }
#if defined(CLOTHLAB_GL_WEB)
  if (check)
    pending_checks_ = count;
  return earlier_batch_diverged ? count : 0;
#else
  if (check) {
    for (int s = 0; s < count; ++s) {
      GLuint diverged = 0;
      glGetQueryObjectuiv(queries_[static_cast<std::size_t>(s)], GL_QUERY_RESULT, &diverged);
      if (diverged != 0)
        return s + 1;
    }
  }
  return 0;
#endif
}

double gpu_cloth::time_steps(const cloth_parameters& p, int count) {
  if (count < 1)
    return 0.0;
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < count; ++i)
    step(p);
  glFinish();
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  return elapsed.count() / count;
}

void gpu_cloth::read_state(spring_mesh& cloth) const {
  if (!is_loaded())
    throw std::logic_error("gpu_cloth::read_state called before a successful load");
  if (cloth.grid_size() != grid_size_) {
    throw std::invalid_argument(
        "gpu_cloth::read_state: the CPU cloth has N=" + std::to_string(cloth.grid_size()) +
        ", the GPU cloth N=" + std::to_string(grid_size_));
  }
  saved_gl_state saved;
  const std::size_t count = static_cast<std::size_t>(grid_size_) * grid_size_;
  std::vector<float>& texels = readback_;  // kept between calls: no allocation per read
  texels.resize(4 * count);
  particle_system& particles = cloth.particles();
  const auto read_attachment = [&](GLenum attachment, std::vector<double>& into) {
    glReadBuffer(attachment);
    glReadPixels(0, 0, grid_size_, grid_size_, GL_RGBA, GL_FLOAT, texels.data());
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t c = 0; c < 3; ++c)
        into[3 * k + c] = texels[4 * k + c];
    }
  };
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_[read_]);
  read_attachment(GL_COLOR_ATTACHMENT0, particles.position);
  read_attachment(GL_COLOR_ATTACHMENT1, particles.velocity);

  // The springs torn on the GPU leave the CPU cloth too. The mask is read as RGBA (OpenGL ES
  // reads an integer target only so): its word k is texel k's red.
  mask_readback_.resize(4 * count);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, mask_framebuffer_[mask_read_]);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, grid_size_, grid_size_, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
               mask_readback_.data());
  for (std::size_t k = 0; k < count; ++k)
    mask_readback_[k] = mask_readback_[4 * k];
  mask_readback_.resize(count);
  remove_torn_springs(mask_readback_, cloth);
}

void check_particle_index(const char* who, int grid_size, std::size_t k) {
  if (grid_size == 0)
    throw std::logic_error(std::string(who) + " called before a successful load");
  const auto n = static_cast<std::size_t>(grid_size);
  if (k >= n * n) {
    throw std::out_of_range(std::string(who) + ": particle k=" + std::to_string(k) +
                            " is outside the " + std::to_string(n) + " x " + std::to_string(n) +
                            " grid");
  }
}

particle_state gpu_cloth::read_particle(std::size_t k) const {
  check_particle_index("gpu_cloth::read_particle", is_loaded() ? grid_size_ : 0, k);
  const auto n = static_cast<std::size_t>(grid_size_);
  const int ku = static_cast<int>(k % n), kv = static_cast<int>(k / n);
  std::array<float, 4> position{}, velocity{};
  read_texel(framebuffer_[read_], GL_COLOR_ATTACHMENT0, ku, kv, position.data());
  read_texel(framebuffer_[read_], GL_COLOR_ATTACHMENT1, ku, kv, velocity.data());
  return {glm::dvec3(position[0], position[1], position[2]),
          glm::dvec3(velocity[0], velocity[1], velocity[2])};
}

}  // namespace clothlab
