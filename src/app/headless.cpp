#include "headless.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#include "energy.hpp"
#include "export.hpp"
#include "gl_context.hpp"
#include "gpu_cloth.hpp"
#include "renderer.hpp"
#include "stability.hpp"
#include "sweep.hpp"

namespace clothlab {
namespace {

// What a run writes as it goes: the particles' states (--csv) and the energies (--energy-csv),
// both at step 0, every csv_every steps and at the last step.
class run_outputs {
 public:
  explicit run_outputs(const options& o) : o_(o), states_(nullptr, &std::fclose) {}

  // Opens the files asked for; false with a message naming the option and the file.
  bool open(std::string& error) {
    if (!o_.csv_path.empty()) {
      states_.reset(std::fopen(o_.csv_path.c_str(), "w"));
      if (!states_) {
        error = "--csv " + o_.csv_path + ": cannot write: " + std::strerror(errno);
        return false;
      }
      write_csv_header(states_.get());
    }
    if (!o_.energy_csv_path.empty()) {
      energies_.open(o_.energy_csv_path);
      if (!energies_) {
        error = "--energy-csv " + o_.energy_csv_path + ": cannot write: " + std::strerror(errno);
        return false;
      }
      write_energy_csv_header(energies_);
    }
    return true;
  }

  template <class Stage>
  void record(long step, double time_step, const Stage& stage) {
    if (step % o_.csv_every != 0 && step != o_.steps)
      return;
    const double t = double(step) * time_step;  // t = s dt (model.md)
    if (states_)
      write_csv_step(states_.get(), step, t, stage.particles());
    if (energies_.is_open())
      write_energy_csv_row(energies_, step, t, compute_energy(stage));
  }

  bool close(std::string& error) {
    bool ok = true;
    if (states_) {
      ok = std::ferror(states_.get()) == 0;
      ok = std::fclose(states_.release()) == 0 && ok;
      if (!ok)
        error = "--csv " + o_.csv_path + ": error while writing";
    }
    if (energies_.is_open()) {
      energies_.close();
      if (!energies_) {
        ok = false;
        error = "--energy-csv " + o_.energy_csv_path + ": error while writing";
      }
    }
    return ok;
  }

