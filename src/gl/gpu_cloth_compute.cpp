#include "gl/gpu_cloth_compute.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "core/i18n.hpp"
#include "core/xpbd.hpp"
#include "gl/gl_state_guard.hpp"
#include "gl/gpu_cloth.hpp"

namespace clothlab {

#if defined(CLOTHLAB_GL_WEB)
// The web build: WebGL2 has no compute shaders (nor OpenGL 4.3's storage buffers and barriers).
// The path is there, never available, and says why, as on a desktop older than 4.3: the panel
// shows it greyed with this reason, and nothing of it can be loaded or run.
bool gpu_cloth_compute::available(std::string& error) {
  error =
      tr("the compute-shader GPU path needs OpenGL 4.3 compute shaders, which WebGL2 (this "
         "browser's GL) does not have");
  return false;
}
bool gpu_cloth_compute::supports(const cloth_parameters&, std::string& error) {
  return available(error);
}
gpu_cloth_compute::~gpu_cloth_compute() = default;
bool gpu_cloth_compute::load(const spring_mesh&, std::string& error) {
  return available(error);
}
int gpu_cloth_compute::run(const cloth_parameters&, int, double) {
  throw std::logic_error("gpu_cloth_compute::run called before a successful load");
}
GLuint gpu_cloth_compute::normal_buffer() {
  return 0;
}
void gpu_cloth_compute::read_state(spring_mesh&) const {
  throw std::logic_error("gpu_cloth_compute::read_state called before a successful load");
}
particle_state gpu_cloth_compute::read_particle(std::size_t k) const {
  check_particle_index("gpu_cloth_compute::read_particle", 0, k);  // throws: never loaded
  return {};
}
#else
namespace {

template <typename T>
GLuint create_buffer(const std::vector<T>& data) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)),
               data.data(), GL_DYNAMIC_COPY);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return buffer;
}

}  // namespace

gpu_cloth_compute::~gpu_cloth_compute() {
  release();
}

void gpu_cloth_compute::release() {
  grid_size_ = 0;
  if (position_[0] == 0)
    return;
  glDeleteBuffers(2, position_.data());
  glDeleteBuffers(2, velocity_.data());
  glDeleteBuffers(1, &normal_);
  glDeleteBuffers(1, &spring_mask_);
  const GLuint xpbd_buffers[] = {xpbd_displacement_, xpbd_multiplier_, xpbd_external_force_};
  glDeleteBuffers(3, xpbd_buffers);
  xpbd_displacement_ = xpbd_multiplier_ = xpbd_external_force_ = 0;
  if (diverged_ != 0)
    glDeleteBuffers(1, &diverged_);
  diverged_ = 0;
  position_ = {};
  velocity_ = {};
  normal_ = 0;
  spring_mask_ = 0;
}

bool gpu_cloth_compute::available(std::string& error) {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major > 4 || (major == 4 && minor >= 3))
    return true;
  error =
      format(tr("the compute-shader path needs OpenGL 4.3; this context has %d.%d"), major, minor);
  return false;
}

bool gpu_cloth_compute::supports(const cloth_parameters& p, std::string& error) {
  if (p.dynamics.integrator != integrator_kind::xpbd)
    return gpu_cloth::supports(p, error);
  return gpu_cloth::supports_contacts(p, error);
}

