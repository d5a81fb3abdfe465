#include "window/picking.hpp"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <array>
#include <cmath>
#include <limits>

namespace clothlab {
namespace {

// Möller-Trumbore: the ray parameter t at which the ray crosses triangle (a, b, c), or nullopt.
std::optional<double> ray_triangle(const pick_ray& ray, const glm::dvec3& a, const glm::dvec3& b,
                                   const glm::dvec3& c) {
  const glm::dvec3 edge1 = b - a;
  const glm::dvec3 edge2 = c - a;
  const glm::dvec3 across = glm::cross(ray.direction, edge2);
  const double determinant = glm::dot(edge1, across);
  if (std::abs(determinant) < 1e-14)
    return std::nullopt;  // the ray runs along the triangle's plane
  const double inverse = 1.0 / determinant;
  const glm::dvec3 from_a = ray.origin - a;
  const double u = glm::dot(from_a, across) * inverse;
  if (u < 0.0 || u > 1.0)
    return std::nullopt;
  const glm::dvec3 q = glm::cross(from_a, edge1);
  const double v = glm::dot(ray.direction, q) * inverse;
  if (v < 0.0 || u + v > 1.0)
    return std::nullopt;
  const double t = glm::dot(edge2, q) * inverse;
  if (t <= 0.0)
    return std::nullopt;
  return t;
}

// The particle seen nearest to the ray, within max_angle (rad, from the eye); particles behind
// the eye are not seen.
std::optional<std::size_t> nearest_within_angle(const particle_system& particles,
                                                const pick_ray& ray, double max_angle) {
  std::optional<std::size_t> best;
  double best_angle = max_angle;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const glm::dvec3 to_particle = particles.get_position(k) - ray.origin;
    const double along = glm::dot(to_particle, ray.direction);
    if (along <= 0.0)
      continue;  // behind the eye
    const double across = glm::length(to_particle - along * ray.direction);
    const double angle = std::atan2(across, along);
    if (angle <= best_angle) {
      best_angle = angle;
      best = k;
    }
  }
  return best;
}

// The ray parameter t > 0 at which the ray enters the sphere (centre, radius), or nullopt.
// With d the unit direction and o = origin - centre: t^2 + 2 (o.d) t + |o|^2 - r^2 = 0.
std::optional<double> ray_sphere(const pick_ray& ray, const glm::dvec3& centre, double radius) {
  const glm::dvec3 o = ray.origin - centre;
  const double half_b = glm::dot(o, ray.direction);
  const double c = glm::dot(o, o) - radius * radius;
  const double discriminant = half_b * half_b - c;
  if (discriminant < 0.0)
    return std::nullopt;
  const double root = std::sqrt(discriminant);
  const double t = -half_b - root >= 0.0 ? -half_b - root : -half_b + root;  // eye inside: exit
  if (t < 0.0)
    return std::nullopt;
  return t;
}

}  // namespace

pick_ray ray_through(const camera& view, float aspect, double ndc_x, double ndc_y) {
  const glm::dmat4 inverse =
      glm::inverse(glm::dmat4(view.projection(aspect)) * glm::dmat4(view.view()));
  const glm::dvec4 near_point = inverse * glm::dvec4(ndc_x, ndc_y, -1.0, 1.0);
  const glm::dvec4 far_point = inverse * glm::dvec4(ndc_x, ndc_y, 1.0, 1.0);
  const glm::dvec3 from = glm::dvec3(near_point) / near_point.w;
  const glm::dvec3 to = glm::dvec3(far_point) / far_point.w;
  return {from, glm::normalize(to - from)};
}

std::optional<std::size_t> pick_particle(const spring_mesh& cloth, const pick_ray& ray,
                                         double max_angle) {
  const int n = cloth.grid_size();
  const particle_system& particles = cloth.particles();
  if (n < 2 || particles.size() != static_cast<std::size_t>(n) * static_cast<std::size_t>(n))
    return std::nullopt;

  // 1. The nearest drawn triangle the ray crosses; its vertex nearest to the crossing.
  double nearest_t = std::numeric_limits<double>::infinity();
  std::array<std::size_t, 3> nearest_triangle{};
  for (int kv = 0; kv + 1 < n; ++kv) {
    for (int ku = 0; ku + 1 < n; ++ku) {
      for (const bool upper : {false, true}) {
        if (!cloth.triangle_intact(ku, kv, upper))
          continue;
        const std::array<std::size_t, 3> corners = {
            spring_mesh::index(ku, kv, n),
            upper ? spring_mesh::index(ku + 1, kv + 1, n) : spring_mesh::index(ku + 1, kv, n),
            upper ? spring_mesh::index(ku, kv + 1, n) : spring_mesh::index(ku + 1, kv + 1, n)};
        const std::optional<double> t =
            ray_triangle(ray, particles.get_position(corners[0]),
                         particles.get_position(corners[1]), particles.get_position(corners[2]));
        if (t && *t < nearest_t) {
          nearest_t = *t;
          nearest_triangle = corners;
        }
      }
    }
  }
  if (std::isfinite(nearest_t)) {
    const glm::dvec3 hit = ray.origin + nearest_t * ray.direction;
    std::size_t best = nearest_triangle[0];
    for (const std::size_t k : nearest_triangle) {
      if (glm::length(particles.get_position(k) - hit) <
          glm::length(particles.get_position(best) - hit))
        best = k;
    }
    return best;
  }

  // 2. No triangle: the particle seen nearest to the ray, within max_angle.
  return nearest_within_angle(particles, ray, max_angle);
}

std::optional<std::size_t> pick_mass(const particle_system& particles, const pick_ray& ray,
                                     double mass_radius, double fixed_radius, double max_angle) {
  // 1. The first drawn sphere the ray crosses.
  std::optional<std::size_t> first;
  double first_t = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const double radius = particles.is_fixed[k] ? fixed_radius : mass_radius;
    const std::optional<double> t = ray_sphere(ray, particles.get_position(k), radius);
    if (t && *t < first_t) {
      first_t = *t;
      first = k;
    }
  }
  if (first)
    return first;
  // 2. None: the particle seen nearest to the ray, within max_angle.
  return nearest_within_angle(particles, ray, max_angle);
}

glm::dvec3 point_on_plane(const pick_ray& ray, const glm::dvec3& point, const glm::dvec3& normal) {
  const double facing = glm::dot(ray.direction, normal);
  if (std::abs(facing) < 1e-12)
    return point;
  const double t = glm::dot(point - ray.origin, normal) / facing;
  return ray.origin + t * ray.direction;
}

glm::dvec3 viewing_direction(const camera& view) {
  return glm::normalize(glm::dvec3(view.target) - glm::dvec3(view.eye()));
}

}  // namespace clothlab