 private:
  const options& o_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> states_;
  std::ofstream energies_;
};

// After every step: a non-finite value or a runaway speed stops the run (exit 3), with where
// the time step stands against the stage's stability limit (questions 4 and 10).
template <class Stage>
bool diverged(const options& o, const Stage& stage, long step, double time_step) {
  const divergence_status status = divergence_check(stage);
  if (!status.diverged)
    return false;
  const stability_estimate estimate = estimate_stability(stage);
  std::fprintf(stderr,
               "clothlab: the %s simulation diverged at step %ld (t = %g s): %s; dt omega_max = "
               "%.3g (%s)\n",
               std::string(stage_name(o.stage)).c_str(), step, double(step) * time_step,
               status.reason.c_str(), time_step * estimate.omega_max, estimate.explanation.c_str());
  return true;
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

// The CPU path, the same for the three stages: step 0 is the initial state, then one step at a
// time: forces, integration, constraints (inside stage.step()), divergence check, output.
template <class Stage>
int run_cpu(const options& o, Stage& stage, run_outputs& out, double time_step) {
  out.record(0, time_step, stage);
  for (long s = 1; s <= o.steps; ++s) {
    stage.step();
    if (diverged(o, stage, s, time_step))
      return 3;
    out.record(s, time_step, stage);
  }
  return 0;
}

// The GPU path (cloth only): the state lives in float textures; it is read back into the CPU
// cloth after every step for the divergence check and the CSVs, and drawn from the textures.
int run_gpu(const options& o, spring_mesh& cloth, run_outputs& out) {
  std::string error;
  gpu_cloth gpu;
  if (!gpu.load(cloth, error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    return 1;
  }
  const double dt = cloth.parameters.dynamics.time_step;
  out.record(0, dt, cloth);
  for (long s = 1; s <= o.steps; ++s) {
    gpu.step(cloth.parameters);
    gpu.read_state(cloth);
    if (diverged(o, cloth, s, dt))
      return 3;
    out.record(s, dt, cloth);
  }
  if (o.png_path.empty())
    return 0;
  return write_png(o, [&](renderer& r, const camera& view) {
    r.draw_from_textures(gpu.position_texture(), gpu.normal_texture(), cloth, view,
                         render_settings{}, o.width, o.height);
  });
}

// n values spaced evenly on a log scale from `from` to `to`.
std::vector<double> log_spaced(double from, double to, int n) {
  std::vector<double> values;
  for (int i = 0; i < n; ++i)
    values.push_back(from * std::pow(to / from, double(i) / (n - 1)));
  return values;
}

// --sweep: the stability map. Unless given, dt spans the theoretical limit of the base
// parameters (from a fifth of it to twice it) and K spans a quarter to four times the base K.
int run_sweep_map(const options& o) {
  sweep_settings settings;
  settings.stage = o.stage;
  settings.spring = o.spring;
  settings.coupled = o.coupled;
  settings.cloth = o.cloth;
  settings.simulated_time = o.sweep_time;
  double base_dt = 0, base_k = 0, limit = 0;
  switch (o.stage) {
    case stage_kind::spring:
      base_dt = o.spring.dynamics.time_step;
      base_k = o.spring.stiffness;
      limit = estimate_stability(single_spring(o.spring)).time_step_limit;
      break;
    case stage_kind::coupled:
      base_dt = o.coupled.dynamics.time_step;
      base_k = o.coupled.stiffness;
      limit = estimate_stability(coupled_springs(o.coupled)).time_step_limit;
      break;
    case stage_kind::cloth:
      base_dt = o.cloth.dynamics.time_step;
      base_k = o.cloth.structural_stiffness;
      limit = estimate_stability(spring_mesh(o.cloth)).time_step_limit;
      break;
  }
  settings.time_steps = o.sweep_time_steps;
  if (settings.time_steps.empty()) {
    const bool finite_limit = std::isfinite(limit) && limit > 0;
    settings.time_steps = finite_limit ? log_spaced(limit / 5, 2 * limit, 12)
                                       : log_spaced(base_dt / 10, base_dt * 10, 12);
  }
  if (!o.sweep_grid_sizes.empty()) {
    settings.axis = sweep_axis::grid_size;
    settings.grid_sizes = o.sweep_grid_sizes;
  } else {
    settings.axis = sweep_axis::stiffness;
    settings.stiffnesses = o.sweep_stiffnesses;
    if (settings.stiffnesses.empty()) {
      settings.stiffnesses = log_spaced(std::max(base_k, 1e-3) / 4, std::max(base_k, 1e-3) * 4, 9);
    }
  }

  std::ofstream file(o.sweep_path);
  if (!file) {
    std::fprintf(stderr, "clothlab: --sweep %s: cannot write: %s\n", o.sweep_path.c_str(),
                 std::strerror(errno));
    return 1;
  }
  const std::vector<sweep_cell> cells = run_sweep(settings);
  write_sweep_csv(file, cells);
  file.close();
  if (!file) {
    std::fprintf(stderr, "clothlab: --sweep %s: error while writing\n", o.sweep_path.c_str());
    return 1;
  }

  // The map on standard output: one row per K (or N), one column per dt; '.' stable,
  // 'X' diverged, and '|' where dt first passes the cell's theoretical limit.
  const std::size_t columns = settings.time_steps.size();
  std::printf("stability map (%s, %s): rows %s, columns dt from %.3g to %.3g s\n",
              std::string(stage_name(o.stage)).c_str(),
              std::string(integrator_name(cells.front().integrator)).c_str(),
              settings.axis == sweep_axis::stiffness ? "K" : "N", settings.time_steps.front(),
              settings.time_steps.back());
  for (std::size_t row = 0; row * columns < cells.size(); ++row) {
    const sweep_cell& first = cells[row * columns];
    if (settings.axis == sweep_axis::stiffness) {
      std::printf("  K %10.4g  ", first.stiffness);
    } else {
      std::printf("  N %10d  ", first.grid_size);
    }
    bool limit_marked = false;
    for (std::size_t c = 0; c < columns; ++c) {
      const sweep_cell& cell = cells[row * columns + c];
      if (!limit_marked && cell.time_step > cell.time_step_limit) {
        std::putchar('|');
        limit_marked = true;
      }
      std::putchar(cell.diverged ? 'X' : '.');
    }
    std::putchar('\n');
  }
  std::printf("  ('.' stable, 'X' diverged within %g s, '|' the theoretical limit; cells in %s)\n",
              o.sweep_time, o.sweep_path.c_str());
  return 0;
}

}  // namespace

int run_headless(const options& o) {
  if (!o.sweep_path.empty())
    return run_sweep_map(o);

  run_outputs out(o);
  std::string error;
  if (!out.open(error)) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    return 1;
  }

  // One off-screen context serves the GPU path and the PNG.
  std::unique_ptr<gl_context> context;
  if (o.backend == backend_kind::gpu || !o.png_path.empty()) {
    context = create_offscreen_context(o.width, o.height, error);
    if (!context) {
      std::fprintf(stderr, "clothlab: no OpenGL context: %s\n", error.c_str());
      return 1;
    }
  }

  int status = 0;
  switch (o.stage) {
    case stage_kind::spring: {
      single_spring stage(o.spring);
      status = run_cpu(o, stage, out, o.spring.dynamics.time_step);
      if (status == 0 && !o.png_path.empty())
        status = write_cpu_png(o, stage);
      break;
    }
    case stage_kind::coupled: {
      coupled_springs stage(o.coupled);
      status = run_cpu(o, stage, out, o.coupled.dynamics.time_step);
      if (status == 0 && !o.png_path.empty())
        status = write_cpu_png(o, stage);
      break;
    }
    case stage_kind::cloth: {
      spring_mesh cloth(o.cloth);
      const bool on_gpu = o.backend == backend_kind::gpu;
      // (the GPU run writes its PNG from its textures)
      status = on_gpu ? run_gpu(o, cloth, out) : run_cpu(o, cloth, out, o.cloth.dynamics.time_step);
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
      if (!on_gpu && !o.png_path.empty())
        status = write_cpu_png(o, cloth);
      break;
    }
  }
  if (!out.close(error) && status == 0) {
    std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    status = 1;
  }
  return status;
}

}  // namespace clothlab
