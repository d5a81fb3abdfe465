// Questions 11 to 13: the cloth and the paths that can simulate it, in one object. The readable
// CPU cloth (spring_mesh, the lab's code, double precision) is always here and is what the
// panel, the CSV and the OBJ read; while another path runs the cloth (cloth_parallel, gpu_cloth,
// gpu_cloth_compute), the state lives on that path and comes back into the CPU cloth only when
// read_state() is called. Used by the window's scene and by the headless runner alike:
//   - switching with the state carried across: read_state() from the path it is on, then load();
//   - stepping in batches with the divergence check done on the path itself (run);
//   - reading back the whole state (read_state) or one particle (position);
//   - the drawing's inputs on the GPU paths (textures, normals), without a read-back;
//   - question 12's measured rates (measure) and the read-backs counted (readbacks).
// Needs the GL context current in which a GPU path was loaded, for every call on it and for the
// destructor. The CPU and cpu-parallel paths need no context.
#pragma once

#include <glm/vec3.hpp>

#include <chrono>
#include <string>
#include <vector>

#include "core/cloth_backend.hpp"
#include "core/cloth_parallel.hpp"
#include "core/spring_mesh.hpp"
#include "gl/gl.hpp"
#include "gl/gpu_cloth.hpp"
#include "gl/gpu_cloth_compute.hpp"

namespace clothlab {

// Question 12: steps per second of every path for the same cloth, measured on copies of the
// current state (cloth_paths::measure), so that the live run is not disturbed.
struct backend_comparison {
  bool measured = false;
  int grid_size = 0;  // N of the measured cloth
  int steps = 0;      // steps timed on each path
  double cpu_steps_per_second = 0.0;
  double gpu_steps_per_second = 0.0;      // 0 when the GPU could not run it (gpu_error says why)
  double compute_steps_per_second = 0.0;  // the compute path; 0 with compute_error
  std::string gpu_error;
  std::string compute_error;
};

// The N x N textures a GPU path's state is drawn from (renderer::draw_from_textures): positions
// and normals (RGBA32F, texel (ku, kv) for particle k = ku + N kv) and the spring masks (R32UI).
struct cloth_textures {
  GLuint position = 0;
  GLuint normal = 0;
  GLuint spring_mask = 0;
};

class cloth_paths {
 public:
  // The cloth of p, on the CPU path; threads: cpu-parallel's (0: all cores).
  explicit cloth_paths(const cloth_parameters& p, int threads = 0) : cloth(p), parallel_(threads) {}
  ~cloth_paths();
  cloth_paths(const cloth_paths&) = delete;
  cloth_paths& operator=(const cloth_paths&) = delete;

  // The readable cloth: its parameters are the ones every path runs with; its state is the
  // current one on the CPU path, and as of the last read_state() on the others.
  spring_mesh cloth;

  // Whether the current context offers the compute path: OpenGL 4.3, and its shader (absent
  // from the student's copy). Asked once the context is current; until then it is not offered.
  void check_compute_offered();
  bool compute_offered(std::string& why) const {
    why = compute_unavailable_;
    return compute_unavailable_.empty();
  }
  // True when the cloth as now set up can run on that GPU path; otherwise false with the reason
  // (the integrator, tearing or self-collision, the grid size, or a context older than 4.3).
  bool gpu_can_run(cloth_backend target, std::string& why) const;

  cloth_backend backend() const { return backend_; }
  // Uploads the cloth's current state (positions, velocities, pins, rest lengths, torn springs)
  // to `target`, which then holds it; the divergence check's speed bound is the cloth's
  // (divergence_speed_bound). The CPU target loads nothing. False with a full-sentence error
  // when the path cannot take it: the cloth is then on the CPU path.
  bool load(cloth_backend target, std::string& error);
  // The current path's state into the cloth (positions, velocities, the springs torn there);
  // nothing on the CPU path. Counted in readbacks() on the GPU paths.
  void read_state();
  // `count` steps on the current path (not the CPU: spring_mesh::step is the lesson's loop, run
  // by its callers), each checked there for divergence: returns the first step of the batch
  // (1..count) after which a particle was not finite or faster than speed_bound(), 0 if none.
  int run(int count);
  double speed_bound() const { return speed_bound_; }  // m/s, set by load()
  // Waits for the GPU's submitted work (glFinish) on a GPU path, so that it can be timed.
  void finish() const;

  // Particle k = ku + N kv's current position, m: on a GPU path one texel read back.
  glm::dvec3 position(std::size_t k);
  // The textures the current GPU path's state is drawn from; the compute path's buffers are
  // copied into them on the GPU (same layout), nothing leaves the GPU.
  cloth_textures textures();
  // The current GPU path's normals, N x N RGBA floats (row kv, then ku), into `rgba`.
  void read_normals(std::vector<float>& rgba);

  long readbacks() const { return readbacks_; }  // GPU -> CPU read-backs of the whole state
  double seconds_since_readback() const;
  // Question 12: times `steps` steps of every path on copies of the current state (read back
  // first): a spring_mesh copy for the CPU, a second gpu_cloth and gpu_cloth_compute for the GPU
  // paths (timed between two glFinish).
  backend_comparison measure(int steps);

 private:
  void copy_compute_state_to_textures();

  cloth_backend backend_ = cloth_backend::cpu;
  cloth_parallel parallel_;
  gpu_cloth gpu_;
  gpu_cloth_compute gpu_compute_;
  double speed_bound_ = 0.0;
  std::string compute_unavailable_ = "not checked yet";  // "" when the context has 4.3
  long readbacks_ = 0;
  std::chrono::steady_clock::time_point last_readback_ = std::chrono::steady_clock::now();
  // The compute path's buffers copied (on the GPU) into N x N textures for the renderer.
  cloth_textures compute_textures_;
  int compute_texture_size_ = 0;
};

}  // namespace clothlab
