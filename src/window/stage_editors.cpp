#include "window/stage_editors.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "core/parameter_table.hpp"  // the sliders' ranges
#include "core/stability.hpp"        // the core's: step-size limits (question 4)
#include "window/analysis_views.hpp"
#include "window/gpu_section.hpp"
#include "window/layout_probe.hpp"
#include "window/widgets.hpp"

namespace clothlab {
namespace {

// A slider over the range that the parameter table gives the option (for the stage's struct).
template <typename value_type>
bool parameter_slider(const char* label, value_type& value, std::string_view option,
                      stage_kind stage, const char* format = "%.3f") {
  const slider_range range = parameter_named(option).slider_for(stage);
  if constexpr (std::is_same_v<value_type, int>)
    return slider(label, value, static_cast<int>(range.low), static_cast<int>(range.high));
  else
    return slider(label, value, range.low, range.high, format, range.logarithmic);
}

// Question 4: where dt stands against the step-size limit of the stage's stiffest mode
// (stability.hpp), as a bar that fills up to the limit.
void show_stability(const stability_estimate& estimate) {
  const bool unstable = estimate.ratio >= 1.0;
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, tr("dt / limit = %.3g"), estimate.ratio);
  ImGui::PushStyleColor(ImGuiCol_PlotHistogram, unstable ? warning_red : quiet_green);
  ImGui::ProgressBar(static_cast<float>(std::min(estimate.ratio, 1.0)), {-1.0f, 0.0f}, overlay);
  ImGui::PopStyleColor();
  fixed_lines(estimate.explanation, 3, text_style::disabled);
}

// dt, mu, m, g0 and the integrator, which every stage has (model.md, "Common"), and XPBD's
// numbers when it is the integrator. The integrators that the cloth's path does not run are
// offered greyed out, the reason in their tooltip (the fragment GPU path: the two Euler schemes
// only; XPBD where this copy has none).
void edit_dynamics(dynamics_parameters& dynamics, stage_kind stage,
                   cloth_backend backend = cloth_backend::cpu) {
  const bool cloth = stage == stage_kind::cloth;
  parameter_slider(ui_label("dt (s)"), dynamics.time_step, "--dt", stage, "%.5f");
  note_time_step_slider();
  // The damping slider ends where mu dt = 1 for the largest dt of the slider above (the damping
  // factor 1 - mu dt must not turn negative).
  parameter_slider(ui_label("damping mu (1/s)"), dynamics.damping, "--mu", stage, "%.3f");
  parameter_slider(ui_label("mass m (kg)"), dynamics.mass, "--mass", stage, "%.3f");
  parameter_slider(ui_label("gravity g0 (m/s^2)"), dynamics.gravity, "--gravity", stage, "%.2f");
  const std::string chosen(integrator_name(dynamics.integrator));
  if (ImGui::BeginCombo(ui_label("integrator"), tr(chosen.c_str()))) {
    for (const integrator_kind kind : all_integrators) {
      cloth_parameters asked;
      asked.dynamics.integrator = kind;
      std::string why_not;
      const bool offered = cloth_paths::runs(backend, asked, why_not);
      ImGui::BeginDisabled(!offered);
      if (ImGui::Selectable(ui_label(std::string(integrator_name(kind)).c_str()),
                            kind == dynamics.integrator))
        dynamics.integrator = kind;
      ImGui::EndDisabled();
      if (!offered && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s", why_not.c_str());
    }
    ImGui::EndCombo();
  }
  if (dynamics.integrator == integrator_kind::xpbd) {
    // XPBD's substeps and sweeps (docs/model.md): the springs' stiffness K is reached only when
    // (omega h)^2 stays below 1 or the sweeps are many (the stability readout below says which).
    parameter_slider(ui_label("XPBD substeps"), dynamics.xpbd.substeps, "--xpbd-substeps", stage);
    parameter_slider(ui_label("XPBD iterations"), dynamics.xpbd.iterations, "--xpbd-iterations",
                     stage);
    parameter_slider(ui_label("XPBD damping beta (N s/m)"), dynamics.xpbd.constraint_damping,
                     "--xpbd-damping", stage, "%.2f");
  }
  if (cloth) {  // the same lines on both paths, so that switching moves nothing
    // The compute path's half only where it runs XPBD: not in the browser (WebGL2 has no
    // compute shaders), nor in the student copy (no XPBD).
    cloth_parameters asked;
    asked.dynamics.integrator = integrator_kind::xpbd;
    std::string why_not;
    fixed_lines(cloth_paths::runs(cloth_backend::gpu_compute, asked, why_not)
                    ? tr("GPU fragment: the two Euler schemes only; GPU compute: these and xpbd")
                    : tr("GPU fragment: the two Euler schemes only"),
                2, text_style::disabled);
  }
}

// The mouse drag's spring on a mass of stages 1 and 2 (model.md, "drag").
void edit_mass_drag(mass_drag_parameters& drag, stage_kind stage) {
  fixed_lines(tr("left drag on a mass: pull it (p0 is fixed)"), 1, text_style::disabled);
  parameter_slider(ui_label("drag stiffness K_d (N/m)"), drag.stiffness, "--drag-stiffness", stage,
                   "%.0f");
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
      {spring_family::structural, N_("structural")},
      {spring_family::shear, N_("shear")},
      {spring_family::bending, N_("bending")},
  }};
  for (const auto& [family, name] : families) {
    if (family != spring_family::structural)
      ImGui::SameLine();
    const glm::vec4 c = spring_family_colour(family);
    ImGui::ColorButton(name, {c.r, c.g, c.b, 1.0f},  // (the English name: its id)
                       ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop);
    ImGui::SameLine(0.0f, 4.0f);
    ImGui::TextUnformatted(tr(name));
  }
}

