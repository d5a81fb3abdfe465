#include "window/gpu_section.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

#include "window/widgets.hpp"

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

// Question 11: the three state textures, side by side, texel (ku, kv) = particle ku + N kv; the
// values of the texel under the mouse in a tooltip.
void show_state_textures(scene& the_scene) {
  the_scene.panel_needs_state = true;
  const state_images& images = the_scene.state_textures();
  fixed_lines(the_scene.state_textures_from_gpu()
                  ? tr("GPU path: its state textures, read back")
                  : tr("CPU path: its arrays, laid out as the GPU textures"),
              1);
  constexpr std::array<std::pair<state_images::which, const char*>, 3> shown = {{
      {state_images::position, N_("position")},
      {state_images::velocity, N_("velocity")},
      {state_images::normal, N_("normal")},
  }};
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const float side = std::floor((ImGui::GetContentRegionAvail().x - 2 * spacing) / 3);
  for (const auto& [image, name] : shown) {
    if (image != state_images::position)
      ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextUnformatted(tr(name));
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
      ImGui::Text(tr("texel (%d, %d) = particle %d"), ku, kv, ku + n * kv);
      ImGui::Text("%s = (%.4g, %.4g, %.4g)", tr(name), value[0], value[1], value[2]);
      ImGui::EndTooltip();
    }
    ImGui::EndGroup();
  }
  for (const auto& [image, name] : shown)
    fixed_lines(format(tr("%s: %s"), tr(name), images.legend(image).c_str()), 2,
                text_style::disabled);
}

// Question 12: which OpenGL renderer draws and runs the GPU path.
void show_renderer(const scene& the_scene) {
  const std::string& name = the_scene.renderer_name();
  fixed_lines(format(tr("OpenGL renderer: %s"), name.c_str()), 1, text_style::disabled);
  const bool software = name.find("llvmpipe") != std::string::npos ||
                        name.find("softpipe") != std::string::npos ||
                        name.find("SWR") != std::string::npos;
  if (software)
    fixed_lines(
        format(tr("%s: software, the GPU is the CPU here"), name.substr(0, name.find(' ')).c_str()),
        1, text_style::coloured, caution_yellow);
  else
    fixed_lines(tr("a hardware GPU"), 1, text_style::disabled);
}

}  // namespace

