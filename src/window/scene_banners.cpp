#include "window/scene_banners.hpp"

#include <imgui.h>

#include "window/widgets.hpp"

namespace clothlab {
namespace {

// Opens a banner centred over the scene (right of the panel): no title, no input, see-through.
bool begin_scene_banner(const char* name, float panel_covered_width) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos({(panel_covered_width + io.DisplaySize.x) / 2, io.DisplaySize.y * 0.4f},
                          ImGuiCond_Always, {0.5f, 0.5f});
  ImGui::SetNextWindowBgAlpha(0.85f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav;
  return ImGui::Begin(name, nullptr, flags);
}

}  // namespace

// Over the empty scene of a diverged stage: what happened and what to do.
void show_divergence_banner(const run_status& status, float panel_covered_width) {
  if (begin_scene_banner("diverged", panel_covered_width)) {
    ImGui::SetWindowFontScale(1.5f);
    ImGui::TextColored(warning_red, tr("diverged at step %ld (t = %.3f s)"), status.step,
                       status.time);
    ImGui::SetWindowFontScale(1.0f);
    // (broken at spaces: a number is never cut)
    fixed_lines(status.divergence_advice, 4, text_style::plain, {}, ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(tr("reduce dt or K, or add damping; R resets the stage"));
  }
  ImGui::End();
}

// Over the scene of a stage that fell below the view: what happened and what to do. True in
// both copies of the lab: in the student's the cloth falls freely until questions 6 to 9 are
// written; in the teacher's, only without pins and ground (--pins none --ground-z none).
void show_out_of_view_banner(stage_kind stage, float panel_covered_width) {
  if (begin_scene_banner("out of view", panel_covered_width)) {
    ImGui::SetWindowFontScale(1.5f);
    ImGui::TextColored(caution_yellow, "%s",
                       stage == stage_kind::cloth ? tr("The cloth fell out of view")
                                                  : tr("The masses fell out of view"));
    ImGui::SetWindowFontScale(1.0f);
    const float width = ImGui::GetFontSize() * 30.0f;
    if (stage == stage_kind::cloth) {
      fixed_lines(
          tr("Nothing holds it up: it falls freely under gravity. A cloth is held up by questions "
             "6 to 9, written and switched on: apply_force (6), the pins (7), the springs (8) and "
             "the ground (9), in spring_mesh.cpp."),
          4, text_style::plain, {}, width);
    } else {
      fixed_lines(tr("Nothing holds them up: the springs (question 5 for the chain) do."), 2,
                  text_style::plain, {}, width);
    }
    ImGui::TextUnformatted(tr("R resets the stage, V resets the view."));
  }
  ImGui::End();
}

}  // namespace clothlab