// The cloth's presets (model.md, "Interaction and contacts"). Each resets the cloth.
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

// The mouse drag's spring, the sphere, tearing and self-collision (model.md, "Interaction and
// contacts").
void edit_interaction(scene& the_scene, user_actions& actions) {
  cloth_parameters& p = the_scene.cloth_stage.parameters;
  fixed_lines(tr("left drag on the cloth: pull a particle; Shift + left drag: move the sphere"), 2,
              text_style::disabled);
  const stage_kind cloth = stage_kind::cloth;
  parameter_slider(ui_label("drag stiffness K_d (N/m)"), p.drag.stiffness, "--drag-stiffness",
                   cloth, "%.0f");
  ImGui::Checkbox(ui_label("sphere"), &p.sphere.enabled);
  ImGui::SameLine();
  if (ImGui::Button(ui_label("Drape over a sphere (resets)"))) {
    drape_over_sphere(p);
    actions.reset = true;
    window_log("preset Drape over a sphere");
  }
  log_widget("Drape over a sphere");
  const double low = -3.0, high = 3.0;
  ImGui::SliderScalarN(ui_label("centre c (m)"), ImGuiDataType_Double, &p.sphere.centre.x, 3, &low,
                       &high, "%.2f", ImGuiSliderFlags_AlwaysClamp);
  slider(ui_label("radius r (m)"), p.sphere.radius, 0.02, 2.0, "%.2f", true);
  // mu_s dt <= 1 for every dt of the cloth's slider.
  parameter_slider(ui_label("friction mu_s (1/s)"), p.sphere.friction, "--sphere-friction", cloth,
                   "%.2f");

  parameter_slider(ui_label("tear strain eps (0: off)"), p.tear_strain, "--tear-strain", cloth,
                   "%.3f");
  // On its own line: beside the full-width slider the panel's edge would cut it off.
  if (ImGui::Button(ui_label("Rip (resets)"))) {
    rip_preset(p);
    actions.reset = true;
    window_log("preset Rip: m = %g kg, tear strain %g, K_d = %g N/m", p.dynamics.mass,
               p.tear_strain, p.drag.stiffness);
  }
  log_widget("Rip");
  if (ImGui::IsItemHovered())
    // xgettext:no-c-format
    ImGui::SetTooltip("%s", tr("a 0.1 kg cloth that tears at 100 % strain under the mouse"));
  ImGui::SameLine();
  fixed_lines(tr("torn springs stay torn: R restores them"), 1, text_style::disabled);

  // The thickness is remembered while self-collision is off (the model's off is d = 0).
  static double thickness = 0.02;
  bool self_collision = p.self_collision_thickness > 0.0;
  if (self_collision)
    thickness = p.self_collision_thickness;
  ImGui::Checkbox(ui_label("self-collision"), &self_collision);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.45f);
  // Up to the shortest rest length h, where the model clamps it (docs/model.md).
  const slider_range range = parameter_named("--self-collision").slider;
  const double h = p.side_length / std::max(p.grid_size - 1, 1);
  slider(ui_label("thickness d (m)"), thickness, range.low,
         std::max(range.low, std::min(range.high, h)), "%.3f", range.logarithmic);
  p.self_collision_thickness = self_collision ? thickness : 0.0;
  // The GPU paths run what cloth_paths::runs accepts; anything else takes the cloth back to the
  // CPU (scene::draw_scene), and this line says why beforehand.
  if (std::string why; !cloth_paths::runs(the_scene.backend(), p, why))
    fixed_lines(why, 2, text_style::coloured, caution_yellow);
  else
    fixed_lines("", 2);
}

}  // namespace

