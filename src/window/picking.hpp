// The mouse on the cloth and on the masses of stages 1 and 2 (model.md, "drag"): which particle
// is under the cursor, and where the cursor is in the plane facing the camera through a point.
// Geometry only, no GL: the window's mouse handler (window_app.cpp) and the scene
// (scene_mouse.cpp) call these, and the tests run them alone.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <optional>

#include "core/particle_system.hpp"
#include "core/spring_mesh.hpp"
#include "gl/camera.hpp"

namespace clothlab {

// A ray from the eye through a point of the screen: origin + t direction, t >= 0.
struct pick_ray {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};  // unit
};

// The ray through the point (ndc_x, ndc_y) of the view, in normalised device coordinates (-1 to
// 1 from left to right and from bottom to top) of a viewport with this aspect (width / height).
pick_ray ray_through(const camera& view, float aspect, double ndc_x, double ndc_y);

// The particle the user means by pressing on the cloth along `ray`:
//  - the ray hits a drawn triangle of the cloth (each cell split along its (ku, kv)-(ku+1, kv+1)
//    diagonal; a torn triangle is not there): the vertex of the nearest such triangle closest
//    to the hit point;
//  - it hits none: the particle nearest to the ray within max_angle (rad, as seen from the eye:
//    a few pixels times the view's radians per pixel), for a press on the cloth's very edge.
// nullopt when neither. Pinned particles are returned like the others (the caller refuses them).
std::optional<std::size_t> pick_particle(const spring_mesh& cloth, const pick_ray& ray,
                                         double max_angle);

// The mass of stage 1 or 2 the user means by pressing along `ray`, the masses drawn as spheres
// (moving masses of radius mass_radius, fixed ones of radius fixed_radius, m):
//  - the ray crosses spheres: the particle whose sphere it crosses first (nearest the eye);
//  - it crosses none: the particle nearest to the ray within max_angle (rad, as seen from the
//    eye), for a press just beside a mass.
// nullopt when neither. The fixed p0 is returned like the others (the caller refuses it).
std::optional<std::size_t> pick_mass(const particle_system& particles, const pick_ray& ray,
                                     double mass_radius, double fixed_radius, double max_angle);

// Where the ray meets the plane through `point` whose normal is `normal` (the camera's viewing
// direction): the point under the cursor at the grabbed point's depth. A ray parallel to the
// plane (never for a camera-facing plane in front of the eye) gives `point` itself.
glm::dvec3 point_on_plane(const pick_ray& ray, const glm::dvec3& point, const glm::dvec3& normal);

// The camera's viewing direction, unit, from the eye towards the target.
glm::dvec3 viewing_direction(const camera& view);

}  // namespace clothlab
