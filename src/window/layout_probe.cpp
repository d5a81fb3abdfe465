#include "window/layout_probe.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "window/widgets.hpp"  // format

namespace clothlab {
namespace {

bool asked() {
  static const bool asked = std::getenv("CLOTHLAB_PRINT_LAYOUT") != nullptr;
  return asked;
}

// The top of the dt slider this frame, in screen units (every stage has one).
float time_step_slider_y = 0.0f;

}  // namespace

void note_time_step_slider() {
  time_step_slider_y = ImGui::GetItemRectMin().y;
}

void log_layout(const scene& the_scene, const char* state) {
  if (!asked())
    return;
  static std::string last;
  const std::string line =
      format("clothlab-window: layout: %s stage, %s, %s, %s, message %s: dt slider at y = %.1f",
             std::string(stage_name(the_scene.stage())).c_str(), state,
             the_scene.control.mode == time_mode::real_time ? "real time" : "fixed steps",
             backend_name(the_scene.backend()), the_scene.backend_message().empty() ? "no" : "yes",
             time_step_slider_y);
  if (line == last)
    return;
  last = line;
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

void log_widget(const char* name) {
  if (!asked())
    return;
  static std::vector<std::pair<std::string, std::string>> last;  // name -> its last line
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  const ImDrawList& draw = *ImGui::GetWindowDrawList();
  const ImVec2 clip_low = draw.GetClipRectMin(), clip_high = draw.GetClipRectMax();
  const bool whole =
      low.x >= clip_low.x && low.y >= clip_low.y && high.x <= clip_high.x && high.y <= clip_high.y;
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  const std::string line = format("clothlab-window: widget \"%s\" at (%.0f, %.0f), %s", name,
                                  (low.x + high.x) / 2 * scale.x, (low.y + high.y) / 2 * scale.y,
                                  whole ? "in sight" : "hidden or cut");
  auto known =
      std::find_if(last.begin(), last.end(), [&](const auto& e) { return e.first == name; });
  if (known == last.end())
    known = last.insert(last.end(), {name, ""});
  if (known->second == line)
    return;
  known->second = line;
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace clothlab