void edit_stage(scene& the_scene, user_actions& actions) {
  constexpr std::array<std::pair<stage_kind, const char*>, 3> stages = {{
      {stage_kind::spring, N_("1 spring")},
      {stage_kind::coupled, N_("2 coupled")},
      {stage_kind::cloth, N_("3 cloth")},
  }};
  for (const auto& [stage, label] : stages) {
    if (stage != stage_kind::spring)
      ImGui::SameLine();
    if (ImGui::RadioButton(ui_label(label), the_scene.stage() == stage))
      actions.select_stage = stage;
  }
}

void edit_simulation_control(simulation_control& control, user_actions& actions) {
  if (ImGui::Button(control.running ? ui_label("Pause (Space)") : ui_label("Run (Space)")))
    actions.toggle_running = true;
  ImGui::SameLine();
  if (ImGui::Button(ui_label("Step (N)")))
    actions.single_step = true;
  ImGui::SameLine();
  if (ImGui::Button(ui_label("Reset (R)")))
    actions.reset = true;

  int mode = static_cast<int>(control.mode);
  ImGui::RadioButton(ui_label("real time"), &mode, static_cast<int>(time_mode::real_time));
  log_widget("real time");
  ImGui::SameLine();
  ImGui::RadioButton(ui_label("fixed steps per frame"), &mode,
                     static_cast<int>(time_mode::steps_per_frame));
  log_widget("fixed steps per frame");
  control.mode = static_cast<time_mode>(mode);
  // Both modes take the height of three sliders, so that nothing below moves at a switch.
  const float top = ImGui::GetCursorPosY();
  if (control.mode == time_mode::real_time) {
    slider(ui_label("speed (sim s/wall s)"), control.real_time_speed, 0.05, 2.0, "%.2f");
    slider(ui_label("max steps per frame"), control.max_steps_per_frame, 1, 5000);
    slider(ui_label("max step time/frame (s)"), control.max_simulation_seconds_per_frame, 0.005,
           0.5, "%.3f", true);
  } else {
    slider(ui_label("steps per frame"), control.steps_per_frame, 1, 500);
    fixed_lines(format(tr("each frame advances t by %d x dt, however long the frame takes"),
                       control.steps_per_frame),
                2, text_style::disabled);
  }
  const float spacing = ImGui::GetStyle().ItemSpacing.y;
  const float missing = top + 3 * ImGui::GetFrameHeightWithSpacing() - ImGui::GetCursorPosY();
  if (missing > 0.0f)
    ImGui::Dummy({1.0f, std::max(missing - spacing, 0.0f)});
}

void edit_single_spring(scene& the_scene, user_actions& actions) {
  single_spring& stage = the_scene.spring_stage;
  if (section(ui_label("Q2-Q4 spring: dt, K, damping"))) {
    edit_dynamics(stage.parameters.dynamics, stage_kind::spring);
    parameter_slider(ui_label("stiffness K (N/m)"), stage.parameters.stiffness, "--K",
                     stage_kind::spring, "%.2f");
    show_stability(estimate_stability(stage));
  }
  if (section(ui_label("Q2 motion: extension x(t), exact solution, error")))
    show_spring_motion(the_scene, actions);
  if (section(ui_label("Mouse")))
    edit_mass_drag(stage.parameters.drag, stage_kind::spring);
}

void edit_coupled_springs(coupled_springs& stage, user_actions& actions) {
  if (section(ui_label("Q5 coupled springs: the chain"))) {
    actions.reset |= parameter_slider(ui_label("masses n (rebuilds)"), stage.parameters.mass_count,
                                      "--chain", stage_kind::coupled);
  }
  if (section(ui_label("Q4 dt, K, damping"))) {
    edit_dynamics(stage.parameters.dynamics, stage_kind::coupled);
    parameter_slider(ui_label("stiffness K (N/m)"), stage.parameters.stiffness, "--K",
                     stage_kind::coupled, "%.2f");
    show_stability(estimate_stability(stage));
  }
  if (section(ui_label("Mouse")))
    edit_mass_drag(stage.parameters.drag, stage_kind::coupled);
}

