// The renderer's scenery: the sky, the ground, the soft shadows, the spheres (masses, pins, the
// obstacle) and the wind's arrow (renderer_impl.hpp).
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gl/renderer_impl.hpp"

namespace clothlab {

// The sky, after the opaque geometry and before anything blended: it lies on the far plane and
// is drawn only where nothing else is (depth test, no depth write), so that no pixel is shaded
// twice (on a software rasteriser the background and the ground are most of a frame's work).
void renderer::impl::draw_background(const frame& f) {
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_LEQUAL);
  background_program.use();
  background_program.set("inverse_view_projection", glm::inverse(f.view_projection));
  background_program.set("horizon_colour", horizon_colour);
  background_program.set("sky_colour", sky_colour);
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
}

void renderer::impl::set_ground_uniforms(const shader_program& program, const frame& f,
                                         float height, const glm::vec2& centre,
                                         float light_fraction) {
  program.use();
  program.set("view_projection", f.view_projection);
  program.set("ground_height", height);
  program.set("tile_size", tile_size);
  program.set("light_tile_colour", light_tile_colour);
  program.set("dark_tile_colour", dark_tile_colour);
  program.set("horizon_colour", horizon_colour);
  program.set("fade_centre", centre);
  program.set("fade_start", fade_start);
  program.set("fade_end", fade_end);
  program.set("light_fraction", light_fraction);
  // For the cloth's shadow, whose vertex shader squashes the cloth onto the ground.
  program.set("project_onto_ground", 1);
  program.set("light_direction", light_direction);
}

void renderer::impl::draw_ground(const frame& f, float height, const glm::vec2& centre) {
  set_ground_uniforms(ground_program, f, height, centre, 1.0f);
  // Pushed back in depth so that cloth lying on the ground (z = z_g exactly) stays in front.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, ground_offset_units);
  glBindVertexArray(ground_vao);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

// Question 13: an arrow along the wind direction u_w above the cloth, longer for a stronger wind
// (K_w). A shaft and a head of two crossed triangles, seen from any side.
void renderer::impl::draw_wind_arrow(const frame& f, const spring_mesh& cloth) {
  const cloth_parameters& p = cloth.parameters;
  if (!(p.wind_strength > 0.0) || p.wind_direction == glm::dvec3(0.0))
    return;
  const particle_system& particles = cloth.particles();
  glm::dvec3 centre(0.0);
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    centre += particles.get_position(k);
    top = std::max(top, particles.get_position(k).z);
  }
  centre /= static_cast<double>(std::max<std::size_t>(particles.size(), 1));
  centre.z = top + wind_arrow_height;
  const glm::vec3 direction = glm::normalize(glm::vec3(p.wind_direction));
  const auto length = static_cast<float>(0.3 + 0.03 * std::min(p.wind_strength, 50.0));  // m
  const glm::vec3 tip = glm::vec3(centre) + 0.5f * length * direction;
  const glm::vec3 tail = tip - length * direction;
  const glm::vec3 base = tip - 0.16f * direction;
  // Two directions across the arrow.
  const glm::vec3 helper =
      std::abs(direction.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 across = 0.07f * glm::normalize(glm::cross(direction, helper));
  const glm::vec3 across2 = 0.07f * glm::normalize(glm::cross(direction, across));
  floats.clear();
  const auto add = [this](const glm::vec3& v) { floats.insert(floats.end(), {v.x, v.y, v.z}); };
  // The shaft: a thin cross of four lines (lines are 1 px wide).
  for (const glm::vec3& offset :
       {glm::vec3(0.0f), 0.1f * across, -0.1f * across, 0.1f * across2, -0.1f * across2}) {
    add(tail + offset);
    add(base + offset);
  }
  for (const glm::vec3& side : {across, across2}) {
    add(tip);
    add(base + side);
    add(base - side);
  }
  coil_points.upload(floats);
  flat_program.use();
  flat_program.set("view_projection", f.view_projection);
  flat_program.set("project_onto_ground", 0);
  flat_program.set("flat_colour", wind_arrow_colour);
  glBindVertexArray(coil_vao);
  glDrawArrays(GL_LINES, 0, 10);
  glDrawArrays(GL_TRIANGLES, 10, 6);
}

// Multiplies the ground's colour by each blob's shade: in front of the ground (its polygon
// offset), behind whatever stands on it, writing no depth.
void renderer::impl::draw_blob_shadows(const frame& f, float height) {
  if (blobs.empty())
    return;
  blob_instances.upload({glm::value_ptr(blobs[0]), blobs.size() * 4});
  blob_shadow_program.use();
  blob_shadow_program.set("view_projection", f.view_projection);
  blob_shadow_program.set("ground_height", height);
  glEnable(GL_BLEND);
  glBlendFunc(GL_DST_COLOR, GL_ZERO);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 4.0f);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glBindVertexArray(blob_vao);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(blobs.size()));
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_BLEND);
}

// The obstacle sphere's shadow: a soft disc where the sphere's centre projects onto the ground
// along the light.
void renderer::impl::draw_obstacle_shadow(const frame& f, const sphere_parameters& sphere,
                                          float ground_height) {
  const glm::vec3 centre(sphere.centre);
  const auto radius = static_cast<float>(sphere.radius);
  const float height = centre.z - ground_height;
  if (height < -radius)
    return;  // entirely under the ground
  const glm::vec3 on_ground = centre - std::max(height, 0.0f) / light_direction.z * light_direction;
  blobs.assign(1, glm::vec4(on_ground.x, on_ground.y, 1.3f * radius + 0.1f * height,
                            0.55f / (1.0f + std::max(height - radius, 0.0f))));
  draw_blob_shadows(f, ground_height);
}

void renderer::impl::add_sphere(const glm::vec3& centre, float radius, const glm::vec3& colour) {
  instances.insert(instances.end(),
                   {centre.x, centre.y, centre.z, radius, colour.r, colour.g, colour.b});
}

void renderer::impl::draw_spheres(const frame& f, float depth_push) {
  if (instances.empty())
    return;
  sphere_instances.upload(instances);
  spheres_program.use();
  spheres_program.set("view_projection", f.view_projection);
  spheres_program.set("depth_push", depth_push);
  spheres_program.set("use_texture", 0);
  spheres_program.set("light_direction", light_direction);
  spheres_program.set("eye_position", f.eye);
  spheres_program.set("back_tint", glm::vec3(1.0f));
  spheres_program.set("shininess", 60.0f);
  spheres_program.set("specular_strength", 0.45f);
  glBindVertexArray(sphere_vao);
  glDrawElementsInstanced(GL_TRIANGLES, sphere_index_count, GL_UNSIGNED_INT, nullptr,
                          static_cast<GLsizei>(instances.size() / floats_per_sphere));
}

}  // namespace clothlab
