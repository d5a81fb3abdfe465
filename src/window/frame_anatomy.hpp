// Questions 1 and 3 made visible: what ran in the last frame, in the handout's scene structure
// (load_model once; every frame draw_scene: k steps of compute_force and apply_force, the
// constraints, the normals, the drawing), with the measured time of each and the function and
// file that does it. The scene measures (std::chrono around each phase, in scene.cpp and
// window_main.cpp, never inside the student's functions); this file turns the measures into the
// rows the panel shows. No ImGui here: tested without a window.
#pragma once

#include <string>
#include <vector>

#include "core/parameters.hpp"   // stage_kind
#include "core/step_phases.hpp"  // step_phase

namespace clothlab {

// The measured times of one frame, s (sums over the frame's steps).
struct frame_anatomy {
  stage_kind stage = stage_kind::cloth;
  bool on_gpu = false;        // the cloth's steps ran on a GPU path
  bool gpu_compute = false;   // ... its compute-shader path
  double load_seconds = 0.0;  // the last load_model of this stage (at start, R, a rebuild)
  long frame = 0;             // frames drawn since the start
  int steps = 0;              // k, the steps this frame took
  double compute_force_seconds = 0.0;
  double apply_force_seconds = 0.0;     // the integration (fixed vertices skipped)
  double constraints_seconds = 0.0;     // apply_constraints: sphere, ground, ...
  double check_seconds = 0.0;           // divergence_check after each step (question 4)
  double gpu_steps_seconds = 0.0;       // on the GPU paths: the batches of steps, between glFinish
  double normals_seconds = 0.0;         // the cloth's vertex normals for the drawing (CPU path)
  double draw_seconds = 0.0;            // the renderer's calls (the GPU finishes them at the swap)
  double poll_and_panel_seconds = 0.0;  // events, then the panel's widgets (Dear ImGui)
  double panel_and_swap_seconds = 0.0;  // the panel drawn over the scene, then the swap
  double frame_seconds = 0.0;           // the whole frame, wall-clock

  // The time of a phase of the step: compute_force_seconds, apply_force_seconds or
  // constraints_seconds.
  double& seconds_of(step_phase phase) {
    switch (phase) {
      case step_phase::forces:
        return compute_force_seconds;
      case step_phase::integration:
        return apply_force_seconds;
      case step_phase::constraints:
        break;
    }
    return constraints_seconds;
  }
};

// One line of the view: the phase, which function of which file does it, its time.
struct anatomy_row {
  int depth = 0;          // 0: once / every frame; 1: inside draw_scene; 2: inside a step
  std::string phase;      // "compute_force", "10 steps", ...
  std::string where;      // "spring_mesh.cpp (Q8, Q13)"
  std::string question3;  // the part of question 3: initialisation, force computation, ...
  double seconds = -1.0;  // measured, s; -1: not measured apart (shown as "in the above")
};

std::vector<anatomy_row> anatomy_rows(const frame_anatomy& anatomy);

// A duration, short: "850 ns", "81 us", "2.14 ms", "1.20 s".
std::string format_duration(double seconds);

}  // namespace clothlab
