// The renderer's cloth: its buffers, built again when N or the springs change, and its drawing
// from the CPU's arrays or from the GPU's textures (renderer_impl.hpp).
#include <algorithm>
#include <chrono>
#include <cstdint>

#include "gl/renderer_impl.hpp"

namespace clothlab {

void renderer::impl::ensure_cloth_buffers(const spring_mesh& cloth) {
  std::size_t spring_count = 0;
  for (const spring_family family : all_spring_families) {
    spring_count += cloth.springs(family).size();
  }
  const int n = cloth.grid_size();
  if (n == cloth_grid_size && spring_count == cloth_spring_count && cloth_vao != 0)
    return;
  cloth_grid_size = n;
  cloth_spring_count = spring_count;

  if (cloth_vao == 0) {
    glGenVertexArrays(1, &cloth_vao);
    glGenVertexArrays(1, &texture_cloth_vao);
    for (GLuint* buffer : {&cloth_position_vbo, &cloth_normal_vbo, &cloth_grid_coordinates_vbo,
                           &cloth_texel_vbo, &cloth_ebo}) {
      glGenBuffers(1, buffer);
    }
  }
  const auto particle_count = static_cast<GLsizeiptr>(n) * n;
  const std::vector<float> grid_coordinates = make_grid_texture_coordinates(n);
  const std::vector<std::int32_t> texels = make_grid_texels(n);
  cloth_index_ranges = make_cloth_indices(cloth);

  glBindBuffer(GL_ARRAY_BUFFER, cloth_position_vbo);
  glBufferData(GL_ARRAY_BUFFER, particle_count * 3 * GLsizeiptr{sizeof(float)}, nullptr,
               GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_normal_vbo);
  glBufferData(GL_ARRAY_BUFFER, particle_count * 3 * GLsizeiptr{sizeof(float)}, nullptr,
               GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_grid_coordinates_vbo);
  glBufferData(GL_ARRAY_BUFFER, byte_size(grid_coordinates), grid_coordinates.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_texel_vbo);
  glBufferData(GL_ARRAY_BUFFER, byte_size(texels), texels.data(), GL_STATIC_DRAW);

  // CPU path: positions and normals streamed each frame.
  glBindVertexArray(cloth_vao);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, cloth_ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, byte_size(cloth_index_ranges.indices),
               cloth_index_ranges.indices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_position_vbo);
  glEnableVertexAttribArray(position_or_texel_location);
  glVertexAttribPointer(position_or_texel_location, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_normal_vbo);
  glEnableVertexAttribArray(normal_location);
  glVertexAttribPointer(normal_location, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_grid_coordinates_vbo);
  glEnableVertexAttribArray(grid_coordinates_location);
  glVertexAttribPointer(grid_coordinates_location, 2, GL_FLOAT, GL_FALSE, 0, nullptr);

  // GPU path: the flat grid of texels, same indices.
  glBindVertexArray(texture_cloth_vao);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, cloth_ebo);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_texel_vbo);
  glEnableVertexAttribArray(position_or_texel_location);
  glVertexAttribIPointer(position_or_texel_location, 2, GL_INT, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, cloth_grid_coordinates_vbo);
  glEnableVertexAttribArray(grid_coordinates_location);
  glVertexAttribPointer(grid_coordinates_location, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
}