bool gpu_cloth_compute::load(const spring_mesh& cloth, std::string& error) {
  release();
  if (!available(error))
    return false;
  const saved_gl_state saved_state;  // the caller's program, bindings, ... restored on return
  const saved_storage_buffer saved_buffer;
  if (step_program_.id() == 0) {
    if (!step_program_.load_compute("gpu_compute_step.comp", error))
      return false;
    step_uniforms_.locate(step_program_);
    sent_speed_bound_ = -1.0f;
  }
  if (normal_program_.id() == 0 && !normal_program_.load_compute("gpu_compute_normal.comp", error))
    return false;
  if (tear_program_.id() == 0) {
    if (!tear_program_.load_compute("gpu_compute_tear.comp", error))
      return false;
    tear_uniform_.forget();
  }
  const std::array<std::pair<shader_program*, const char*>, 3> xpbd_passes = {{
      {&xpbd_predict_program_, "gpu_xpbd_predict.comp"},
      {&xpbd_solve_program_, "gpu_xpbd_solve.comp"},
      {&xpbd_velocity_program_, "gpu_xpbd_velocity.comp"},
  }};
  for (std::size_t pass = 0; pass < xpbd_passes.size(); ++pass) {
    auto [program, file] = xpbd_passes[pass];
    if (program->id() != 0)
      continue;
    if (!program->load_compute(file, error))
      return false;
    xpbd_uniforms_[pass].locate(*program);
  }
  rest_length_ = family_rest_lengths(cloth);
  const particle_system& particles = cloth.particles();
  const std::size_t count = particles.size();
  std::vector<float> positions(4 * count), velocities(4 * count);
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t c = 0; c < 3; ++c) {
      positions[4 * k + c] = static_cast<float>(particles.position[3 * k + c]);
      velocities[4 * k + c] = static_cast<float>(particles.velocity[3 * k + c]);
    }
    positions[4 * k + 3] = particles.is_fixed[k] ? 1.0f : 0.0f;  // w: pinned
  }
  for (std::size_t copy = 0; copy < 2; ++copy) {
    position_[copy] = create_buffer(positions);
    velocity_[copy] = create_buffer(velocities);
  }
  normal_ = create_buffer(std::vector<float>(4 * count, 0.0f));
  xpbd_displacement_ = create_buffer(std::vector<float>(4 * count, 0.0f));
  xpbd_multiplier_ = create_buffer(std::vector<float>(6 * count, 0.0f));
  xpbd_external_force_ = create_buffer(std::vector<float>(4 * count, 0.0f));
  std::vector<std::uint32_t> masks;
  spring_masks(cloth, masks);  // the springs the CPU cloth still has
  spring_mask_ = create_buffer(masks);
  read_ = 0;
  normals_current_ = false;
  grid_size_ = cloth.grid_size();
  tear_program_.use();
  glUniform1i(tear_program_.uniform("grid_size"), grid_size_);
  normal_program_.use();
  glUniform1i(normal_program_.uniform("grid_size"), grid_size_);
  return true;
}

void gpu_cloth_compute::compute_normals() {
  normal_program_.use();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, position_[read_]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, normal_);
  normal_program_.dispatch_over_grid(grid_size_);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  normals_current_ = true;
}

GLuint gpu_cloth_compute::normal_buffer() {
  if (is_loaded() && !normals_current_) {
    const saved_gl_state saved_state;  // the caller's program
    const saved_storage_buffer saved_buffer;
    compute_normals();
  }
  return normal_;
}

int gpu_cloth_compute::run(const cloth_parameters& p, int count, double speed_bound) {
  if (!is_loaded())
    throw std::logic_error("gpu_cloth_compute::run called before a successful load");
  check_effective(p, "gpu_cloth_compute::run");
  if (std::string error; !supports(p, error))
    throw std::invalid_argument("gpu_cloth_compute::run: " + error);
  if (count < 1)
    return 0;
  const saved_gl_state saved_state;  // the caller's program, bindings, ... restored on return
  const saved_storage_buffer saved_buffer;
  step_program_.use();
  step_uniforms_.set(p, grid_size_, rest_length_);
  const bool check = speed_bound > 0.0;
  if (const float bound = check ? static_cast<float>(std::min(speed_bound, 1e30)) : 0.0f;
      bound != sent_speed_bound_) {
    glUniform1f(step_program_.uniform("speed_bound"), bound);
    sent_speed_bound_ = bound;
  }
  if (check) {
    // One counter per step of this batch, zeroed on the GPU; the buffer grows when a batch is
    // longer than every earlier one.
    const auto bytes = static_cast<GLsizeiptr>(count * sizeof(std::uint32_t));
    if (diverged_ == 0)
      glGenBuffers(1, &diverged_);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, diverged_);
    if (bytes > diverged_capacity_) {
      glBufferData(GL_SHADER_STORAGE_BUFFER, bytes, nullptr, GL_DYNAMIC_READ);
      diverged_capacity_ = bytes;
    }
    glClearBufferSubData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, 0, bytes, GL_RED_INTEGER,
                         GL_UNSIGNED_INT, nullptr);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, diverged_);
  }
  if (p.tear_strain > 0.0)
    tear_uniform_.set(tear_program_, p.tear_strain, rest_length_);
  // Bound once per batch: the normals and the spring mask (updated in place).
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, normal_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, spring_mask_);
  if (p.dynamics.integrator == integrator_kind::xpbd)
    run_xpbd(p, count, check);
  else
    run_mass_spring(p, count, check);
  if (!check)
    return 0;
  std::vector<std::uint32_t>& counts = diverged_counts_;
  counts.resize(static_cast<std::size_t>(count));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, diverged_);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(counts.size() * 4),
                     counts.data());
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  for (int s = 0; s < count; ++s) {
    if (counts[static_cast<std::size_t>(s)] != 0)
      return s + 1;
  }
  return 0;
}

