// Questions 11 to 13: the cloth and every path that can simulate it. The CPU paths (the readable
// spring_mesh and cloth_parallel) are core/cpu_cloth_paths.hpp's; this class adds the two GPU
// paths (gpu_cloth, gpu_cloth_compute), whose state lives on the GPU and comes back into the CPU
// cloth only when read_state() is called. Used by the window's scene and by the headless runner
// for a GPU path:
//   - everything cpu_cloth_paths does (load, read_state, run, position), on the GPU paths too;
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
#include "core/cpu_cloth_paths.hpp"
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

class cloth_paths final : public cpu_cloth_paths {
 public:
  // The cloth of p, on the CPU path; threads: cpu-parallel's (0: all cores).
  explicit cloth_paths(const cloth_parameters& p, int threads = 0) : cpu_cloth_paths(p, threads) {}
  ~cloth_paths() override;

  // Whether the current context offers the compute path: OpenGL 4.3, and its shader (absent
  // from the student's copy). Asked once the context is current; until then it is not offered.
  void check_compute_offered();
  bool compute_offered(std::string& why) const {
    why = compute_unavailable_;
    return compute_unavailable_.empty();
  }
  // True when `target` runs the cloth as p sets it up (its integrator, self-collision);
  // otherwise false with the reason. The CPU path runs everything this copy has.
  static bool runs(cloth_backend target, const cloth_parameters& p, std::string& why);
  // True when the cloth as now set up can run on that GPU path; otherwise false with the reason
  // (the integrator, tearing or self-collision, the grid size, or a context older than 4.3).
  bool gpu_can_run(cloth_backend target, std::string& why) const;

  // As cpu_cloth_paths', the GPU paths included; their read-backs are counted in readbacks().
  bool load(cloth_backend target, std::string& error) override;
  void read_state() override;
  int run(int count) override;
  glm::dvec3 position(std::size_t k) override;
  // Waits for the GPU's submitted work (glFinish) on a GPU path, so that it can be timed.
  void finish() const;

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

  gpu_cloth gpu_;
  gpu_cloth_compute gpu_compute_;
  std::string compute_unavailable_ = "not checked yet";  // "" when the context has 4.3
  long readbacks_ = 0;
  std::chrono::steady_clock::time_point last_readback_ = std::chrono::steady_clock::now();
  // The compute path's buffers copied (on the GPU) into N x N textures for the renderer.
  cloth_textures compute_textures_;
  int compute_texture_size_ = 0;
};

}  // namespace clothlab