void renderer::impl::draw_cloth(const frame& f, const spring_mesh& cloth,
                                const render_settings& settings, const cloth_programs& programs,
                                GLuint vao) {
  const bool show_ground = cloth.parameters.ground_enabled && settings.show_ground;
  const auto ground_height = static_cast<float>(cloth.parameters.ground_height);
  if (show_ground) {
    draw_ground(f, ground_height, {0.0f, 0.0f});
    if (cloth.parameters.sphere.enabled)
      draw_obstacle_shadow(f, cloth.parameters.sphere, ground_height);
  }

  const auto draw_range = [](GLenum mode, const index_range& range) {
    glDrawElements(mode, static_cast<GLsizei>(range.count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(range.first * sizeof(std::uint32_t)));
  };
  // The surface: the CPU cloth's intact triangles by index; the GPU cloth's every triangle
  // (draw_from_textures), its vertex shaders collapsing those that lost a spring.
  const auto draw_triangles = [&] {
    if (vao != texture_cloth_vao) {
      draw_range(GL_TRIANGLES, cloth_index_ranges.triangles);
      return;
    }
    const GLsizei cells = (cloth.grid_size() - 1) * (cloth.grid_size() - 1);
    glBindVertexArray(empty_vao);
    // The shadow's shader also declares the lines' integer input `texel`, unused here: with no
    // array it reads the generic value, which WebGL requires to be an integer one too.
    glVertexAttribI4i(position_or_texel_location, 0, 0, 0, 0);
    glDrawArrays(GL_TRIANGLES, 0, 6 * cells);
    glBindVertexArray(vao);
  };

  glActiveTexture(GL_TEXTURE0 + cloth_texture_unit);
  glBindTexture(GL_TEXTURE_2D, cloth_texture);
  const shader_program& surface = programs.surface;
  surface.use();
  surface.set("view_projection", f.view_projection);
  surface.set("use_texture", 1);
  surface.set("light_direction", light_direction);
  surface.set("eye_position", f.eye);
  surface.set("back_tint", cloth_back_tint);
  surface.set("shininess", 24.0f);
  surface.set("specular_strength", 0.12f);
  // Surfaces are pushed back in depth so that lines lying on them are drawn in front.
  // Two layers of a cloth folded flat on the ground lie at z = z_g exactly (the ground contact
  // puts every particle below it there): their depths tie, and the rasteriser's rounding would pick
  // the layer pixel by pixel, differently from frame to frame as the cloth moves (they would
  // flicker through each other). The tie is broken the same way everywhere: the side facing
  // away from the eye (a layer folded over, back side up) a few depth units nearer than the
  // side facing it. The triangles are wound counter-clockwise seen from their normal's side
  // (render_geometry.hpp), so GL's front faces are the cloth's.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_CULL_FACE);
  glBindVertexArray(vao);
  glCullFace(GL_BACK);
  glPolygonOffset(1.0f, front_offset_units);
  draw_triangles();
  glCullFace(GL_FRONT);
  glPolygonOffset(1.0f, back_offset_units);
  draw_triangles();
  glDisable(GL_CULL_FACE);
  glDisable(GL_POLYGON_OFFSET_FILL);

  if (show_ground) {
    // The cloth's shadow: the ground drawn again, darker, over the cloth's triangles squashed
    // onto it along the light. Every fragment of it computes the same colour, so where two
    // triangles overlap the shadow is not darkened twice; the cloth in front of it (even lying
    // on the ground) keeps it hidden.
    set_ground_uniforms(programs.shadow, f, ground_height, {0.0f, 0.0f}, light_fraction_in_shadow);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, shadow_offset_units);  // in front of the ground, behind the cloth
    glDepthFunc(GL_LEQUAL);
    draw_triangles();
    glDepthFunc(GL_LESS);
    glDisable(GL_POLYGON_OFFSET_FILL);
  }

  if (settings.show_wind)
    draw_wind_arrow(f, cloth);
  draw_background(f);
  glBindVertexArray(vao);  // the cloth's again, for its lines

  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  const shader_program& flat = programs.lines;
  flat.use();
  flat.set("view_projection", f.view_projection);
  flat.set("project_onto_ground", 0);

  // Lines are hidden by the surface but not by each other (a bending spring runs along two
  // structural ones): they test depth without writing it.
  glDepthMask(GL_FALSE);
  if (settings.wireframe) {
    flat.set("flat_colour", wireframe_colour);
    draw_range(GL_LINES, cloth_index_ranges.edges);
  }
  if (settings.show_springs) {
    // Bending first, so that the structural springs (the grid itself) are drawn on top.
    for (const spring_family family :
         {spring_family::bending, spring_family::shear, spring_family::structural}) {
      const auto i = static_cast<std::size_t>(family);
      flat.set("flat_colour", spring_family_colours[i]);
      draw_range(GL_LINES, cloth_index_ranges.springs[i]);
    }
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);

  // Pinned particles never move: their positions in `cloth` are valid on the GPU path too.
  instances.clear();
  if (cloth.parameters.sphere.enabled) {
    const sphere_parameters& sphere = cloth.parameters.sphere;
    const auto radius = static_cast<float>(sphere.radius);
    const float spacing = static_cast<float>(cloth.parameters.side_length) /
                          static_cast<float>(std::max(cloth.grid_size() - 1, 1));
    add_sphere(glm::vec3(sphere.centre), obstacle_drawn_fraction * radius, obstacle_colour);
    draw_spheres(f, std::min(obstacle_depth_push * spacing, 0.2f * radius));
    instances.clear();
  }
  const particle_system& particles = cloth.particles();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      add_sphere(particles.get_position(k), pin_radius, pin_colour);
  }
  draw_spheres(f);
  glBindVertexArray(0);
}

