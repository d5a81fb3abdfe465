#include "window/panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "core/stability.hpp"  // the core's: step-size limits and divergence (question 4)
#include "window/frame_anatomy.hpp"
#include "window/plot.hpp"

namespace clothlab {
namespace {

// A GL texture name as Dear ImGui's ImTextureID: a pointer up to Dear ImGui 1.91.3 (Debian 12's
// 1.86), an integer (ImU64) since 1.91.4 (Debian unstable's 1.92), which a reinterpret_cast
// cannot make. (A template, so that only the branch of the ImGui at hand is compiled.)
template <typename id = ImTextureID>
id imgui_texture(unsigned int gl_name) {
  if constexpr (std::is_pointer_v<id>)
    return reinterpret_cast<id>(static_cast<std::uintptr_t>(gl_name));
  else
    return static_cast<id>(gl_name);
}

const ImVec4 warning_red = {1.0f, 0.35f, 0.3f, 1.0f};
const ImVec4 caution_yellow = {1.0f, 0.85f, 0.3f, 1.0f};
const ImVec4 quiet_green = {0.5f, 0.9f, 0.5f, 1.0f};

// The top of the dt slider this frame, in screen units (every stage has one): the layout log
// below checks that it does not move when the status changes.
float time_step_slider_y = 0.0f;

// Text broken into lines at spaces only (a number is never cut), in exactly `lines` lines of the
// panel, so that nothing below moves when the text changes length or appears. What does not fit
// ends in "..." and the whole text shows in a tooltip under the mouse.
enum class text_style { plain, disabled, coloured };
// width: of the lines, 0 for the panel's width.
void fixed_lines(const std::string& text, int lines, text_style style = text_style::plain,
                 const ImVec4& colour = {}, float width = 0.0f) {
  if (width <= 0.0f)
    width = std::max(ImGui::GetContentRegionAvail().x, 1.0f);
  const auto fits = [&](const std::string& line) {
    return ImGui::CalcTextSize(line.c_str()).x <= width;
  };
  std::vector<std::string> shown;
  std::string line;
  bool cut = false;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos)
      end = text.size();
    const std::string word = text.substr(start, end - start);
    start = end + 1;
    const std::string longer = line.empty() ? word : line + " " + word;
    if (line.empty() || fits(longer)) {
      line = longer;
      continue;
    }
    shown.push_back(line);
    line = word;
    if (static_cast<int>(shown.size()) == lines) {
      cut = true;
      break;
    }
  }
  if (!cut && !line.empty())
    shown.push_back(line);
  if (static_cast<int>(shown.size()) > lines) {
    shown.resize(static_cast<std::size_t>(lines));
    cut = true;
  }
  if (cut && !shown.empty()) {
    std::string& last = shown.back();
    while (!last.empty() && !fits(last + " ...")) {
      const std::size_t space = last.rfind(' ');
      last.erase(space == std::string::npos ? 0 : space);
    }
    last += last.empty() ? "..." : " ...";
  }
  shown.resize(static_cast<std::size_t>(lines));  // empty lines keep the height
  ImGui::BeginGroup();
  for (const std::string& l : shown) {
    switch (style) {
      case text_style::plain:
        ImGui::TextUnformatted(l.c_str());
        break;
      case text_style::disabled:
        ImGui::TextDisabled("%s", l.c_str());
        break;
      case text_style::coloured:
        ImGui::TextColored(colour, "%s", l.c_str());
        break;
    }
  }
  ImGui::EndGroup();
  if (cut && ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 35.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

std::string format(const char* format_string, auto... values) {
  char text[512];
  std::snprintf(text, sizeof text, format_string, values...);
  return text;
}

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
  ImGui::Text("t = %.3f s   step %ld", status.time, status.step);
  const double time_step = the_scene.current_time_step();
  ImGui::Text("%.0f steps/s (%.2fx real time)   %.0f frames/s", the_scene.steps_per_second(),
              the_scene.steps_per_second() * time_step, the_scene.frames_per_second());

  // The cloth's path: G and M act on the cloth whatever stage is shown.
  if (the_scene.stage() == stage_kind::cloth) {
    std::string why_not;
    switch (the_scene.backend()) {
      case cloth_backend::gpu:
        fixed_lines(std::string("cloth on the GPU (float, fragment shaders)   G: ") +
                        (the_scene.compute_offered(why_not) ? "compute" : "CPU"),
                    1, text_style::coloured, quiet_green);
        break;
      case cloth_backend::gpu_compute:
        fixed_lines("cloth on the GPU (float, compute shaders)   G: CPU", 1, text_style::coloured,
                    quiet_green);
        break;
      case cloth_backend::cpu:
      case cloth_backend::cpu_parallel:  // (not offered by the window: --backend refuses it)
        fixed_lines("cloth on the CPU (double)   G: GPU", 1);
        break;
    }
  } else {
    fixed_lines(std::string("G, M act on the cloth (stage 3), now on the ") +
                    backend_name(the_scene.backend()),
                1, text_style::disabled);
  }

  // One status line, then one line for the details or the cloth's last switch.
  const std::string state = run_state(the_scene);
  if (state == "diverged") {
    fixed_lines(format("diverged at step %ld (t = %.3f s): R resets", status.step, status.time), 1,
                text_style::coloured, warning_red);
    fixed_lines(status.divergence_reason + "; " + status.divergence_advice, 1, text_style::coloured,
                warning_red);
    return;
  }
  if (state == "paused")
    fixed_lines("paused (Space runs, N steps once)", 1, text_style::coloured, caution_yellow);
  else if (state == "starting")
    fixed_lines(format("the initial state: the first step in %.1f s", status.start_hold_left), 1,
                text_style::coloured, quiet_green);
  else if (state == "behind real time")
    fixed_lines("behind real time: a frame hit its step limit", 1, text_style::coloured,
                caution_yellow);
  else
    fixed_lines("running (Space pauses)", 1, text_style::disabled);
  fixed_lines(the_scene.backend_message(), 1, text_style::disabled);
}

// CLOTHLAB_PRINT_LAYOUT=1: prints where the dt slider is whenever it or the run's state changes
// (the window tests check that status messages move no slider).
void log_layout(const scene& the_scene) {
  static const bool asked = std::getenv("CLOTHLAB_PRINT_LAYOUT") != nullptr;
  if (!asked)
    return;
  static std::string last;
  const std::string line =
      format("clothlab-window: layout: %s stage, %s, %s, %s, message %s: dt slider at y = %.1f",
             std::string(stage_name(the_scene.stage())).c_str(), run_state(the_scene),
             the_scene.control.mode == time_mode::real_time ? "real time" : "fixed steps",
             backend_name(the_scene.backend()), the_scene.backend_message().empty() ? "no" : "yes",
             time_step_slider_y);
  if (line == last)
    return;
  last = line;
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

// CLOTHLAB_PRINT_LAYOUT=1: where a named widget (the last item) is, in window pixels from the
// top-left corner, and whether it is whole in the panel's visible part, printed when that
// changes (the window tests click the widget there).
void log_widget(const char* name) {
  static const bool asked = std::getenv("CLOTHLAB_PRINT_LAYOUT") != nullptr;
  if (!asked)
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

// Every slider clamps what is typed after Ctrl+click too, so that no value outside its range
// (a zero time step, a grid of 1) can reach the simulation.
bool slider(const char* label, double& value, double min, double max, const char* format,
            bool logarithmic = false) {
  const ImGuiSliderFlags flags =
      ImGuiSliderFlags_AlwaysClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
  return ImGui::SliderScalar(label, ImGuiDataType_Double, &value, &min, &max, format, flags);
}

bool slider(const char* label, int& value, int min, int max) {
  return ImGui::SliderInt(label, &value, min, max, "%d", ImGuiSliderFlags_AlwaysClamp);
}

bool section(const char* title) {
  return ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen);
}

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

// Question 4: the map of stable (green) and diverged (red) runs over dt (across, centred on the
// theoretical limit) and K (up, around the current K); the outlined cell is the current (dt, K);
// a white dot marks the cells that the theory (stability.hpp) predicts unstable.
void show_stability_map(scene& the_scene) {
  stability_map& map = the_scene.stability_explorer;
  if (ImGui::Button(map.running() ? "Restart the map" : "Map dt x K around the current values")) {
    map.start(the_scene.stage(), the_scene.spring_stage.parameters,
              the_scene.chain_stage.parameters, the_scene.cloth_stage.parameters,
              current_time_step_limit(the_scene));
  }
  log_widget("Map dt x K");
  if (map.running()) {
    ImGui::SameLine();
    if (ImGui::Button("Stop"))
      map.cancel();
  }
  if (map.started())  // stays when done, so that the map below does not move
    ImGui::ProgressBar(static_cast<float>(map.fraction_done()), {-1.0f, 0.0f});
  if (!map.started() || map.stage() != the_scene.stage())
    return;

  const std::vector<sweep_cell> cells = map.cells();
  if (cells.size() < static_cast<std::size_t>(stability_map::columns * stability_map::rows))
    return;
  // Axes: K (N/m) of every other row on the left, dt (s) of every third column below.
  const float text_height = ImGui::GetTextLineHeight();
  float label_width = ImGui::CalcTextSize("K (N/m)").x;
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
  draw.AddText(corner, text_colour, "K (N/m)");
  for (int row = 0; row < stability_map::rows; row += 2) {
    const std::string label = tick_label(cells[row * stability_map::columns].stiffness);
    const float y =
        origin.y + (static_cast<float>(stability_map::rows - 1 - row) + 0.5f) * cell_height;
    draw.AddText({origin.x - 4.0f - ImGui::CalcTextSize(label.c_str()).x, y - text_height / 2},
                 text_colour, label.c_str());
  }
  const float bottom = origin.y + stability_map::rows * cell_height;
  draw.AddText({corner.x, bottom + 2.0f}, text_colour, "dt (s)");
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
  ImGui::TextDisabled(
      "dt across (x %.3g per cell, centred on the limit of the current K), K up (x 10^1/4), "
      "the outlined cell is now; green stable, red diverged, dot: unstable in theory",
      map.column_factor());
  ImGui::PopTextWrapPos();
  if (hovered != nullptr) {
    ImGui::BeginTooltip();
    ImGui::Text("dt = %.4g s, K = %.4g N/m", hovered->time_step, hovered->stiffness);
    ImGui::Text("theory: stable while dt < %.4g s", hovered->time_step_limit);
    if (hovered->computed) {
      ImGui::Text(hovered->diverged ? "run: diverged at step %ld" : "run: stable for %ld steps",
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
  constexpr const char* names[4] = {"kinetic", "gravity", "spring", "total"};
  constexpr ImU32 colours[4] = {IM_COL32(110, 190, 255, 255), IM_COL32(150, 220, 140, 255),
                                IM_COL32(255, 190, 90, 255), IM_COL32(240, 240, 240, 255)};
  const std::vector<float>& times = the_scene.energy_times();
  for (std::size_t i = 0; i < 4; ++i) {
    const std::vector<float>& history = the_scene.energy_history()[i];
    const plot_series curve = {times, history, colours[i], names[i]};
    plot_style style;
    style.height = (i == 3 ? 78.0f : 52.0f) * ui_scale();
    style.x_numbers = i == 3;  // the time axis's numbers under the last one
    style.x_unit = "t (s)";
    style.y_unit = "J";
    style.title = format("%s %.5g J", names[i], now[i]);
    style.min_label_width = ImGui::CalcTextSize("-0.000").x;
    line_plot(names[i], {&curve, 1}, style);
  }
}

// Question 2: the spring's extension along its rest direction, simulated and exact (the 1D
// damped oscillator, spring_motion.hpp), and their difference.
void show_spring_motion(scene& the_scene, user_actions& actions) {
  actions.reset |= ImGui::Checkbox("1D start: v1 along the spring (resets)",
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
      {exact_times, exact_values, IM_COL32(240, 240, 240, 255), "exact"},
      {times, motion.simulated(), IM_COL32(255, 150, 60, 255), "simulated"}};
  plot_style style;
  style.height = 96.0f * ui_scale();
  style.x_unit = "t (s)";
  style.y_unit = "m";
  style.title = "x (m): simulated (orange), exact (white)";
  line_plot("extension", extension, style);
  const plot_series error = {times, motion.error(), IM_COL32(255, 90, 80, 255), "error"};
  style.height = 66.0f * ui_scale();
  style.y_from_zero = true;
  style.title = "error (m): simulated - exact";
  line_plot("error", {&error, 1}, style);
  fixed_lines(format("largest |error| %.3g m since t = %.2f s (the reset or the last change of "
                     "K, mu, m, g0)",
                     motion.largest_error(), motion.start_time()),
              2, text_style::disabled);
  if (the_scene.spring_one_dimensional_start)
    fixed_lines("1D start: the motion is along the spring, the 1D model's exactly", 2,
                text_style::disabled);
  else
    fixed_lines(
        "x along the rest direction; the mass also swings sideways (v1 is across the "
        "spring), which the 1D model leaves out: tick 1D start for the integrator alone",
        2, text_style::disabled);
}

void edit_stage(scene& the_scene, user_actions& actions) {
  constexpr std::array<std::pair<stage_kind, const char*>, 3> stages = {{
      {stage_kind::spring, "1 spring"},
      {stage_kind::coupled, "2 coupled"},
      {stage_kind::cloth, "3 cloth"},
  }};
  for (const auto& [stage, label] : stages) {
    if (stage != stage_kind::spring)
      ImGui::SameLine();
    if (ImGui::RadioButton(label, the_scene.stage() == stage))
      actions.select_stage = stage;
  }
}

void edit_simulation_control(simulation_control& control, user_actions& actions) {
  if (ImGui::Button(control.running ? "Pause (Space)" : "Run (Space)"))
    actions.toggle_running = true;
  ImGui::SameLine();
  if (ImGui::Button("Step (N)"))
    actions.single_step = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)"))
    actions.reset = true;

  int mode = static_cast<int>(control.mode);
  ImGui::RadioButton("real time", &mode, static_cast<int>(time_mode::real_time));
  log_widget("real time");
  ImGui::SameLine();
  ImGui::RadioButton("fixed steps per frame", &mode, static_cast<int>(time_mode::steps_per_frame));
  log_widget("fixed steps per frame");
  control.mode = static_cast<time_mode>(mode);
  // Both modes take the height of three sliders, so that nothing below moves at a switch.
  const float top = ImGui::GetCursorPosY();
  if (control.mode == time_mode::real_time) {
    slider("speed (sim s/wall s)", control.real_time_speed, 0.05, 2.0, "%.2f");
    slider("max steps per frame", control.max_steps_per_frame, 1, 5000);
    slider("max step time/frame (s)", control.max_simulation_seconds_per_frame, 0.005, 0.5, "%.3f",
           true);
  } else {
    slider("steps per frame", control.steps_per_frame, 1, 500);
    fixed_lines(format("each frame advances t by %d x dt, however long the frame takes",
                       control.steps_per_frame),
                2, text_style::disabled);
  }
  const float spacing = ImGui::GetStyle().ItemSpacing.y;
  const float missing = top + 3 * ImGui::GetFrameHeightWithSpacing() - ImGui::GetCursorPosY();
  if (missing > 0.0f)
    ImGui::Dummy({1.0f, std::max(missing - spacing, 0.0f)});
}

// Questions 1 and 3: what ran in the last frame (frame_anatomy.hpp), in the handout's scene
// structure: load_model once; every frame draw_scene, its k steps of compute_force and
// apply_force, apply_constraints, the normals, the drawing; the measured time of each and the
// function and file that does it. Each phase is coloured by its part of question 3.
void show_frame_anatomy(const scene& the_scene) {
  const frame_anatomy& anatomy = the_scene.last_frame_anatomy();
  const std::array<std::pair<const char*, ImVec4>, 4> parts = {{
      {"initialisation", {0.55f, 0.75f, 1.0f, 1.0f}},
      {"force computation", {1.0f, 0.7f, 0.35f, 1.0f}},
      {"numerical integration", {0.55f, 0.9f, 0.55f, 1.0f}},
      {"display", {0.85f, 0.7f, 1.0f, 1.0f}},
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
  fixed_lines(format("frame %ld: %s in all. The parts of question 3:", anatomy.frame,
                     format_duration(anatomy.frame_seconds).c_str()),
              1, text_style::disabled);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i % 2 == 1)
      ImGui::SameLine();
    ImGui::TextColored(parts[i].second, i % 2 == 0 ? "  %s," : "%s", parts[i].first);
  }
  const ImGuiTableFlags flags =
      ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV;
  if (!ImGui::BeginTable("frame anatomy", 3, flags))
    return;
  ImGui::TableSetupColumn("phase", ImGuiTableColumnFlags_WidthFixed, 122.0f * ui_scale());
  ImGui::TableSetupColumn("function, file", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableSetupColumn("time", ImGuiTableColumnFlags_WidthFixed, 58.0f * ui_scale());
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
      ImGui::SetTooltip("question 3: %s", row.question3.c_str());
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
  fixed_lines(
      "The last whole frame, timed by std::chrono around each call (scene.cpp, "
      "window_main.cpp). The GPU draws what the renderer asked at the swap.",
      4, text_style::disabled);
}

// Question 4: where dt stands against the step-size limit of the stage's stiffest mode
// (stability.hpp), as a bar that fills up to the limit.
void show_stability(const stability_estimate& estimate) {
  const bool unstable = estimate.ratio >= 1.0;
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "dt / limit = %.3g", estimate.ratio);
  ImGui::PushStyleColor(ImGuiCol_PlotHistogram, unstable ? warning_red : quiet_green);
  ImGui::ProgressBar(static_cast<float>(std::min(estimate.ratio, 1.0)), {-1.0f, 0.0f}, overlay);
  ImGui::PopStyleColor();
  fixed_lines(estimate.explanation, 3, text_style::disabled);
}

// dt, mu, m, g0 and the integrator, which every stage has (model.md, "Common"). While the cloth
// runs on the GPU, the integrators the GPU does not have are offered greyed out.
void edit_dynamics(dynamics_parameters& dynamics, double max_time_step, bool cloth = false,
                   bool on_gpu = false) {
  slider("dt (s)", dynamics.time_step, 1e-4, max_time_step, "%.5f", true);
  time_step_slider_y = ImGui::GetItemRectMin().y;
  // mu dt stays at most 1 (the damping factor 1 - mu dt must not turn negative) for every dt
  // of the slider above.
  slider("damping mu (1/s)", dynamics.damping, 0.0, 1.0 / max_time_step, "%.3f");
  slider("mass m (kg)", dynamics.mass, 0.01, 10.0, "%.3f", true);
  slider("gravity g0 (m/s^2)", dynamics.gravity, 0.0, 30.0, "%.2f");
  if (ImGui::BeginCombo("integrator", std::string(integrator_name(dynamics.integrator)).c_str())) {
    for (const integrator_kind kind : all_integrators) {
      std::string why_not;
      const bool offered = !on_gpu || gpu_cloth::supports_integrator(kind, why_not);
      ImGui::BeginDisabled(!offered);
      if (ImGui::Selectable(std::string(integrator_name(kind)).c_str(),
                            kind == dynamics.integrator))
        dynamics.integrator = kind;
      ImGui::EndDisabled();
    }
    ImGui::EndCombo();
  }
  if (cloth)  // the same line on both paths, so that switching moves nothing
    fixed_lines("GPU path: semi-implicit and explicit Euler only", 1, text_style::disabled);
}

constexpr double max_spring_time_step = 0.1;  // s, spring and chain
constexpr double max_cloth_time_step = 0.02;  // s
constexpr double max_stiffness = 1e5;         // N/m: far past every stability limit
constexpr double max_drag_stiffness = 1e5;    // K_d, N/m
// N: stronger wind folds the default cloth through itself (without self-collision).
constexpr double max_wind_strength = 20.0;

// Issue 10: the mouse drag's spring on a mass of stages 1 and 2.
void edit_mass_drag(mass_drag_parameters& drag) {
  fixed_lines("left drag on a mass: pull it (p0 is fixed)", 1, text_style::disabled);
  slider("drag stiffness K_d (N/m)", drag.stiffness, 1.0, max_drag_stiffness, "%.0f", true);
}

void edit_single_spring(scene& the_scene, user_actions& actions) {
  single_spring& stage = the_scene.spring_stage;
  if (section("Q2-Q4 spring: dt, K, damping")) {
    edit_dynamics(stage.parameters.dynamics, max_spring_time_step);
    slider("stiffness K (N/m)", stage.parameters.stiffness, 0.0, max_stiffness, "%.2f", true);
    show_stability(estimate_stability(stage));
  }
  if (section("Q2 motion: extension x(t), exact solution, error"))
    show_spring_motion(the_scene, actions);
  if (section("Mouse"))
    edit_mass_drag(stage.parameters.drag);
}

void edit_coupled_springs(coupled_springs& stage, user_actions& actions) {
  if (section("Q5 coupled springs: the chain")) {
    actions.reset |= slider("masses n (rebuilds)", stage.parameters.mass_count, 1, 50);
  }
  if (section("Q4 dt, K, damping")) {
    edit_dynamics(stage.parameters.dynamics, max_spring_time_step);
    slider("stiffness K (N/m)", stage.parameters.stiffness, 0.0, max_stiffness, "%.2f", true);
    show_stability(estimate_stability(stage));
  }
  if (section("Mouse"))
    edit_mass_drag(stage.parameters.drag);
}

// Question 11: the three state textures, side by side, texel (ku, kv) = particle ku + N kv; the
// values of the texel under the mouse in a tooltip.
void show_state_textures(scene& the_scene) {
  the_scene.panel_needs_state = true;
  const state_images& images = the_scene.state_textures();
  fixed_lines(the_scene.state_textures_from_gpu()
                  ? "GPU path: its state textures, read back"
                  : "CPU path: its arrays, laid out as the GPU textures",
              1);
  constexpr std::array<std::pair<state_images::which, const char*>, 3> shown = {{
      {state_images::position, "position"},
      {state_images::velocity, "velocity"},
      {state_images::normal, "normal"},
  }};
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const float side = std::floor((ImGui::GetContentRegionAvail().x - 2 * spacing) / 3);
  for (const auto& [image, name] : shown) {
    if (image != state_images::position)
      ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextUnformatted(name);
    const ImVec2 top_left = ImGui::GetCursorScreenPos();
    // Texel row kv = 0 at the top, as in the texture's memory.
    ImGui::Image(imgui_texture(images.texture(image)), {side, side});
    if (ImGui::IsItemHovered() && images.grid_size() > 0) {
      const ImVec2 mouse = ImGui::GetIO().MousePos;
      const int n = images.grid_size();
      const int ku = std::clamp(
          static_cast<int>((mouse.x - top_left.x) / side * static_cast<float>(n)), 0, n - 1);
      const int kv = std::clamp(
          static_cast<int>((mouse.y - top_left.y) / side * static_cast<float>(n)), 0, n - 1);
      const std::array<double, 3> value = images.texel(image, ku, kv);
      ImGui::BeginTooltip();
      ImGui::Text("texel (%d, %d) = particle %d", ku, kv, ku + n * kv);
      ImGui::Text("%s = (%.4g, %.4g, %.4g)", name, value[0], value[1], value[2]);
      ImGui::EndTooltip();
    }
    ImGui::EndGroup();
  }
  for (const auto& [image, name] : shown)
    fixed_lines(std::string(name) + ": " + images.legend(image), 2, text_style::disabled);
}

// Question 12: which OpenGL renderer draws and runs the GPU path.
void show_renderer(const scene& the_scene) {
  const std::string& name = the_scene.renderer_name();
  fixed_lines("OpenGL renderer: " + name, 1, text_style::disabled);
  const bool software = name.find("llvmpipe") != std::string::npos ||
                        name.find("softpipe") != std::string::npos ||
                        name.find("SWR") != std::string::npos;
  if (software)
    fixed_lines(name.substr(0, name.find(' ')) + ": software, the GPU is the CPU here", 1,
                text_style::coloured, caution_yellow);
  else
    fixed_lines("a hardware GPU", 1, text_style::disabled);
}

// Questions 11 and 12: which path runs the cloth, the switch, and every path's speed.
void show_gpu_path(scene& the_scene, user_actions& actions) {
  const cloth_backend backend = the_scene.backend();
  constexpr std::array<std::pair<cloth_backend, const char*>, 3> paths = {{
      {cloth_backend::cpu, "CPU (double)"},
      {cloth_backend::gpu, "GPU fragment"},
      {cloth_backend::gpu_compute, "GPU compute"},
  }};
  std::string compute_why;
  const bool compute = the_scene.compute_offered(compute_why);
  for (const auto& [path, label] : paths) {
    if (path != cloth_backend::cpu)
      ImGui::SameLine();
    ImGui::BeginDisabled(path == cloth_backend::gpu_compute && !compute);
    if (ImGui::RadioButton(label, backend == path) && backend != path)
      actions.select_cloth_backend = path;
    ImGui::EndDisabled();
  }
  // Fixed lines: a hint, a measurement or a refusal appearing moves nothing below.
  if (std::string why; !the_scene.gpu_can_run(cloth_backend::gpu, why))
    fixed_lines("Not on the GPU: " + why, 2, text_style::coloured, caution_yellow);
  else if (!compute)
    fixed_lines("GPU compute greyed: " + compute_why, 2, text_style::disabled);
  else
    fixed_lines(
        "fragment: the handout's path (textures); compute: OpenGL 4.3 compute shaders "
        "over buffers (issue 9)",
        2, text_style::disabled);

  ImGui::Text("live: %s, %.0f steps/s (stepping alone)", backend_name(the_scene.backend()),
              the_scene.stepping_rate());
  show_renderer(the_scene);
  const std::string measure_label =
      "Measure all (M): " + std::to_string(steps_per_backend_measurement) +
      " steps each, on copies";
  if (ImGui::Button(measure_label.c_str()))
    actions.measure_backends = true;
  const backend_comparison& comparison = the_scene.comparison();
  const auto rate = [](double steps_per_second) {
    return steps_per_second > 0.0 ? format("%.0f", steps_per_second) : std::string("-");
  };
  if (!comparison.measured) {
    fixed_lines("N = -  steps/s: CPU -  GPU -  compute -  (not measured)", 1, text_style::disabled);
    fixed_lines("", 1);
  } else {
    fixed_lines(format("N = %d  steps/s: CPU %s  GPU %s  compute %s", comparison.grid_size,
                       rate(comparison.cpu_steps_per_second).c_str(),
                       rate(comparison.gpu_steps_per_second).c_str(),
                       rate(comparison.compute_steps_per_second).c_str()),
                1);
    const double cpu = comparison.cpu_steps_per_second;
    if (comparison.gpu_steps_per_second <= 0.0)
      fixed_lines(comparison.gpu_error, 1, text_style::coloured, warning_red);
    else if (comparison.grid_size != the_scene.cloth_stage.grid_size())
      fixed_lines("measured for another N: measure again", 1, text_style::disabled);
    else if (comparison.compute_steps_per_second > 0.0)
      fixed_lines(
          format("GPU/CPU = %.2f x   compute/CPU = %.2f x", comparison.gpu_steps_per_second / cpu,
                 comparison.compute_steps_per_second / cpu),
          1);
    else
      fixed_lines(format("GPU/CPU = %.2f x   compute: %s", comparison.gpu_steps_per_second / cpu,
                         comparison.compute_error.c_str()),
                  1);
  }
  fixed_lines(format("read-backs of the GPU state so far: %ld (only for this panel's images and "
                     "the energy plot, at most %.0f/s)",
                     the_scene.readbacks(), scene::max_readbacks_per_second),
              2, text_style::disabled);
  show_state_textures(the_scene);
  ImGui::PushTextWrapPos(0.0f);
  // BEGIN TEACHER: the answer to question 11, which the student copy leaves to the student
  ImGui::TextDisabled(
      "Q11: every particle is one texel of N x N float (RGBA32F) textures: positions (w: "
      "pinned) and velocities, two copies each that swap after every step (ping-pong), and the "
      "normals. The simulation runs in fragment shaders: a triangle covering an N x N viewport "
      "runs one fragment per particle, which sums its springs, gravity and wind, integrates, "
      "applies the ground and writes the new state into the other copy; a second pass writes the "
      "normals. The CPU sends a flat N x N grid once; the vertex shader fetches each vertex's "
      "position and normal from the textures. The divergence check runs on the GPU; the state "
      "comes back to the CPU only for these images and the energy plot.");
  // END TEACHER
  ImGui::PopTextWrapPos();
}

// The height of the lowest pinned particle; with no pins, of the cloth's start (z = 0, model.md).
double lowest_pinned_height(const spring_mesh& cloth) {
  const particle_system& particles = cloth.particles();
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      lowest = std::min(lowest, particles.get_position(k).z);
  }
  return std::isfinite(lowest) ? lowest : 0.0;
}

// What the colours of the springs overlay mean (the renderer's colours).
void show_spring_legend() {
  constexpr std::array<std::pair<spring_family, const char*>, 3> families = {{
      {spring_family::structural, "structural"},
      {spring_family::shear, "shear"},
      {spring_family::bending, "bending"},
  }};
  for (const auto& [family, name] : families) {
    if (family != spring_family::structural)
      ImGui::SameLine();
    const glm::vec4 c = spring_family_colour(family);
    ImGui::ColorButton(name, {c.r, c.g, c.b, 1.0f},
                       ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop);
    ImGui::SameLine(0.0f, 4.0f);
    ImGui::TextUnformatted(name);
  }
}

// Issue 10's presets (model.md, "Interaction and contacts"). Each resets the cloth.
// Drape: no pins, the sphere under the cloth's centre; the cloth falls onto it. The friction is
// high (mu_s dt = 0.08 at dt = 2 ms): the model's friction only damps the sliding (there is no
// sticking), and with the default 5/s the draped cloth slides off within seconds, sooner on the
// GPU paths (float rounding breaks the symmetry sooner).
void drape_over_sphere(cloth_parameters& p) {
  p.pins = pin_mode::none;
  p.sphere = {.enabled = true, .centre = {0.0, 0.0, -0.6}, .radius = 0.3, .friction = 40.0};
  p.tear_strain = 0.0;
}
// Rip: a cloth ten times lighter (m = 0.1 kg, still stable at dt = 2 ms), whose springs tear at
// 100 % strain. Hanging from its two corners it stays whole (its weight stretches the springs at
// the pins less than that; the default 1 kg cloth tears there even at 200 %), while the mouse
// drag (K_d = 2000 N/m) tears it when pulled some 0.3 m away.
void rip_preset(cloth_parameters& p) {
  p.pins = pin_mode::corners;
  p.dynamics.mass = 0.1;
  p.tear_strain = 1.0;
  p.drag.stiffness = 2000.0;
  p.sphere.enabled = false;
}

// Issue 10: the mouse drag's spring, the sphere, tearing and self-collision.
void edit_interaction(scene& the_scene, user_actions& actions) {
  cloth_parameters& p = the_scene.cloth_stage.parameters;
  fixed_lines("left drag on the cloth: pull a particle; Shift + left drag: move the sphere", 2,
              text_style::disabled);
  slider("drag stiffness K_d (N/m)", p.drag.stiffness, 1.0, max_drag_stiffness, "%.0f", true);
  ImGui::Checkbox("sphere", &p.sphere.enabled);
  ImGui::SameLine();
  if (ImGui::Button("Drape over a sphere (resets)")) {
    drape_over_sphere(p);
    actions.reset = true;
    std::printf("clothlab-window: preset Drape over a sphere\n");
    std::fflush(stdout);
  }
  log_widget("Drape over a sphere");
  const double low = -3.0, high = 3.0;
  ImGui::SliderScalarN("centre c (m)", ImGuiDataType_Double, &p.sphere.centre.x, 3, &low, &high,
                       "%.2f", ImGuiSliderFlags_AlwaysClamp);
  slider("radius r (m)", p.sphere.radius, 0.02, 2.0, "%.2f", true);
  // mu_s dt <= 1 for every dt of the cloth's slider.
  slider("friction mu_s (1/s)", p.sphere.friction, 0.0, 1.0 / max_cloth_time_step, "%.2f");

  slider("tear strain eps (0: off)", p.tear_strain, 0.0, 3.0, "%.3f");
  // On its own line: beside the full-width slider it was cut off by the panel's edge.
  if (ImGui::Button("Rip (resets)")) {
    rip_preset(p);
    actions.reset = true;
    std::printf("clothlab-window: preset Rip: m = %g kg, tear strain %g, K_d = %g N/m\n",
                p.dynamics.mass, p.tear_strain, p.drag.stiffness);
    std::fflush(stdout);
  }
  log_widget("Rip");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("a 0.1 kg cloth that tears at 100 %% strain under the mouse");
  ImGui::SameLine();
  fixed_lines("torn springs stay torn: R restores them", 1, text_style::disabled);

  // The thickness is remembered while self-collision is off (the model's off is d = 0).
  static double thickness = 0.02;
  bool self_collision = p.self_collision_thickness > 0.0;
  if (self_collision)
    thickness = p.self_collision_thickness;
  ImGui::Checkbox("self-collision", &self_collision);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.45f);
  // Up to the shortest rest length h, where the model clamps it (docs/model.md).
  const double h = p.side_length / std::max(p.grid_size - 1, 1);
  slider("thickness d (m)", thickness, 0.001, std::max(0.001, std::min(0.2, h)), "%.3f", true);
  p.self_collision_thickness = self_collision ? thickness : 0.0;
  // The GPU paths run what gpu_cloth::supports accepts; anything else takes the cloth back to
  // the CPU (scene::draw_scene), and this line says why beforehand.
  if (std::string why; the_scene.backend() != cloth_backend::cpu && !gpu_cloth::supports(p, why))
    fixed_lines(why, 2, text_style::coloured, caution_yellow);
  else
    fixed_lines("", 2);
}

void edit_cloth(scene& the_scene, user_actions& actions) {
  spring_mesh& stage = the_scene.cloth_stage;
  render_settings& display = the_scene.display;
  cloth_parameters& p = stage.parameters;
  if (section("Q4 dt, damping")) {
    edit_dynamics(p.dynamics, max_cloth_time_step, true, the_scene.backend() != cloth_backend::cpu);
    show_stability(estimate_stability(stage));
  }
  if (section("Q8 springs: three stiffnesses")) {
    slider("K_struct (N/m)", p.structural_stiffness, 0.0, max_stiffness, "%.1f", true);
    slider("K_shear (N/m)", p.shear_stiffness, 0.0, max_stiffness, "%.1f", true);
    slider("K_bend (N/m)", p.bending_stiffness, 0.0, max_stiffness, "%.1f", true);
    ImGui::Checkbox("show the springs, coloured by family", &display.show_springs);
    show_spring_legend();
  }
  if (section("Q7 pins")) {
    int pins = p.pins == pin_mode::corners ? 0 : 1;
    actions.reset |= ImGui::RadioButton("two corners", &pins, 0);
    ImGui::SameLine();
    actions.reset |= ImGui::RadioButton("none: free fall (rebuilds)", &pins, 1);
    p.pins = pins == 0 ? pin_mode::corners : pin_mode::none;
  }
  if (section("Q9 ground")) {
    ImGui::Checkbox("ground plane z = z_g", &p.ground_enabled);
    // The floor stays below the pins (or, with none, below the flat cloth's start): a floor above
    // them would be a ceiling.
    const double highest_ground = lowest_pinned_height(stage) - 0.05;
    slider("height z_g (m)", p.ground_height, -3.0, highest_ground, "%.2f");
    p.ground_height = std::min(p.ground_height, highest_ground);
    // mu_g dt <= 1 for every dt of the cloth's slider.
    slider("friction mu_g (1/s)", p.ground_friction, 0.0, 1.0 / max_cloth_time_step, "%.2f");
  }
  if (section("Q10 resolution")) {
    actions.reset |= slider("grid N (rebuilds)", p.grid_size, 2, 100);
    actions.reset |= slider("side S (m, rebuilds)", p.side_length, 0.2, 4.0, "%.2f");
    int scaling = static_cast<int>(p.scaling);
    ImGui::RadioButton("per particle (handout)", &scaling,
                       static_cast<int>(resolution_scaling::per_particle));
    ImGui::SameLine();
    ImGui::RadioButton("resolution-independent", &scaling,
                       static_cast<int>(resolution_scaling::resolution_independent));
    p.scaling = static_cast<resolution_scaling>(scaling);
    if (p.scaling == resolution_scaling::resolution_independent)
      slider("reference grid N_ref", p.reference_grid_size, 2, 100);
    // What the simulation really uses at this N (parameters.hpp).
    const cloth_parameters effective = effective_cloth_parameters(p);
    ImGui::Text("h = S/(N-1) = %.4g m, %d particles", p.side_length / (p.grid_size - 1),
                p.grid_size * p.grid_size);
    ImGui::Text("used: m = %.4g kg, K_bend = %.4g N/m", effective.dynamics.mass,
                effective.bending_stiffness);
  }
  if (section("Q13 wind")) {
    slider("strength K_w (N)", p.wind_strength, 0.0, max_wind_strength, "%.2f");
    glm::dvec3 direction = p.wind_direction;
    const double min = -1.0, max = 1.0;
    ImGui::SliderScalarN("direction u_w", ImGuiDataType_Double, &direction.x, 3, &min, &max, "%.2f",
                         ImGuiSliderFlags_AlwaysClamp);
    // u_w is normalised before use: a zero vector has no direction, keep the previous one.
    if (direction != glm::dvec3(0.0))
      p.wind_direction = direction;
  }
  if (section("Mouse, sphere, tearing, self-collision"))
    edit_interaction(the_scene, actions);
  if (section("Q11-Q12 GPU"))
    show_gpu_path(the_scene, actions);
}

void edit_display(render_settings& display, user_actions& actions) {
  ImGui::Checkbox("cloth wireframe (W)", &display.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("ground", &display.show_ground);
  if (ImGui::Button("Reset view (V)"))
    actions.reset_view = true;
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (P)"))
    actions.screenshot = true;
  ImGui::SameLine();
  if (ImGui::Button("Keys (H)"))
    actions.toggle_help = true;
}

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

// Over the empty scene of a diverged stage: what happened and what to do.
void show_divergence_banner(const run_status& status, float panel_covered_width) {
  if (begin_scene_banner("diverged", panel_covered_width)) {
    ImGui::SetWindowFontScale(1.5f);
    ImGui::TextColored(warning_red, "diverged at step %ld (t = %.3f s)", status.step, status.time);
    ImGui::SetWindowFontScale(1.0f);
    // (broken at spaces: a number is never cut)
    fixed_lines(status.divergence_advice, 4, text_style::plain, {}, ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted("reduce dt or K, or add damping; R resets the stage");
  }
  ImGui::End();
}

// Over the scene of a stage that fell below the view: what happened and what to do. True in
// both copies of the lab: in the student's the cloth falls freely until questions 6 to 9 are
// written; in the teacher's, only without pins and ground (--pins none --ground-z none).
void show_out_of_view_banner(stage_kind stage, float panel_covered_width) {
  if (begin_scene_banner("out of view", panel_covered_width)) {
    ImGui::SetWindowFontScale(1.5f);
    ImGui::TextColored(caution_yellow, stage == stage_kind::cloth ? "The cloth fell out of view"
                                                                  : "The masses fell out of view");
    ImGui::SetWindowFontScale(1.0f);
    const float width = ImGui::GetFontSize() * 30.0f;
    if (stage == stage_kind::cloth) {
      fixed_lines(
          "Nothing holds it up: it falls freely under gravity. A cloth is held up by questions "
          "6 to 9, written and switched on: apply_force (6), the pins (7), the springs (8) and "
          "the ground (9), in spring_mesh.cpp.",
          4, text_style::plain, {}, width);
    } else {
      fixed_lines("Nothing holds them up: the springs (question 5 for the chain) do.", 2,
                  text_style::plain, {}, width);
    }
    ImGui::TextUnformatted("R resets the stage, V resets the view.");
  }
  ImGui::End();
}

}  // namespace

float ui_scale() {
  return ImGui::GetFontSize() / 13.0f;
}

float build_control_panel(scene& the_scene, user_actions& actions) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos({0.0f, 0.0f}, ImGuiCond_Always);
  ImGui::SetNextWindowSize({panel_width * ui_scale(), io.DisplaySize.y}, ImGuiCond_Always);
  float covered_width = 0.0f;           // collapsed: the scene takes the whole window
  the_scene.panel_needs_state = false;  // until a section that shows the state is open
  if (ImGui::Begin("clothlab: mass-spring lab", nullptr,
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize)) {
    covered_width = panel_width * ui_scale();
    show_readouts(the_scene);  // always in sight; the sections below scroll
    ImGui::BeginChild("sections");
    ImGui::PushItemWidth(-170.0f * ui_scale());  // room for the labels on the right
    if (section("Q1 stage and time")) {
      edit_stage(the_scene, actions);
      edit_simulation_control(the_scene.control, actions);
    }
    const bool anatomy_open = ImGui::CollapsingHeader("Q1, Q3 frame anatomy: what ran, how long");
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
    if (section("Q4 energy (last frames)")) {
      the_scene.panel_needs_state = true;
      show_energy(the_scene);
    }
    if (ImGui::CollapsingHeader("Q4 stability map (dt x K)"))
      show_stability_map(the_scene);
    if (section("Display"))
      edit_display(the_scene.display, actions);
    ImGui::PopItemWidth();
    ImGui::EndChild();
  }
  ImGui::End();

  if (the_scene.status().diverged)
    show_divergence_banner(the_scene.status(), covered_width);
  else if (the_scene.fell_out_of_view())
    show_out_of_view_banner(the_scene.stage(), covered_width);
  log_layout(the_scene);
  return covered_width;
}

void build_key_help(bool& open) {
  constexpr std::array<std::pair<const char*, const char*>, 15> keys = {{
      {"1 2 3", "stage: spring, coupled, cloth"},
      {"Space", "pause / run"},
      {"N", "one step (pauses)"},
      {"R", "reset the stage"},
      {"W", "wireframe"},
      {"P", "screenshot (PNG in the working directory)"},
      {"V", "reset the view"},
      {"H", "this help"},
      {"G", "cloth: next path (CPU, GPU fragment, GPU compute)"},
      {"M", "cloth: measure every path's steps/s"},
      {"Esc", "quit"},
      {"left drag", "on the cloth or a mass: pull it; elsewhere: orbit"},
      {"Shift+left drag", "move the sphere"},
      {"right drag", "pan"},
      {"wheel", "zoom"},
  }};
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos({io.DisplaySize.x - 20.0f, 20.0f}, ImGuiCond_Appearing, {1.0f, 0.0f});
  if (ImGui::Begin("Keys", &open, ImGuiWindowFlags_AlwaysAutoResize)) {
    for (const auto& [key, meaning] : keys) {
      ImGui::TextColored(caution_yellow, "%-10s", key);
      ImGui::SameLine();
      ImGui::TextUnformatted(meaning);
    }
  }
  ImGui::End();
}

}  // namespace clothlab
