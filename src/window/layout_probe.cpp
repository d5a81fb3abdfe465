#include "window/layout_probe.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdarg>
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

void window_log(const char* format_string, ...) {
  std::va_list arguments;
  va_start(arguments, format_string);
  std::fputs("clothlab-window: ", stdout);
  std::vprintf(format_string, arguments);
  std::fputc('\n', stdout);
  va_end(arguments);
  std::fflush(stdout);
}

void note_time_step_slider() {
  time_step_slider_y = ImGui::GetItemRectMin().y;
}

void log_layout(const scene& the_scene, const char* state) {
  if (!asked())
    return;
  static std::string last;
  // (not translated: the window's log, read by the tests)
  const std::string line =
      format("layout: %s stage, %s, %s, %s, message %s: dt slider at y = %.1f",
             std::string(stage_name(the_scene.stage())).c_str(), state,
             the_scene.control.mode == time_mode::real_time ? "real time" : "fixed steps",
             backend_name(the_scene.backend()), the_scene.backend_message().empty() ? "no" : "yes",
             time_step_slider_y);
  if (line == last)
    return;
  last = line;
  window_log("%s", line.c_str());
}

void log_widget(const char* name) {
  if (!asked())
    return;
  static std::vector<std::pair<std::string, std::string>> last;  // name -> its last line
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  const ImDrawList& draw = *ImGui::GetWindowDrawList();
  // (A selectable's rectangle, in a combo's list, reaches half the items' spacing past the clip
  // rectangle: that much does not count as cut.)
  const ImVec2 margin = {ImGui::GetStyle().ItemSpacing.x / 2, ImGui::GetStyle().ItemSpacing.y / 2};
  const ImVec2 clip_low = draw.GetClipRectMin(), clip_high = draw.GetClipRectMax();
  const bool whole = low.x >= clip_low.x - margin.x && low.y >= clip_low.y - margin.y &&
                     high.x <= clip_high.x + margin.x && high.y <= clip_high.y + margin.y;
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  // (not translated: the window's log, read by the tests)
  const std::string line =
      format("widget \"%s\" at (%.0f, %.0f), %s", name, (low.x + high.x) / 2 * scale.x,
             (low.y + high.y) / 2 * scale.y, whole ? "in sight" : "hidden or cut");
  auto known =
      std::find_if(last.begin(), last.end(), [&](const auto& e) { return e.first == name; });
  if (known == last.end())
    known = last.insert(last.end(), {name, ""});
  if (known->second == line)
    return;
  known->second = line;
  window_log("%s", line.c_str());
}

}  // namespace clothlab
