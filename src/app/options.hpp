// What the command line of docs/cli.md sets (parsed by command_line.hpp): the run, its outputs,
// and the parameters of the three stages. Shared by the headless program and the window, so
// that every option means the same in both.
#pragma once

#include <string>
#include <vector>

#include "core/cloth_backend.hpp"  // --backend
#include "core/coupled_springs.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

// The off-screen OpenGL context of a headless run (--gl): auto is EGL on a hardware device when
// there is one, else OSMesa.
enum class gl_choice { automatic, egl, osmesa };

struct options {
  bool headless = false;
  stage_kind stage = stage_kind::cloth;
  cloth_backend backend = cloth_backend::cpu;
  int threads = 0;                      // cpu-parallel: threads (0: all cores)
  gl_choice gl = gl_choice::automatic;  // --gl
  long steps = 1000;                    // headless: steps to run
  std::string csv_path;                 // empty: no CSV
  long csv_every = 1;
  std::string obj_path;         // empty: no OBJ
  std::string png_path;         // empty: no PNG
  int width = 800;              // px, of --png
  int height = 600;             // px, of --png
  std::string energy_csv_path;  // empty: no energy CSV (step,t,kinetic,gravity,spring,total)
  // --sweep: the stability map of the stage and integrator instead of one run.
  std::string sweep_path;                 // empty: no sweep
  std::vector<double> sweep_time_steps;   // dt of each column, s (empty: around the limit)
  std::vector<double> sweep_stiffnesses;  // K of each row, N/m (empty with no grid sizes: around K)
  std::vector<int> sweep_grid_sizes;      // N (cloth) or n (chain) of each row, instead of K
  double sweep_time = 2.0;                // s simulated in each cell
  long frames = 0;                        // window: run this many frames and exit (0: until closed)
  single_spring_parameters spring;
  // --start 1d: the single spring's v1 along the spring (question 2's 1D motion), as the
  // window's "1D start" box; else the handout's v1 = (1, -1, 0), across the spring.
  bool spring_1d_start = false;
  coupled_springs_parameters coupled;
  cloth_parameters cloth;
};

}  // namespace clothlab
