#include "headless.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "export.hpp"
#include "gl_context.hpp"
#include "gpu_cloth.hpp"
#include "renderer.hpp"

namespace clothlab {
namespace {

using file_ptr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

// Where the run writes its CSV, every csv_every steps (step 0 and the last step always).
class csv_writer {
 public:
  csv_writer(const options& o)
      : file_(nullptr, &std::fclose), every_(o.csv_every), last_(o.steps) {}

  bool open(const std::string& path) {
    if (path.empty())
      return true;
    file_.reset(std::fopen(path.c_str(), "w"));
    if (!file_)
      return false;
    write_csv_header(file_.get());
    return true;
  }
  bool wants(long step) const { return file_ && (step % every_ == 0 || step == last_); }
  void write(long step, double time, const particle_system& particles) {
    write_csv_step(file_.get(), step, time, particles);
  }
  bool close() {
    if (!file_)
      return true;
    const bool ok = std::ferror(file_.get()) == 0;
    return std::fclose(file_.release()) == 0 && ok;
  }

 private:
  file_ptr file_;
  long every_;
  long last_;
};

int report_divergence(stage_kind stage, long step, double dt) {
  std::fprintf(stderr,
               "clothlab: the %s simulation diverged at step %ld (t = %g s): a position or "
               "velocity is no longer finite; reduce --dt or the stiffness, or add damping\n",
               std::string(stage_name(stage)).c_str(), step, double(step) * dt);
  return 3;
}

// Renders the final state into the off-screen context with the stage's fixed camera and writes
// the PNG. `draw` receives the renderer and the view and draws the state.
template <class Draw>
int write_png(const options& o, Draw&& draw) {
  std::string error;
  renderer scene_renderer;
  if (!scene_renderer.init(error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    return 1;
  }
  draw(scene_renderer, camera::default_for(o.stage));
  if (!save_framebuffer_png(o.png_path, o.width, o.height, error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    return 1;
  }
  return 0;
}

template <class Stage>
int write_cpu_png(const options& o, const Stage& stage) {
  return write_png(o, [&](renderer& r, const camera& view) {
    r.draw(stage, view, render_settings{}, o.width, o.height);
  });
}

// The CPU path, the same for the three stages: step 0 is the initial state; after s steps
// t = s dt. A non-finite state stops the run (exit 3) after the CSV of every earlier step.
template <class Stage>
int run_cpu(const options& o, Stage& stage, csv_writer& csv, const dynamics_parameters& d) {
  if (csv.wants(0))
    csv.write(0, 0.0, stage.particles());
  for (long s = 1; s <= o.steps; ++s) {
    stage.step();
    if (!stage.particles().is_finite())
      return report_divergence(o.stage, s, d.time_step);
    if (csv.wants(s))
      csv.write(s, double(s) * d.time_step, stage.particles());
  }
  return 0;
}

std::unique_ptr<gl_context> make_context(const options& o) {
  std::string error;
  auto context = create_offscreen_context(o.width, o.height, error);
  if (!context)
    std::fprintf(stderr, "clothlab: no OpenGL context: %s\n", error.c_str());
  return context;
}

// The GPU path (cloth only): the state lives in float textures; it is read back into the CPU
// cloth for every CSV step, for the divergence check, and at the end for OBJ and PNG.
int run_gpu(const options& o, spring_mesh& cloth, csv_writer& csv) {
  std::string error;
  gpu_cloth gpu;
  if (!gpu.load(cloth, error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    return 1;
  }
  const double dt = cloth.parameters.dynamics.time_step;
  if (csv.wants(0))
    csv.write(0, 0.0, cloth.particles());
  for (long s = 1; s <= o.steps; ++s) {
    gpu.step(cloth.parameters);
    gpu.read_state(cloth);
    if (!cloth.particles().is_finite())
      return report_divergence(o.stage, s, dt);
    if (csv.wants(s))
      csv.write(s, double(s) * dt, cloth.particles());
  }
  return 0;
}

}  // namespace

int run_headless(const options& o) {
  csv_writer csv(o);
  if (!csv.open(o.csv_path)) {
    std::fprintf(stderr, "clothlab: --csv %s: cannot write: %s\n", o.csv_path.c_str(),
                 std::strerror(errno));
    return 1;
  }

  // One off-screen context serves the GPU path and the PNG.
  std::unique_ptr<gl_context> context;
  if (o.backend == backend_kind::gpu || !o.png_path.empty()) {
    context = make_context(o);
    if (!context)
      return 1;
  }

  int status = 0;
  switch (o.stage) {
    case stage_kind::spring: {
      single_spring stage(o.spring);
      status = run_cpu(o, stage, csv, o.spring.dynamics);
      if (status == 0 && !o.png_path.empty())
        status = write_cpu_png(o, stage);
      break;
    }
    case stage_kind::coupled: {
      coupled_springs stage(o.coupled);
      status = run_cpu(o, stage, csv, o.coupled.dynamics);
      if (status == 0 && !o.png_path.empty())
        status = write_cpu_png(o, stage);
      break;
    }
    case stage_kind::cloth: {
      spring_mesh cloth(o.cloth);
      status = o.backend == backend_kind::gpu ? run_gpu(o, cloth, csv)
                                              : run_cpu(o, cloth, csv, o.cloth.dynamics);
      if (status != 0)
        break;
      cloth.compute_normals();  // of the final positions
      if (!o.obj_path.empty() &&
          !write_obj(o.obj_path, cloth.grid_size(), cloth.particles(), cloth.normals())) {
        std::fprintf(stderr, "clothlab: --obj %s: cannot write: %s\n", o.obj_path.c_str(),
                     std::strerror(errno));
        status = 1;
        break;
      }
      // (the GPU run wrote its PNG from its textures)
      if (!o.png_path.empty() && o.backend == backend_kind::cpu)
        status = write_cpu_png(o, cloth);
      break;
    }
  }
  if (!csv.close() && status == 0) {
    std::fprintf(stderr, "clothlab: --csv %s: error while writing\n", o.csv_path.c_str());
    status = 1;
  }
  return status;
}

}  // namespace clothlab
