#include "window/analysis_views.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/stability.hpp"  // the core's: step-size limits (question 4)
#include "window/frame_anatomy.hpp"
#include "window/layout_probe.hpp"
#include "window/plot.hpp"
#include "window/widgets.hpp"

namespace clothlab {
namespace {

// The step-size limit of the current stage as it is now (stability.hpp), s.
double current_time_step_limit(const scene& the_scene) {
  switch (the_scene.stage()) {
    case stage_kind::spring:
      return estimate_stability(the_scene.spring_stage).time_step_limit;
    case stage_kind::coupled:
      return estimate_stability(the_scene.chain_stage).time_step_limit;
    case stage_kind::cloth:
      break;
  }
  return estimate_stability(the_scene.cloth_stage).time_step_limit;
}

}  // namespace

// Question 4: the map of stable (green) and diverged (red) runs over dt (across, centred on the
// theoretical limit) and K (up, around the current K); the outlined cell is the current (dt, K);
// a white dot marks the cells that the theory (stability.hpp) predicts unstable.
void show_stability_map(scene& the_scene) {
  stability_map& map = the_scene.stability_explorer;
  if (ImGui::Button(map.running() ? ui_label("Restart the map")
                                  : ui_label("Map dt x K around the current values"))) {
    map.start(the_scene.stage(), the_scene.spring_stage.parameters,
              the_scene.chain_stage.parameters, the_scene.cloth_stage.parameters,
              current_time_step_limit(the_scene));
  }
  log_widget("Map dt x K");
  if (map.running()) {
    ImGui::SameLine();
    if (ImGui::Button(ui_label("Stop")))
      map.cancel();
  }
  if (map.started())  // stays when done, so that the map below does not move
    ImGui::ProgressBar(static_cast<float>(map.fraction_done()), {-1.0f, 0.0f});
  if (!map.started() || map.stage() != the_scene.stage())
    return;

  const std::vector<sweep_cell> cells = map.cells();
  if (cells.size() < static_cast<std::size_t>(stability_map::columns * stability_map::rows))
    return;
  if (map.just_ended()) {  // on standard output, once: the map's result in one line
    const auto computed =
        std::count_if(cells.begin(), cells.end(), [](const sweep_cell& c) { return c.computed; });
    const auto diverged =
        std::count_if(cells.begin(), cells.end(), [](const sweep_cell& c) { return c.diverged; });
    // (not translated: the window's log, read by the tests)
    std::printf("clothlab-window: stability map (%s, %s): %ld of %zu cells run, %ld diverged\n",
                std::string(stage_name(map.stage())).c_str(),
                std::string(integrator_name(cells.front().integrator)).c_str(),
                static_cast<long>(computed), cells.size(), static_cast<long>(diverged));
    std::fflush(stdout);
  }
  // Axes: K (N/m) of every other row on the left, dt (s) of every third column below.
  const float text_height = ImGui::GetTextLineHeight();
  float label_width = ImGui::CalcTextSize(tr("K (N/m)")).x;
  for (int row = 0; row < stability_map::rows; row += 2) {
    const std::string label = tick_label(cells[row * stability_map::columns].stiffness);
    label_width = std::max(label_width, ImGui::CalcTextSize(label.c_str()).x);
  }
  const float cell_height = 14.0f * ui_scale();
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  const ImVec2 origin = {corner.x + label_width + 6.0f, corner.y + text_height + 2.0f};
  const float cell_width =
      (ImGui::GetContentRegionAvail().x - label_width - 6.0f) / stability_map::columns;
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const ImU32 text_colour = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  draw.AddText(corner, text_colour, tr("K (N/m)"));
  for (int row = 0; row < stability_map::rows; row += 2) {
    const std::string label = tick_label(cells[row * stability_map::columns].stiffness);
    const float y =
        origin.y + (static_cast<float>(stability_map::rows - 1 - row) + 0.5f) * cell_height;
    draw.AddText({origin.x - 4.0f - ImGui::CalcTextSize(label.c_str()).x, y - text_height / 2},
                 text_colour, label.c_str());
  }
  const float bottom = origin.y + stability_map::rows * cell_height;
  draw.AddText({corner.x, bottom + 2.0f}, text_colour, tr("dt (s)"));
  for (int column = 0; column < stability_map::columns; column += 3) {
    const std::string label = tick_label(cells[column].time_step);
    const float half = ImGui::CalcTextSize(label.c_str()).x / 2;
    const float x = origin.x + (static_cast<float>(column) + 0.5f) * cell_width;
    draw.AddLine({x, bottom}, {x, bottom + 3.0f}, text_colour);
    draw.AddText({std::max(x - half, origin.x), bottom + 3.0f}, text_colour, label.c_str());
  }

  const sweep_cell* hovered = nullptr;
  for (std::size_t index = 0; index < cells.size(); ++index) {
    const sweep_cell& cell = cells[index];
    const int column = static_cast<int>(index % stability_map::columns);
    const int row = static_cast<int>(index / stability_map::columns);  // K grows upwards
    const ImVec2 low = {origin.x + static_cast<float>(column) * cell_width,
                        origin.y + static_cast<float>(stability_map::rows - 1 - row) * cell_height};
    const ImVec2 high = {low.x + cell_width - 1.0f, low.y + cell_height - 1.0f};
    const ImU32 colour = !cell.computed  ? IM_COL32(70, 70, 70, 255)
                         : cell.diverged ? IM_COL32(200, 60, 50, 255)
                                         : IM_COL32(70, 170, 80, 255);
    draw.AddRectFilled(low, high, colour);
    if (cell.time_step >= cell.time_step_limit)  // theory: unstable (limit 0: always)
      draw.AddCircleFilled({(low.x + high.x) / 2, (low.y + high.y) / 2}, 2.5f,
                           IM_COL32(255, 255, 255, 255));
    if (column == map.current_column() && row == stability_map::rows / 2)
      draw.AddRect(low, high, IM_COL32(255, 255, 255, 255), 0.0f, 0, 2.0f);
    if (ImGui::IsMouseHoveringRect(low, high))
      hovered = &cell;
  }
  ImGui::Dummy({ImGui::GetContentRegionAvail().x,
                text_height * 2 + 5.0f + cell_height * stability_map::rows});
  ImGui::PushTextWrapPos(0.0f);
  const std::string integrator(integrator_name(cells.front().integrator));
  // Implicit Euler and XPBD have no limit: their map is centred on the current dt.
  const bool limited = std::isfinite(cells[cells.size() / 2].time_step_limit);
  ImGui::TextDisabled(
      tr("%s: dt across (x %.3g per cell, centred on %s), K up (x 10^1/4), the outlined cell is "
         "now; green stable, red diverged, dot: unstable in theory"),
      tr(integrator.c_str()), map.column_factor(),
      limited ? tr("the limit of the current K") : tr("the current dt: no limit"));
  ImGui::PopTextWrapPos();
  if (hovered != nullptr) {
    ImGui::BeginTooltip();
    ImGui::Text(tr("dt = %.4g s, K = %.4g N/m"), hovered->time_step, hovered->stiffness);
    if (std::isfinite(hovered->time_step_limit))
      ImGui::Text(tr("theory: stable while dt < %.4g s"), hovered->time_step_limit);
    else
      ImGui::Text(tr("theory: stable at every dt (%s)"), tr(integrator.c_str()));
    if (hovered->computed) {
      ImGui::Text(
          hovered->diverged ? tr("run: diverged at step %ld") : tr("run: stable for %ld steps"),
          hovered->step);
    }
    ImGui::EndTooltip();
  }
}

// Question 4: what the integrator does with the energy (energy.hpp), frame after frame, against
// the simulated time; each curve on its own scale (the shape is the lesson: growth, oscillation,
// decay), the four over one time axis.
void show_energy(const scene& the_scene) {
  const energy_breakdown& energy = the_scene.energy();
  const double now[4] = {energy.kinetic, energy.gravity, energy.spring, energy.total};
  const char* const names[4] = {tr("kinetic"), tr("gravity"), tr("spring"), tr("total")};
  constexpr const char* ids[4] = {"kinetic", "gravity", "spring", "total"};  // the plots' ids
  constexpr ImU32 colours[4] = {IM_COL32(110, 190, 255, 255), IM_COL32(150, 220, 140, 255),
                                IM_COL32(255, 190, 90, 255), IM_COL32(240, 240, 240, 255)};
  const std::vector<float>& times = the_scene.energy_times();
  for (std::size_t i = 0; i < 4; ++i) {
    const std::vector<float>& history = the_scene.energy_history()[i];
    const plot_series curve = {times, history, colours[i], names[i]};
    plot_style style;
    style.height = (i == 3 ? 78.0f : 52.0f) * ui_scale();
    style.x_numbers = i == 3;  // the time axis's numbers under the last one
    style.x_unit = tr("t (s)");
    style.y_unit = "J";
    style.title = format("%s %.5g J", names[i], now[i]);
    style.min_label_width = ImGui::CalcTextSize("-0.000").x;
    line_plot(ids[i], {&curve, 1}, style);
  }
}

// Question 2: the spring's extension along its rest direction, simulated and exact (the 1D
// damped oscillator, spring_motion.hpp), and their difference.
void show_spring_motion(scene& the_scene, user_actions& actions) {
  actions.reset |= ImGui::Checkbox(ui_label("1D start: v1 along the spring (resets)"),
                                   &the_scene.spring_one_dimensional_start);
  const spring_motion& motion = the_scene.motion();
  const std::vector<float>& times = motion.times();
  // The exact solution as a smooth curve over the plotted time, not only at the frames.
  std::vector<float> exact_times, exact_values;
  if (!times.empty()) {
    constexpr int samples = 300;
    for (int i = 0; i <= samples; ++i) {
      const double t = times.front() + double(times.back() - times.front()) * i / samples;
      exact_times.push_back(static_cast<float>(t));
      exact_values.push_back(static_cast<float>(motion.exact(t)));
    }
  }
  const plot_series extension[] = {
      {exact_times, exact_values, IM_COL32(240, 240, 240, 255), tr("exact")},
      {times, motion.simulated(), IM_COL32(255, 150, 60, 255), tr("simulated")}};
  plot_style style;
  style.height = 96.0f * ui_scale();
  style.x_unit = tr("t (s)");
  style.y_unit = "m";
  style.title = tr("x (m): simulated (orange), exact (white)");
  line_plot("extension", extension, style);
  const plot_series error = {times, motion.error(), IM_COL32(255, 90, 80, 255), tr("error")};
  style.height = 66.0f * ui_scale();
  style.y_from_zero = true;
  style.title = tr("error (m): simulated - exact");
  line_plot("error", {&error, 1}, style);
  fixed_lines(format(tr("largest |error| %.3g m since t = %.2f s (the reset or the last change of "
                        "K, mu, m, g0)"),
                     motion.largest_error(), motion.start_time()),
              2, text_style::disabled);
  if (the_scene.spring_one_dimensional_start)
    fixed_lines(tr("1D start: the motion is along the spring, the 1D model's exactly"), 2,
                text_style::disabled);
  else
    fixed_lines(
        tr("x along the rest direction; the mass also swings sideways (v1 is across the "
           "spring), which the 1D model leaves out: tick 1D start for the integrator alone"),
        2, text_style::disabled);
}

// Questions 1 and 3: what ran in the last frame (frame_anatomy.hpp), in the handout's scene
// structure: load_model once; every frame draw_scene, its k steps of compute_force and
// apply_force, apply_constraints, the normals, the drawing; the measured time of each and the
// function and file that does it. Each phase is coloured by its part of question 3.
void show_frame_anatomy(const scene& the_scene) {
  const frame_anatomy& anatomy = the_scene.last_frame_anatomy();
  const std::array<std::pair<const char*, ImVec4>, 4> parts = {{
      {N_("initialisation"), {0.55f, 0.75f, 1.0f, 1.0f}},
      {N_("force computation"), {1.0f, 0.7f, 0.35f, 1.0f}},
      {N_("numerical integration"), {0.55f, 0.9f, 0.55f, 1.0f}},
      {N_("display"), {0.85f, 0.7f, 1.0f, 1.0f}},
  }};
  const auto colour_of = [&](const std::string& part) {
    for (const auto& [name, colour] : parts) {
      if (part.starts_with(name))
        return colour;
    }
    if (part.starts_with("constraints"))
      return parts[2].second;
    if (part.starts_with("forces"))  // the GPU's step: forces, integration and ground at once
      return parts[1].second;
    return ImGui::GetStyleColorVec4(ImGuiCol_Text);
  };
  fixed_lines(format(tr("frame %ld: %s in all. The parts of question 3:"), anatomy.frame,
                     format_duration(anatomy.frame_seconds).c_str()),
              1, text_style::disabled);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i % 2 == 1)
      ImGui::SameLine();
    ImGui::TextColored(parts[i].second, i % 2 == 0 ? "  %s," : "%s", tr(parts[i].first));
  }
  const ImGuiTableFlags flags =
      ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV;
  if (!ImGui::BeginTable("frame anatomy", 3, flags))
    return;
  ImGui::TableSetupColumn(ui_label("phase"), ImGuiTableColumnFlags_WidthFixed, 122.0f * ui_scale());
  ImGui::TableSetupColumn(ui_label("function, file"), ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableSetupColumn(ui_label("time"), ImGuiTableColumnFlags_WidthFixed, 58.0f * ui_scale());
  for (const anatomy_row& row : anatomy_rows(anatomy)) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    // (ImGui::Indent(0) would indent by the default spacing)
    const float indent = static_cast<float>(row.depth) * 10.0f * ui_scale();
    ImGui::SetCursorPosX(ImGui::GetCursorPosX() + indent);
    ImGui::TextColored(colour_of(row.question3), "%s", row.phase.c_str());
    if (row.phase == "compute_force")
      log_widget("frame anatomy: compute_force");
    if (!row.question3.empty() && ImGui::IsItemHovered())
      ImGui::SetTooltip(tr("question 3: %s"), tr(row.question3.c_str()));
    ImGui::TableNextColumn();
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s", row.where.c_str());
    ImGui::PopTextWrapPos();
    ImGui::TableNextColumn();
    if (row.seconds >= 0.0)
      ImGui::TextUnformatted(format_duration(row.seconds).c_str());
    else
      ImGui::TextDisabled("-");
  }
  ImGui::EndTable();
  fixed_lines(tr("The last whole frame, timed by std::chrono around each call (scene.cpp, "
                 "window_main.cpp). The GPU draws what the renderer asked at the swap."),
              4, text_style::disabled);
}

}  // namespace clothlab
