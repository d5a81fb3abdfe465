// The command line of docs/cli.md, parsed with CLI11. Shared by the headless program and the
// window, so that every option means the same in both.
#pragma once

#include <optional>
#include <string>
#include <string_view>
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

struct parse_result {
  std::optional<options> parsed;  // set when the program should go on
  int exit_code = 0;              // when not: 0 after --help/--version, 2 after bad usage
};

// Parses argv. --help and --version print to stdout; bad usage prints one line to stderr
// naming the option and what is wrong. Options that every stage shares (--dt, --mu, --mass,
// --gravity, --integrator) are set in all three parameter structs.
parse_result parse_command_line(int argc, const char* const* argv);

// The text with its control characters escaped (a newline as \n, others as \xHH), so that a
// message that quotes a value stays one line.
std::string one_line(std::string_view text);

}  // namespace clothlab
