#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "core/i18n.hpp"
#include "gl/render_geometry.hpp"  // chain_mass_radius, drawn_mass_radius
#include "window/layout_probe.hpp"
#include "window/run_statistics.hpp"  // intact_spring_count
#include "window/scene.hpp"

namespace clothlab {

// ---- The mouse on the cloth and the masses (model.md, "drag") ------------------------------

pick_ray scene::ray_at(double x, double y) const {
  const double ndc_x = 2.0 * (x - viewport_left_) / viewport_width_ - 1.0;
  const double ndc_y = 1.0 - 2.0 * y / viewport_height_;
  const float aspect = static_cast<float>(viewport_width_) / static_cast<float>(viewport_height_);
  return ray_through(view, aspect, ndc_x, ndc_y);
}

double scene::radians_per_pixel() const {
  return static_cast<double>(view.field_of_view) / viewport_height_;
}

std::optional<glm::dvec2> scene::framebuffer_point(const glm::dvec3& point) const {
  const float aspect = static_cast<float>(viewport_width_) / static_cast<float>(viewport_height_);
  const glm::dvec4 clip =
      glm::dmat4(view.projection(aspect)) * glm::dmat4(view.view()) * glm::dvec4(point, 1.0);
  if (clip.w <= 0.0)
    return std::nullopt;
  return glm::dvec2(viewport_left_ + (clip.x / clip.w + 1.0) / 2.0 * viewport_width_,
                    (1.0 - clip.y / clip.w) / 2.0 * viewport_height_);
}

mass_drag_parameters* scene::mass_drag() {
  return const_cast<mass_drag_parameters*>(std::as_const(*this).mass_drag());
}

const mass_drag_parameters* scene::mass_drag() const {
  return stage_ == stage_kind::spring    ? &spring_stage.parameters.drag
         : stage_ == stage_kind::coupled ? &chain_stage.parameters.drag
                                         : nullptr;
}

const particle_system& scene::mass_particles() const {
  return stage_ == stage_kind::spring ? spring_stage.particles() : chain_stage.particles();
}

bool scene::grabbing() const {
  if (const mass_drag_parameters* drag = mass_drag())
    return drag->enabled;
  return cloth_stage.parameters.drag.enabled;
}

glm::dvec3 scene::drag_target() const {
  if (const mass_drag_parameters* drag = mass_drag())
    return drag->target;
  return cloth_stage.parameters.drag.target;
}

bool scene::grab_particle(const pick_ray& ray, double max_angle) {
  if (status().diverged)
    return false;
  if (mass_drag_parameters* drag = mass_drag()) {  // stages 1 and 2: a mass
    const particle_system& particles = mass_particles();
    // The spheres as drawn: at least a few pixels wide, however far the view.
    const float metres_per_pixel = view.metres_per_pixel(static_cast<float>(viewport_height_));
    const std::optional<std::size_t> picked =
        pick_mass(particles, ray, drawn_mass_radius(chain_mass_radius, metres_per_pixel),
                  drawn_mass_radius(chain_fixed_point_radius, metres_per_pixel), max_angle);
    if (!picked)
      return false;
    const std::string stage = std::string(stage_name(stage_));
    if (particles.is_fixed[*picked]) {
      std::printf(
          tr("clothlab-window: %s\n"),
          format(tr("p%zu of %s is fixed: it cannot be dragged"), *picked, stage_in_words(stage_))
              .c_str());
      std::fflush(stdout);
      return false;
    }
    const glm::dvec3 position = particles.get_position(*picked);
    drag->enabled = true;
    drag->mass = static_cast<int>(*picked);
    drag->target = position;
    grab_plane_point_ = position;
    window_log("grabbed mass %zu of the %s stage at (%.3f, %.3f, %.3f)", *picked, stage.c_str(),
               position.x, position.y, position.z);
    return true;
  }
  if (cloth_on_gpu())
    read_gpu_state();  // the positions the user sees, once, at the press
  const std::optional<std::size_t> picked = pick_particle(cloth_stage, ray, max_angle);
  if (!picked)
    return false;
  const int n = cloth_stage.grid_size();
  const int ku = static_cast<int>(*picked % static_cast<std::size_t>(n));
  const int kv = static_cast<int>(*picked / static_cast<std::size_t>(n));
  const glm::dvec3 position = cloth_stage.particles().get_position(*picked);
  if (cloth_stage.particles().is_fixed[*picked]) {
    std::printf(tr("clothlab-window: %s\n"),
                format(tr("particle (%d, %d) is pinned: it cannot be dragged"), ku, kv).c_str());
    std::fflush(stdout);
    return false;
  }
  drag_parameters& drag = cloth_stage.parameters.drag;
  drag.enabled = true;
  drag.ku = ku;
  drag.kv = kv;
  drag.target = position;
  grab_plane_point_ = position;
  window_log("grabbed particle (%d, %d) at (%.3f, %.3f, %.3f)", ku, kv, position.x, position.y,
             position.z);
  return true;
}

void scene::drag_grabbed(const pick_ray& ray) {
  if (!grabbing())
    return;
  const glm::dvec3 target = point_on_plane(ray, grab_plane_point_, viewing_direction(view));
  if (mass_drag_parameters* drag = mass_drag())
    drag->target = target;
  else
    cloth_stage.parameters.drag.target = target;
}

void scene::release_grab() {
  if (!grabbing())
    return;
  const glm::dvec3 position = grabbed_position();
  if (mass_drag_parameters* drag = mass_drag()) {
    drag->enabled = false;
    window_log("released mass %d of the %s stage at (%.3f, %.3f, %.3f), target (%.3f, %.3f, %.3f)",
               drag->mass, std::string(stage_name(stage_)).c_str(), position.x, position.y,
               position.z, drag->target.x, drag->target.y, drag->target.z);
    return;
  }
  drag_parameters& drag = cloth_stage.parameters.drag;
  drag.enabled = false;
  const std::size_t springs =
      intact_spring_count(cloth_stage);  // fewer than at the start when it tore
  window_log(
      "released particle (%d, %d) at (%.3f, %.3f, %.3f), target (%.3f, %.3f, %.3f), %zu "
      "springs",
      drag.ku, drag.kv, position.x, position.y, position.z, drag.target.x, drag.target.y,
      drag.target.z, springs);
}

glm::dvec3 scene::grabbed_position() {
  if (const mass_drag_parameters* mass = mass_drag()) {
    const particle_system& particles = mass_particles();
    return particles.get_position(
        std::min(static_cast<std::size_t>(std::max(mass->mass, 0)), particles.size() - 1));
  }
  const drag_parameters& drag = cloth_stage.parameters.drag;
  const int n = cloth_stage.grid_size();
  const std::size_t k =
      spring_mesh::index(std::clamp(drag.ku, 0, n - 1), std::clamp(drag.kv, 0, n - 1), n);
  return paths_.position(k);  // on a GPU path, one texel read back
}

void scene::start_sphere_move(const pick_ray& ray) {
  const sphere_parameters& sphere = cloth_stage.parameters.sphere;
  sphere_plane_point_ = sphere.centre;
  sphere_grab_offset_ = point_on_plane(ray, sphere.centre, viewing_direction(view)) - sphere.centre;
}

void scene::move_sphere(const pick_ray& ray) {
  cloth_stage.parameters.sphere.centre =
      point_on_plane(ray, sphere_plane_point_, viewing_direction(view)) - sphere_grab_offset_;
}

}  // namespace clothlab