void gpu_cloth_compute::run_mass_spring(const cloth_parameters& p, int count, bool check) {
  const bool wind = p.wind_strength != 0.0;  // the only force that needs the normals
  const bool tear = p.tear_strain > 0.0;
  // Only one dispatch per step without wind or tearing: its program stays in use.
  const bool one_pass = !wind && !tear;
  step_program_.use();
  for (int s = 0; s < count; ++s) {
    // The normals of the current positions, when this step's wind needs them.
    if (wind && !normals_current_)
      compute_normals();

    const int write = 1 - read_;
    if (!one_pass)
      step_program_.use();
    if (check)
      glUniform1i(step_program_.uniform("step_index"), s);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, position_[read_]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, velocity_[read_]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, position_[write]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, velocity_[write]);
    step_program_.dispatch_over_grid(grid_size_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    read_ = write;  // ping-pong: the copy just written is the current state
    normals_current_ = false;

    // Tearing, last in the step: from the new positions, into the mask.
    if (tear) {
      tear_program_.use();
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, position_[read_]);
      tear_program_.dispatch_over_grid(grid_size_);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
}

void gpu_cloth_compute::run_xpbd(const cloth_parameters& p, int count, bool check) {
  const xpbd_parameters& settings = p.dynamics.xpbd;
  const double h = p.dynamics.time_step / settings.substeps;
  const auto f = [](double x) { return static_cast<float>(x); };
  // alpha~ and gamma of each family over h, computed as the CPU computes them (xpbd.hpp).
  std::array<float, 3> alpha_tilde{}, gamma{};
  const double stiffness[3] = {p.structural_stiffness, p.shear_stiffness, p.bending_stiffness};
  for (int family = 0; family < 3; ++family) {
    const xpbd_compliance c = compliance_of(stiffness[family], h, settings.constraint_damping);
    alpha_tilde[family] = f(c.alpha_tilde);
    gamma[family] = f(c.gamma);
  }
  shader_program* const programs[3] = {&xpbd_predict_program_, &xpbd_solve_program_,
                                       &xpbd_velocity_program_};
  for (int pass = 0; pass < 3; ++pass) {
    programs[pass]->use();
    xpbd_uniforms_[pass].set(p, grid_size_, rest_length_);
  }
  xpbd_predict_program_.use();
  glUniform1f(xpbd_predict_program_.uniform("substep"), f(h));
  xpbd_solve_program_.use();
  glUniform3fv(xpbd_solve_program_.uniform("alpha_tilde"), 1, alpha_tilde.data());
  glUniform3fv(xpbd_solve_program_.uniform("gamma"), 1, gamma.data());
  const GLint colour_at = xpbd_solve_program_.uniform("colour");
  xpbd_velocity_program_.use();
  glUniform1f(xpbd_velocity_program_.uniform("substep"), f(h));
  // The contacts come every substep, over h (xpbd.hpp).
  glUniform1f(xpbd_velocity_program_.uniform("time_step"), f(h));
  glUniform1f(xpbd_velocity_program_.uniform("speed_bound"), check ? sent_speed_bound_ : 0.0f);
  const GLint first_at = xpbd_predict_program_.uniform("first_substep");
  const GLint last_at = xpbd_velocity_program_.uniform("last_substep");
  const GLint step_at = xpbd_velocity_program_.uniform("step_index");
  // In place: the current copy of the positions and velocities, and XPBD's own buffers.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, xpbd_displacement_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, xpbd_multiplier_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, xpbd_external_force_);
  const bool wind = p.wind_strength != 0.0;
  const bool tear = p.tear_strain > 0.0;
  for (int s = 0; s < count; ++s) {
    if (wind && !normals_current_)
      compute_normals();  // F_ext's normals, from the start of the step
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, position_[read_]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, velocity_[read_]);
    for (int substep = 0; substep < settings.substeps; ++substep) {
      xpbd_predict_program_.use();
      glUniform1i(first_at, substep == 0);
      xpbd_predict_program_.dispatch_over_grid(grid_size_);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      xpbd_solve_program_.use();
      for (int iteration = 0; iteration < settings.iterations; ++iteration) {
        for (int colour = 0; colour < cloth_constraint_colours; ++colour) {
          glUniform1i(colour_at, colour);
          xpbd_solve_program_.dispatch_over_grid(grid_size_);
          glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
      }
      xpbd_velocity_program_.use();
      glUniform1i(last_at, substep + 1 == settings.substeps);
      if (check)
        glUniform1i(step_at, s);
      xpbd_velocity_program_.dispatch_over_grid(grid_size_);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    normals_current_ = false;
    if (tear) {  // last in the step, from the new positions, into the mask
      tear_program_.use();
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, position_[read_]);
      tear_program_.dispatch_over_grid(grid_size_);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
}

void gpu_cloth_compute::read_state(spring_mesh& cloth) const {
  if (cloth.grid_size() != grid_size_)
    throw std::invalid_argument(
        "gpu_cloth_compute::read_state: the cloth has N = " + std::to_string(cloth.grid_size()) +
        ", the GPU state N = " + std::to_string(grid_size_));
  const saved_storage_buffer saved_buffer;
  particle_system& particles = cloth.particles();
  const std::size_t count = particles.size();
  readback_.resize(4 * count);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  for (const auto& [buffer, target] : {std::pair{position_[read_], &particles.position},
                                       std::pair{velocity_[read_], &particles.velocity}}) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                       static_cast<GLsizeiptr>(readback_.size() * sizeof(float)), readback_.data());
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t c = 0; c < 3; ++c)
        (*target)[3 * k + c] = static_cast<double>(readback_[4 * k + c]);
    }
  }
  // The springs torn on the GPU leave the CPU cloth too.
  mask_readback_.resize(count);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, spring_mask_);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                     static_cast<GLsizeiptr>(count * sizeof(std::uint32_t)), mask_readback_.data());
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  remove_torn_springs(mask_readback_, cloth);
}

particle_state gpu_cloth_compute::read_particle(std::size_t k) const {
  check_particle_index("gpu_cloth_compute::read_particle", is_loaded() ? grid_size_ : 0, k);
  const saved_storage_buffer saved_buffer;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::array<std::array<float, 4>, 2> texels{};  // position, velocity
  const auto offset = static_cast<GLintptr>(k * sizeof(texels[0]));
  for (std::size_t i = 0; i < 2; ++i) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, i == 0 ? position_[read_] : velocity_[read_]);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, offset, sizeof(texels[i]), texels[i].data());
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return {glm::dvec3(texels[0][0], texels[0][1], texels[0][2]),
          glm::dvec3(texels[1][0], texels[1][1], texels[1][2])};
}

#endif  // CLOTHLAB_GL_WEB

}  // namespace clothlab
