#include "window/panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "window/analysis_views.hpp"
#include "window/layout_probe.hpp"
#include "window/scene_banners.hpp"
#include "window/stage_editors.hpp"
#include "window/widgets.hpp"

namespace clothlab {
namespace {

// The state of the run in one word, for the status line and the layout log.
const char* run_state(const scene& the_scene) {
  const run_status& status = the_scene.status();
  if (status.diverged)
    return "diverged";
  if (!the_scene.control.running)
    return "paused";
  if (status.start_hold_left > 0.0)
    return "starting";
  if (status.behind_real_time)
    return "behind real time";
  return "running";
}

// The readouts at the top of the panel, always in sight, in a fixed number of lines (five): the
// status messages (paused, behind real time, diverged, the cloth's path) take their place
// without pushing the sliders below.
void show_readouts(const scene& the_scene) {
  const run_status& status = the_scene.status();
  ImGui::Text(tr("t = %.3f s   step %ld"), status.time, status.step);
  const double time_step = the_scene.current_time_step();
  ImGui::Text(tr("%.0f steps/s (%.2fx real time)   %.0f frames/s"), the_scene.steps_per_second(),
              the_scene.steps_per_second() * time_step, the_scene.frames_per_second());

  // The cloth's path: G and M act on the cloth whatever stage is shown.
  if (the_scene.stage() == stage_kind::cloth) {
    switch (the_scene.backend()) {
      case cloth_backend::gpu:
        fixed_lines(the_scene.next_cloth_backend() == cloth_backend::gpu_compute
                        ? tr("cloth on the GPU (float, fragment shaders)   G: compute")
                        : tr("cloth on the GPU (float, fragment shaders)   G: CPU"),
                    1, text_style::coloured, quiet_green);
        break;
      case cloth_backend::gpu_compute:
        fixed_lines(tr("cloth on the GPU (float, compute shaders)   G: CPU"), 1,
                    text_style::coloured, quiet_green);
        break;
      case cloth_backend::cpu:
      case cloth_backend::cpu_parallel:  // (not offered by the window: --backend refuses it)
        fixed_lines(the_scene.next_cloth_backend() == cloth_backend::gpu_compute
                        ? tr("cloth on the CPU (double)   G: GPU compute")
                        : tr("cloth on the CPU (double)   G: GPU"),
                    1);
        break;
    }
  } else {
    fixed_lines(format(tr("G, M act on the cloth (stage 3), now on the %s"),
                       tr(backend_name(the_scene.backend()))),
                1, text_style::disabled);
  }

  // One status line, then one line for the details or the cloth's last switch.
  const std::string state = run_state(the_scene);
  if (state == "diverged") {
    fixed_lines(format(tr("diverged at step %ld (t = %.3f s): R resets"), status.step, status.time),
                1, text_style::coloured, warning_red);
    fixed_lines(status.divergence_reason + "; " + status.divergence_advice, 1, text_style::coloured,
                warning_red);
    return;
  }
  if (state == "paused")
    fixed_lines(tr("paused (Space runs, N steps once)"), 1, text_style::coloured, caution_yellow);
  else if (state == "starting")
    fixed_lines(format(tr("the initial state: the first step in %.1f s"), status.start_hold_left),
                1, text_style::coloured, quiet_green);
  else if (state == "behind real time")
    fixed_lines(tr("behind real time: a frame hit its step limit"), 1, text_style::coloured,
                caution_yellow);
  else
    fixed_lines(tr("running (Space pauses)"), 1, text_style::disabled);
  fixed_lines(the_scene.backend_message(), 1, text_style::disabled);
}

}  // namespace

float build_control_panel(scene& the_scene, user_actions& actions) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos({0.0f, 0.0f}, ImGuiCond_Always);
  ImGui::SetNextWindowSize({panel_width * ui_scale(), io.DisplaySize.y}, ImGuiCond_Always);
  float covered_width = 0.0f;           // collapsed: the scene takes the whole window
  the_scene.panel_needs_state = false;  // until a section that shows the state is open
  if (ImGui::Begin(ui_label("clothlab: mass-spring lab"), nullptr,
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize)) {
    covered_width = panel_width * ui_scale();
    show_readouts(the_scene);  // always in sight; the sections below scroll
    ImGui::BeginChild("sections");
    ImGui::PushItemWidth(-170.0f * ui_scale());  // room for the labels on the right
    if (section(ui_label("Q1 stage and time"))) {
      edit_stage(the_scene, actions);
      edit_simulation_control(the_scene.control, actions);
    }
    const bool anatomy_open =
        ImGui::CollapsingHeader(ui_label("Q1, Q3 frame anatomy: what ran, how long"));
    log_widget("frame anatomy");
    if (anatomy_open)
      show_frame_anatomy(the_scene);
    switch (the_scene.stage()) {
      case stage_kind::spring:
        edit_single_spring(the_scene, actions);
        break;
      case stage_kind::coupled:
        edit_coupled_springs(the_scene.chain_stage, actions);
        break;
      case stage_kind::cloth:
        edit_cloth(the_scene, actions);
        break;
    }
    if (section(ui_label("Q4 energy (last frames)"))) {
      the_scene.panel_needs_state = true;
      show_energy(the_scene);
    }
    const bool map_open = ImGui::CollapsingHeader(ui_label("Q4 stability map (dt x K)"));
    log_widget("stability map");
    if (map_open)
      show_stability_map(the_scene);
    if (section(ui_label("Display")))
      edit_display(the_scene.display, actions);
    ImGui::PopItemWidth();
    ImGui::EndChild();
  }
  ImGui::End();

  if (the_scene.status().diverged)
    show_divergence_banner(the_scene.status(), covered_width);
  else if (the_scene.fell_out_of_view())
    show_out_of_view_banner(the_scene.stage(), covered_width);
  log_layout(the_scene, run_state(the_scene));
  return covered_width;
}

void build_key_help(bool& open) {
  constexpr std::array<std::pair<const char*, const char*>, 15> keys = {{
      {"1 2 3", N_("stage: spring, coupled, cloth")},
      {N_("Space"), N_("pause / run")},
      {"N", N_("one step (pauses)")},
      {"R", N_("reset the stage")},
      {"W", N_("wireframe")},
      {"P", N_("screenshot (PNG in the working directory)")},
      {"V", N_("reset the view")},
      {"H", N_("this help")},
      {"G", N_("cloth: next path (CPU, GPU fragment, GPU compute)")},
      {"M", N_("cloth: measure every path's steps/s")},
      {N_("Esc"), N_("quit")},
      {N_("left drag"), N_("on the cloth or a mass: pull it; elsewhere: orbit")},
      {N_("Shift+left drag"), N_("move the sphere")},
      {N_("right drag"), N_("pan")},
      {N_("wheel"), N_("zoom")},
  }};
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos({io.DisplaySize.x - 20.0f, 20.0f}, ImGuiCond_Appearing, {1.0f, 0.0f});
  if (ImGui::Begin(ui_label("Keys"), &open, ImGuiWindowFlags_AlwaysAutoResize)) {
    // The meanings in one column, after the longest key's name in the language shown.
    float key_width = 0.0f;
    for (const auto& [key, meaning] : keys)
      key_width = std::max(key_width, ImGui::CalcTextSize(tr(key)).x);
    for (const auto& [key, meaning] : keys) {
      ImGui::TextColored(caution_yellow, "%s", tr(key));
      ImGui::SameLine(key_width + ImGui::GetStyle().ItemSpacing.x * 3);
      ImGui::TextUnformatted(tr(meaning));
    }
  }
  ImGui::End();
}

}  // namespace clothlab
