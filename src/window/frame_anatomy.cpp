#include "window/frame_anatomy.hpp"

#include <cstdio>

namespace clothlab {

std::string format_duration(double seconds) {
  char text[32];
  if (seconds < 0.0)
    return "-";
  if (seconds < 1e-6)
    std::snprintf(text, sizeof text, "%.0f ns", seconds * 1e9);
  else if (seconds < 1e-3)
    std::snprintf(text, sizeof text, "%.0f us", seconds * 1e6);
  else if (seconds < 1.0)
    std::snprintf(text, sizeof text, "%.2f ms", seconds * 1e3);
  else
    std::snprintf(text, sizeof text, "%.2f s", seconds);
  return text;
}

std::vector<anatomy_row> anatomy_rows(const frame_anatomy& a) {
  // The files of each stage's model (src/core/) and what its functions answer.
  const char* model = "spring_mesh.cpp";
  const char* forces = "spring_mesh.cpp (Q8 springs, Q13 wind)";
  const char* integration = "spring_mesh.cpp (Q6 loops)";
  const char* constraints =
      "apply_constraints (spring_mesh_step.cpp): apply_ground_contact (Q9, spring_mesh.cpp)";
  if (a.stage == stage_kind::spring) {
    model = "single_spring.cpp";
    forces = "single_spring.cpp (Q2, equation 2)";
    integration = "single_spring.cpp (Q2-Q4)";
    constraints = "single_spring.hpp: none (p0 fixed by apply_force)";
  } else if (a.stage == stage_kind::coupled) {
    model = "coupled_springs.cpp";
    forces = "coupled_springs.cpp (Q5)";
    integration = "coupled_springs.cpp";
    constraints = "coupled_springs.hpp: none (p0 fixed by apply_force)";
  }
  std::vector<anatomy_row> rows;
  rows.push_back({0, "load_model", std::string("once, at start (and R): ") + model,
                  "initialisation", a.load_seconds});
  rows.push_back({0, "poll, panel", "window_main.cpp, panel.cpp: events, widgets",
                  "(the user's input)", a.poll_and_panel_seconds});
  rows.push_back({0, "draw_scene", "scene.cpp", "", -1.0});
  const std::string steps = std::to_string(a.steps) + (a.steps == 1 ? " step" : " steps");
  if (a.on_gpu) {
    rows.push_back({1, std::to_string(a.steps) + " GPU steps",
                    a.gpu_compute ? "gpu_cloth_compute.cpp, shaders/gpu_compute_step.comp"
                                  : "gpu_cloth.cpp, shaders/gpu_step.frag (Q11-Q12)",
                    "forces, integration, ground: one pass a step", a.gpu_steps_seconds});
    rows.push_back({1, "normals",
                    a.gpu_compute ? "shaders/gpu_compute_normal.comp" : "shaders/gpu_normal.frag",
                    "display", -1.0});
  } else {
    rows.push_back({1, steps + ", each:", "scene.cpp step_current_stage", "", -1.0});
    rows.push_back({2, "compute_force", forces, "force computation", a.compute_force_seconds});
    rows.push_back({2, "apply_force", integration, "numerical integration", a.apply_force_seconds});
    rows.push_back({2, "constraints", constraints, "constraints", a.constraints_seconds});
    rows.push_back({2, "check", "stability.cpp: divergence_check (Q4)", "", a.check_seconds});
    if (a.stage == stage_kind::cloth)
      rows.push_back(
          {1, "normals", "renderer.cpp: compute_vertex_normals", "display", a.normals_seconds});
  }
  rows.push_back({1, "draw", "renderer.cpp, shaders/draw_*", "display", a.draw_seconds});
  rows.push_back({0, "panel, swap", "window_main.cpp: the panel drawn, the swap", "display",
                  a.panel_and_swap_seconds});
  return rows;
}

}  // namespace clothlab
