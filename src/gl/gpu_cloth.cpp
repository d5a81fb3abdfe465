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
// One step, one full-screen pass (shaders/), a second for the normals when they are used, and a
// third when the cloth tears:
//   1. gpu_step.frag (questions 12, 13): reads position, velocity and normal; sums the forces of
//      the particle's own up to 12 springs (structural, shear, bending) and the wind, then runs
//      the integrator and the ground contact; writes the new position and the new velocity
//      (two render targets) into the other copy of each: positions and velocities ping-pong.
//   2. gpu_normal.frag: the normals of the current positions (central differences), run only
//      when they are used: before a step with wind (its force needs them), and when
//      normal_texture() is asked for (the renderer, once per drawn frame).
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

#include "core/i18n.hpp"
#include "gl/gl_state_guard.hpp"
#include "gl/grid_textures.hpp"

namespace clothlab {

#if defined(CLOTHLAB_GL_WEB)
namespace {

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
}  // namespace
#endif

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
  if (grid_size < 2) {
    error = format(tr("grid size N=%d: must be at least 2"), grid_size);
    return false;
  }
  if (grid_size > max_texture_size) {
    error = format(tr("grid size N=%d: too large for the GPU cloth, whose N x N textures are "
                      "limited to %d texels a side here (GL_MAX_TEXTURE_SIZE)"),
                   grid_size, max_texture_size);
    return false;
  }
  if (grid_size > max_viewport[0] || grid_size > max_viewport[1]) {
    error = format(tr("grid size N=%d: too large for the GPU cloth, whose N x N passes are "
                      "limited to %d x %d pixels here (GL_MAX_VIEWPORT_DIMS)"),
                   grid_size, max_viewport[0], max_viewport[1]);
    return false;
  }
  return true;
}

bool gpu_cloth::supports_integrator(integrator_kind integrator, std::string& error) {
  if (integrator == integrator_kind::semi_implicit ||
      integrator == integrator_kind::explicit_euler) {
    return true;
  }
  if (integrator == integrator_kind::xpbd) {
    error =
        tr("integrator xpbd: the fragment GPU path runs the mass-spring integrators "
           "(semi-implicit and explicit) only; XPBD runs on GPU compute");
    return false;
  }
  error = format(tr("integrator %s: the GPU path runs semi-implicit or explicit only"),
                 std::string(integrator_name(integrator)).c_str());
  return false;
}

bool gpu_cloth::supports(const cloth_parameters& p, std::string& error) {
  return supports_integrator(p.dynamics.integrator, error) && supports_contacts(p, error);
}

bool gpu_cloth::supports_contacts(const cloth_parameters& p, std::string& error) {
  if (p.self_collision_thickness > 0.0) {
    error = format(tr("self-collision (--self-collision %s): the GPU paths have no "
                      "self-collision; run the cloth on the CPU"),
                   std::to_string(p.self_collision_thickness).c_str());
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
    tear_uniform_.forget();
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
  normals_current_ = false;
  grid_size_ = n;
  normal_program_.use();
  glUniform1i(normal_program_.uniform("grid_size"), n);
  return true;
}

void gpu_cloth::compute_normals() {
  glBindFramebuffer(GL_FRAMEBUFFER, normal_framebuffer_);
  normal_program_.use();
  bind_texture(0, position_[read_]);
  draw_full_screen_pass();
  normals_current_ = true;
}

GLuint gpu_cloth::normal_texture() {
  if (is_loaded() && !normals_current_) {
    saved_gl_state saved;
    saved_gl_state::set_pass_state();
    glBindVertexArray(empty_vertex_array_);
    glViewport(0, 0, grid_size_, grid_size_);
    compute_normals();
  }
  return normal_;
}

void gpu_cloth::step(const cloth_parameters& p) {
  run(p, 1);
}

int gpu_cloth::run(const cloth_parameters& p, int count, double speed_bound) {
  if (!is_loaded())
    throw std::logic_error("gpu_cloth::step called before a successful load");
  check_effective(p, "gpu_cloth::step");
  if (std::string error; !supports(p, error))
    throw std::invalid_argument("gpu_cloth::step: " + error);
  if (count < 1)
    return 0;
  // Once per batch: the caller's GL state saved, the state every pass shares set (the N x N
  // viewport, the normals on unit 2, the spring mask on unit 3), the uniforms that changed set
  // (the samplers' units and the normal pass's N were set by load).
  saved_gl_state saved;
  saved_gl_state::set_pass_state();
  glBindVertexArray(empty_vertex_array_);
  glViewport(0, 0, grid_size_, grid_size_);
  bind_texture(2, normal_);
  bind_texture(3, spring_mask_[mask_read_]);

  step_program_.use();
  step_uniforms_.set(p, grid_size_, rest_length_);
  const bool wind = p.wind_strength != 0.0;  // the only force that needs the normals
  const bool tear = p.tear_strain > 0.0;
  if (tear)
    tear_uniform_.set(tear_program_, p.tear_strain, rest_length_);
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
  // Only one pass per step without wind, tearing or check: its program stays in use.
  const bool one_pass = !wind && !tear && !check;
  step_program_.use();

  for (int s = 0; s < count; ++s) {
    // Pass 2 of the previous step, when this step's wind needs it: the normals of the current
    // positions.
    if (wind && !normals_current_)
      compute_normals();

    // Pass 1: forces, integrator and contacts, from copy read_ into copy write_.
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_[write_]);
    if (!one_pass)
      step_program_.use();
    bind_texture(0, position_[read_]);
    bind_texture(1, velocity_[read_]);
    draw_full_screen_pass();

    // Ping-pong: the copy just written becomes the current state, the old one the next target.
    std::swap(read_, write_);
    normals_current_ = false;  // they are those of the old positions

    // Pass 3 (tearing, last in the step): the springs the new positions overstretch are
    // removed, from mask copy mask_read_ into the other one, which becomes the current one.
    if (tear) {
      glBindFramebuffer(GL_FRAMEBUFFER, mask_framebuffer_[1 - mask_read_]);
      tear_program_.use();
      bind_texture(0, position_[read_]);
      draw_full_screen_pass();
      mask_read_ = 1 - mask_read_;
      bind_texture(3, spring_mask_[mask_read_]);
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
      draw_full_screen_pass();
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