glm::vec4 spring_family_colour(spring_family family) {
  return spring_family_colours[static_cast<std::size_t>(family)];
}

void renderer::draw(const spring_mesh& cloth, const camera& view, const render_settings& settings,
                    int width, int height, int left) {
  impl_->ensure_cloth_buffers(cloth);
  // Normals of the current positions (model.md: central differences), not those of the start
  // of the last step.
  const auto& position = cloth.particles().position;
  impl_->normals.resize(position.size());
  const auto normals_start = std::chrono::steady_clock::now();
  compute_vertex_normals(cloth.grid_size(), position, impl_->normals);
  impl_->normals_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - normals_start).count();

  convert_to_float(position, impl_->floats);
  glBindBuffer(GL_ARRAY_BUFFER, impl_->cloth_position_vbo);
  glBufferSubData(GL_ARRAY_BUFFER, 0, byte_size(impl_->floats), impl_->floats.data());
  convert_to_float(impl_->normals, impl_->floats);
  glBindBuffer(GL_ARRAY_BUFFER, impl_->cloth_normal_vbo);
  glBufferSubData(GL_ARRAY_BUFFER, 0, byte_size(impl_->floats), impl_->floats.data());

  const frame f = impl_->begin_frame(view, left, width, height);
  impl_->draw_cloth(f, cloth, settings, impl_->cpu_cloth, impl_->cloth_vao);
  glDisable(GL_SCISSOR_TEST);
}

double renderer::last_normals_seconds() const {
  return impl_->normals_seconds;
}

void renderer::draw_from_textures(GLuint position_texture, GLuint normal_texture,
                                  const spring_mesh& cloth, const camera& view,
                                  const render_settings& settings, int width, int height, int left,
                                  GLuint spring_mask_texture) {
  impl_->ensure_cloth_buffers(cloth);
  const frame f = impl_->begin_frame(view, left, width, height);
  glActiveTexture(GL_TEXTURE0 + position_texture_unit);
  glBindTexture(GL_TEXTURE_2D, position_texture);
  glActiveTexture(GL_TEXTURE0 + normal_texture_unit);
  glBindTexture(GL_TEXTURE_2D, normal_texture);
  glActiveTexture(GL_TEXTURE0 + spring_mask_texture_unit);
  glBindTexture(GL_TEXTURE_2D, spring_mask_texture);
  // The triangles come from gl_VertexID (cell, corner) and are left out where the mask says a
  // spring of theirs tore; without a mask, all are drawn.
  for (const shader_program* program :
       {&impl_->texture_cloth.surface, &impl_->texture_cloth.shadow, &impl_->texture_cloth.lines}) {
    program->use();
    program->set("spring_mask_texture", spring_mask_texture_unit);
    program->set("use_spring_mask", spring_mask_texture != 0 ? 1 : 0);
    program->set("grid_size", cloth.grid_size());
    program->set("triangles_from_vertex_id", program != &impl_->texture_cloth.lines ? 1 : 0);
  }
  impl_->draw_cloth(f, cloth, settings, impl_->texture_cloth, impl_->texture_cloth_vao);
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace clothlab
