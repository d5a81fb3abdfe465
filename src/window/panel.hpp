// The control panel (Dear ImGui): the readouts, the stage, the simulation control, every
// parameter of docs/model.md for the current stage and the display toggles, in sections named
// after the handout question each one answers. Also the key-help window (H). panel.cpp lays the
// panel out; its sections are in stage_editors, analysis_views and gpu_section, its widgets in
// widgets, the banners over the scene in scene_banners.
#pragma once

#include <optional>

#include "window/scene.hpp"

namespace clothlab {

// What the user asked for this frame, by key or by button; applied in one place by the main loop.
struct user_actions {
  std::optional<stage_kind> select_stage;  // keys 1, 2, 3
  bool toggle_running = false;             // Space
  bool single_step = false;                // N
  bool reset = false;                      // R, or a parameter that needs load_model changed
  bool reset_view = false;                 // V
  bool toggle_wireframe = false;           // W
  bool screenshot = false;                 // P
  bool toggle_help = false;                // H
  bool switch_cloth_backend = false;       // G: the cloth's next path (questions 11, 12)
  std::optional<cloth_backend> select_cloth_backend;  // the panel's choice of path
  bool measure_backends = false;                      // question 12: time every path on copies
  bool quit = false;                                  // Esc
};

inline constexpr int steps_per_backend_measurement = 200;  // question 12's "measure"
// In ImGui's (screen) units at the default 13 px font, at the window's left; scaled with the
// font on HiDPI screens (ui_scale, widgets.hpp).
inline constexpr float panel_width = 410.0f;

// Builds this frame's panel at the window's left. Parameters and the simulation control are
// edited in place in `the_scene`; everything else comes back in `actions`. Returns the width the
// panel covers, in ImGui's (screen) units: 0 when it is collapsed.
float build_control_panel(scene& the_scene, user_actions& actions);

// The window listing the keys; `open` is cleared when the user closes it.
void build_key_help(bool& open);

}  // namespace clothlab