// Questions 11 and 12: which path runs the cloth, the switch, and every path's speed.
void show_gpu_path(scene& the_scene, user_actions& actions) {
  const cloth_backend backend = the_scene.backend();
  constexpr std::array<std::pair<cloth_backend, const char*>, 3> paths = {{
      {cloth_backend::cpu, N_("CPU (double)")},
      {cloth_backend::gpu, N_("GPU fragment")},
      {cloth_backend::gpu_compute, N_("GPU compute")},
  }};
  std::string compute_why;
  const bool compute = the_scene.compute_offered(compute_why);
  // The fragment path is the handout's mass-spring path: with XPBD chosen it is greyed, the
  // reason in its tooltip.
  std::string fragment_why;
  const bool fragment_runs_integrator =
      the_scene.cloth_stage.parameters.dynamics.integrator != integrator_kind::xpbd ||
      cloth_paths::runs(cloth_backend::gpu, the_scene.cloth_stage.parameters, fragment_why);
  for (const auto& [path, label] : paths) {
    if (path != cloth_backend::cpu)
      ImGui::SameLine();
    const bool greyed = (path == cloth_backend::gpu_compute && !compute) ||
                        (path == cloth_backend::gpu && !fragment_runs_integrator);
    ImGui::BeginDisabled(greyed);
    if (ImGui::RadioButton(ui_label(label), backend == path) && backend != path)
      actions.select_cloth_backend = path;
    ImGui::EndDisabled();
    if (greyed && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("%s",
                        path == cloth_backend::gpu ? fragment_why.c_str() : compute_why.c_str());
  }
  // Fixed lines: a hint, a measurement or a refusal appearing moves nothing below.
  if (std::string why; !the_scene.gpu_can_run(cloth_backend::gpu, why))
    fixed_lines(format(tr("Not on the GPU: %s"), why.c_str()), 2, text_style::coloured,
                caution_yellow);
  else if (!compute)
    fixed_lines(format(tr("GPU compute greyed: %s"), compute_why.c_str()), 2, text_style::disabled);
  else
    fixed_lines(tr("fragment: the handout's path (textures); compute: OpenGL 4.3 compute shaders "
                   "over buffers"),
                2, text_style::disabled);

  ImGui::Text(tr("live: %s, %.0f steps/s (stepping alone)"), tr(backend_name(the_scene.backend())),
              the_scene.stepping_rate());
  show_renderer(the_scene);
  const std::string measure_label =
      format(tr("Measure all (M): %d steps each, on copies"), steps_per_backend_measurement) +
      "###measure all";
  if (ImGui::Button(measure_label.c_str()))
    actions.measure_backends = true;
  const backend_comparison& comparison = the_scene.comparison();
  const auto rate = [](double steps_per_second) {
    return steps_per_second > 0.0 ? format("%.0f", steps_per_second) : std::string("-");
  };
  if (!comparison.measured) {
    fixed_lines(tr("N = -  steps/s: CPU -  GPU -  compute -  (not measured)"), 1,
                text_style::disabled);
    fixed_lines("", 1);
  } else {
    fixed_lines(format(tr("N = %d  steps/s: CPU %s  GPU %s  compute %s"), comparison.grid_size,
                       rate(comparison.cpu_steps_per_second).c_str(),
                       rate(comparison.gpu_steps_per_second).c_str(),
                       rate(comparison.compute_steps_per_second).c_str()),
                1);
    const double cpu = comparison.cpu_steps_per_second;
    if (comparison.gpu_steps_per_second <= 0.0)
      fixed_lines(comparison.gpu_error, 1, text_style::coloured, warning_red);
    else if (comparison.grid_size != the_scene.cloth_stage.grid_size())
      fixed_lines(tr("measured for another N: measure again"), 1, text_style::disabled);
    else if (comparison.compute_steps_per_second > 0.0)
      fixed_lines(
          format(tr("GPU/CPU = %.2f x   compute/CPU = %.2f x"),
                 comparison.gpu_steps_per_second / cpu, comparison.compute_steps_per_second / cpu),
          1);
    else
      fixed_lines(format(tr("GPU/CPU = %.2f x   compute: %s"),
                         comparison.gpu_steps_per_second / cpu, comparison.compute_error.c_str()),
                  1);
  }
  fixed_lines(format(tr("read-backs of the GPU state so far: %ld (only for this panel's images and "
                        "the energy plot, at most %.0f/s)"),
                     the_scene.readbacks(), scene::max_readbacks_per_second),
              2, text_style::disabled);
  show_state_textures(the_scene);
  ImGui::PushTextWrapPos(0.0f);
  // BEGIN TEACHER: the answer to question 11, which the student copy leaves to the student
  ImGui::TextDisabled(tr(
      "Q11: every particle is one texel of N x N float (RGBA32F) textures: positions (w: "
      "pinned) and velocities, two copies each that swap after every step (ping-pong), and the "
      "normals. The simulation runs in fragment shaders: a triangle covering an N x N viewport "
      "runs one fragment per particle, which sums its springs, gravity and wind, integrates, "
      "applies the ground and writes the new state into the other copy; a second pass writes the "
      "normals. The CPU sends a flat N x N grid once; the vertex shader fetches each vertex's "
      "position and normal from the textures. The divergence check runs on the GPU; the state "
      "comes back to the CPU only for these images and the energy plot."));
  // END TEACHER
  ImGui::PopTextWrapPos();
}

}  // namespace clothlab