void edit_cloth(scene& the_scene, user_actions& actions) {
  spring_mesh& stage = the_scene.cloth_stage;
  render_settings& display = the_scene.display;
  cloth_parameters& p = stage.parameters;
  const stage_kind cloth = stage_kind::cloth;
  if (section(ui_label("Q4 dt, damping"))) {
    edit_dynamics(p.dynamics, stage_kind::cloth, the_scene.backend());
    show_stability(estimate_stability(stage));
  }
  if (section(ui_label("Q8 springs: three stiffnesses"))) {
    parameter_slider(ui_label("K_struct (N/m)"), p.structural_stiffness, "--K-struct", cloth,
                     "%.1f");
    parameter_slider(ui_label("K_shear (N/m)"), p.shear_stiffness, "--K-shear", cloth, "%.1f");
    parameter_slider(ui_label("K_bend (N/m)"), p.bending_stiffness, "--K-bend", cloth, "%.1f");
    ImGui::Checkbox(ui_label("show the springs, coloured by family"), &display.show_springs);
    show_spring_legend();
  }
  if (section(ui_label("Q7 pins"))) {
    int pins = p.pins == pin_mode::corners ? 0 : 1;
    actions.reset |= ImGui::RadioButton(ui_label("two corners"), &pins, 0);
    ImGui::SameLine();
    actions.reset |= ImGui::RadioButton(ui_label("none: free fall (rebuilds)"), &pins, 1);
    p.pins = pins == 0 ? pin_mode::corners : pin_mode::none;
  }
  if (section(ui_label("Q9 ground"))) {
    ImGui::Checkbox(ui_label("ground plane z = z_g"), &p.ground_enabled);
    // The floor stays below the pins (or, with none, below the flat cloth's start): a floor above
    // them would be a ceiling.
    const double highest_ground = lowest_pinned_height(stage) - 0.05;
    slider(ui_label("height z_g (m)"), p.ground_height, -3.0, highest_ground, "%.2f");
    p.ground_height = std::min(p.ground_height, highest_ground);
    // mu_g dt <= 1 for every dt of the cloth's slider.
    parameter_slider(ui_label("friction mu_g (1/s)"), p.ground_friction, "--ground-friction", cloth,
                     "%.2f");
  }
  if (section(ui_label("Q10 resolution"))) {
    actions.reset |= parameter_slider(ui_label("grid N (rebuilds)"), p.grid_size, "--N", cloth);
    actions.reset |=
        parameter_slider(ui_label("side S (m, rebuilds)"), p.side_length, "--size", cloth, "%.2f");
    int scaling = static_cast<int>(p.scaling);
    ImGui::RadioButton(ui_label("per particle (handout)"), &scaling,
                       static_cast<int>(resolution_scaling::per_particle));
    ImGui::SameLine();
    ImGui::RadioButton(ui_label("resolution-independent"), &scaling,
                       static_cast<int>(resolution_scaling::resolution_independent));
    p.scaling = static_cast<resolution_scaling>(scaling);
    if (p.scaling == resolution_scaling::resolution_independent)
      parameter_slider(ui_label("reference grid N_ref"), p.reference_grid_size, "--reference-N",
                       cloth);
    // What the simulation really uses at this N (parameters.hpp).
    const cloth_parameters effective = effective_cloth_parameters(p);
    ImGui::Text(tr("h = S/(N-1) = %.4g m, %d particles"), p.side_length / (p.grid_size - 1),
                p.grid_size * p.grid_size);
    ImGui::Text(tr("used: m = %.4g kg, K_bend = %.4g N/m"), effective.dynamics.mass,
                effective.bending_stiffness);
  }
  if (section(ui_label("Q13 wind"))) {
    parameter_slider(ui_label("strength K_w (N)"), p.wind_strength, "--wind-strength", cloth,
                     "%.2f");
    glm::dvec3 direction = p.wind_direction;
    const double min = -1.0, max = 1.0;
    ImGui::SliderScalarN(ui_label("direction u_w"), ImGuiDataType_Double, &direction.x, 3, &min,
                         &max, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    // u_w is normalised before use: a zero vector has no direction, keep the previous one.
    if (direction != glm::dvec3(0.0))
      p.wind_direction = direction;
  }
  if (section(ui_label("Mouse, sphere, tearing, self-collision")))
    edit_interaction(the_scene, actions);
  if (section(ui_label("Q11-Q12 GPU")))
    show_gpu_path(the_scene, actions);
}

void edit_display(render_settings& display, user_actions& actions) {
  ImGui::Checkbox(ui_label("cloth wireframe (W)"), &display.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox(ui_label("ground"), &display.show_ground);
  if (ImGui::Button(ui_label("Reset view (V)")))
    actions.reset_view = true;
  ImGui::SameLine();
  if (ImGui::Button(ui_label("Screenshot (P)")))
    actions.screenshot = true;
  ImGui::SameLine();
  if (ImGui::Button(ui_label("Keys (H)")))
    actions.toggle_help = true;
  // The language of the panel and of the window's messages, while the window is open (it starts
  // in the locale's, or --lang's). Each language is named in its own words.
  std::string_view current = "English";
  for (const language& l : languages()) {
    if (l.code == current_language())
      current = l.name;
  }
  if (ImGui::BeginCombo(ui_label("language"), std::string(current).c_str())) {
    for (const language& l : languages()) {
      const std::string name(l.name);
      if (ImGui::Selectable(name.c_str(), l.code == current_language()) &&
          l.code != current_language()) {
        set_language(l.code);
        window_log("language %s", std::string(l.code).c_str());
      }
      log_widget(("language: " + std::string(l.code)).c_str());
    }
    ImGui::EndCombo();
  }
  log_widget("language");
}

}  // namespace clothlab
