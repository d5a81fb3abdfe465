#include "gl/renderer.hpp"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/i18n.hpp"
#include "gl/renderer_impl.hpp"

namespace clothlab {

renderer::impl::~impl() {
  glDeleteTextures(1, &cloth_texture);
  const GLuint arrays[] = {empty_vao, ground_vao,        sphere_vao, coil_vao,
                           cloth_vao, texture_cloth_vao, blob_vao};
  glDeleteVertexArrays(static_cast<GLsizei>(std::size(arrays)), arrays);
  const GLuint buffers[] = {
      ground_vbo,      sphere_vbo,         sphere_ebo,       sphere_instances.id,
      coil_points.id,  cloth_position_vbo, cloth_normal_vbo, cloth_grid_coordinates_vbo,
      cloth_texel_vbo, cloth_ebo,          blob_instances.id};
  glDeleteBuffers(static_cast<GLsizei>(std::size(buffers)), buffers);
}

bool renderer::impl::load_programs(std::string& error) {
  struct program_files {
    shader_program* program;
    const char* vertex;
    const char* fragment;
  };
  const program_files programs[] = {
      {&background_program, "draw_background.vert", "draw_background.frag"},
      {&ground_program, "draw_ground.vert", "draw_ground.frag"},
      {&flat_program, "draw_flat.vert", "draw_flat.frag"},
      {&cpu_cloth.surface, "draw_cloth.vert", "draw_lit.frag"},
      {&cpu_cloth.shadow, "draw_flat.vert", "draw_ground.frag"},
      {&cpu_cloth.lines, "draw_flat.vert", "draw_flat.frag"},
      {&texture_cloth.surface, "draw_cloth_from_textures.vert", "draw_lit.frag"},
      {&texture_cloth.shadow, "draw_flat_from_texture.vert", "draw_ground.frag"},
      {&texture_cloth.lines, "draw_flat_from_texture.vert", "draw_flat.frag"},
      {&spheres_program, "draw_spheres.vert", "draw_lit.frag"},
      {&blob_shadow_program, "draw_blob_shadow.vert", "draw_blob_shadow.frag"},
  };
  for (const auto& files : programs) {
    if (!files.program->load(files.vertex, files.fragment, error))
      return false;
  }
  // Samplers read fixed texture units.
  for (const shader_program* program :
       {&cpu_cloth.surface, &texture_cloth.surface, &texture_cloth.shadow, &texture_cloth.lines}) {
    program->use();
    program->set("cloth_texture", cloth_texture_unit);
    program->set("position_texture", position_texture_unit);
    program->set("normal_texture", normal_texture_unit);
  }
  glUseProgram(0);
  return true;
}

bool renderer::impl::load_cloth_texture(std::string& error) {
  const auto path = asset_path("cloth.png");
  int width = 0;
  int height = 0;
  int channels = 0;
  // Row 0 of the image (its top) becomes v = 0, the row of particles kv = 0.
  stbi_uc* pixels = stbi_load(path.string().c_str(), &width, &height, &channels, 4);
  if (pixels == nullptr) {
    error = path.string() + colon() +
            format(tr("cannot load the cloth texture: %s"), stbi_failure_reason());
    return false;
  }
  glGenTextures(1, &cloth_texture);
  glBindTexture(GL_TEXTURE_2D, cloth_texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  stbi_image_free(pixels);
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  return true;
}

void renderer::impl::create_static_buffers() {
  glGenVertexArrays(1, &empty_vao);

  // The ground square, two triangles as a strip.
  const float corners[] = {-ground_extent, -ground_extent, ground_extent, -ground_extent,
                           -ground_extent, ground_extent,  ground_extent, ground_extent};
  glGenVertexArrays(1, &ground_vao);
  glBindVertexArray(ground_vao);
  glGenBuffers(1, &ground_vbo);
  glBindBuffer(GL_ARRAY_BUFFER, ground_vbo);
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glEnableVertexAttribArray(position_or_texel_location);
  glVertexAttribPointer(position_or_texel_location, 2, GL_FLOAT, GL_FALSE, 0, nullptr);

  // One sphere mesh, drawn once per instance.
  const sphere_mesh sphere = make_unit_sphere(sphere_slices, sphere_stacks);
  sphere_index_count = static_cast<GLsizei>(sphere.indices.size());
  glGenVertexArrays(1, &sphere_vao);
  glBindVertexArray(sphere_vao);
  glGenBuffers(1, &sphere_vbo);
  glBindBuffer(GL_ARRAY_BUFFER, sphere_vbo);
  glBufferData(GL_ARRAY_BUFFER, byte_size(sphere.vertices), sphere.vertices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(position_or_texel_location);
  glVertexAttribPointer(position_or_texel_location, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, &sphere_ebo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, sphere_ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, byte_size(sphere.indices), sphere.indices.data(),
               GL_STATIC_DRAW);
  glGenBuffers(1, &sphere_instances.id);
  glBindBuffer(GL_ARRAY_BUFFER, sphere_instances.id);
  constexpr GLsizei stride = floats_per_sphere * sizeof(float);
  glEnableVertexAttribArray(instance_centre_location);
  glVertexAttribPointer(instance_centre_location, 4, GL_FLOAT, GL_FALSE, stride, nullptr);
  glVertexAttribDivisor(instance_centre_location, 1);
  glEnableVertexAttribArray(instance_colour_location);
  glVertexAttribPointer(instance_colour_location, 3, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(4 * sizeof(float)));
  glVertexAttribDivisor(instance_colour_location, 1);

  // The coils of the springs, rewritten every frame.
  glGenVertexArrays(1, &coil_vao);
  glBindVertexArray(coil_vao);
  glGenBuffers(1, &coil_points.id);
  glBindBuffer(GL_ARRAY_BUFFER, coil_points.id);
  glEnableVertexAttribArray(position_or_texel_location);
  glVertexAttribPointer(position_or_texel_location, 3, GL_FLOAT, GL_FALSE, 0, nullptr);

  // The shadows under the masses: a square per instance, its corners from gl_VertexID.
  glGenVertexArrays(1, &blob_vao);
  glBindVertexArray(blob_vao);
  glGenBuffers(1, &blob_instances.id);
  glBindBuffer(GL_ARRAY_BUFFER, blob_instances.id);
  glEnableVertexAttribArray(position_or_texel_location);
  glVertexAttribPointer(position_or_texel_location, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  glVertexAttribDivisor(position_or_texel_location, 1);

  glBindVertexArray(0);
}

frame renderer::impl::begin_frame(const camera& view, int left, int width, int height) {
  // Only this rectangle is cleared and drawn: the scissor keeps the clear inside it.
  glViewport(left, 0, width, height);
  glScissor(left, 0, width, height);
  glEnable(GL_SCISSOR_TEST);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_POLYGON_OFFSET_FILL);

  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const frame f = {view.projection(aspect) * view.view(), view.eye(),
                   view.metres_per_pixel(static_cast<float>(height))};
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  return f;
}

void renderer::impl::draw_chain(const frame& f, const particle_system& particles,
                                std::span<const spring> springs,
                                const dynamics_parameters& dynamics, double stiffness,
                                bool show_floor) {
  const glm::vec3 top = particles.get_position(0);
  if (show_floor) {
    // The floor is only drawn (nothing collides with it): below the lowest swing of a stable
    // chain, and lowered under a mass that goes further (a growing, unstable oscillation), so
    // that no mass disappears through it.
    float floor_height =
        chain_floor_height(top.z, springs, dynamics.mass, dynamics.gravity, stiffness);
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const float z = static_cast<float>(particles.get_position(k).z);
      if (std::isfinite(z))
        floor_height = std::min(floor_height, z - 2.0f * mass_radius);
    }
    // Soft shadows on the floor, larger and lighter for masses high above it.
    blobs.clear();
    for (std::size_t k = 0; k < particles.size(); ++k) {
      if (particles.is_fixed[k])
        continue;
      const glm::vec3 p = particles.get_position(k);
      const float height = std::max(p.z - floor_height, 0.0f);
      blobs.emplace_back(p.x, p.y, 2.5f * mass_radius + 0.15f * height, 0.5f / (1.0f + height));
    }
    draw_ground(f, floor_height, {top.x, top.y});
    draw_blob_shadows(f, floor_height);
  }

  const coil_shape coil;
  floats.clear();
  for (const spring& s : springs) {
    append_coil(particles.get_position(s.a), particles.get_position(s.b), coil, floats);
  }
  coil_points.upload(floats);
  flat_program.use();
  flat_program.set("view_projection", f.view_projection);
  flat_program.set("project_onto_ground", 0);
  flat_program.set("flat_colour", coil_colour);
  // (lines stay 1 px wide: wider ones are not part of a forward-compatible core context)
  glBindVertexArray(coil_vao);
  for (std::size_t i = 0; i < springs.size(); ++i) {
    glDrawArrays(GL_LINE_STRIP, static_cast<GLint>(i) * coil.vertex_count(), coil.vertex_count());
  }

  instances.clear();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const bool fixed = particles.is_fixed[k] != 0;
    // At least a few pixels wide, however far the view (a long chain framed whole).
    const float radius =
        drawn_mass_radius(fixed ? fixed_point_radius : mass_radius, f.metres_per_pixel);
    add_sphere(particles.get_position(k), radius, fixed ? fixed_point_colour : mass_colour);
  }
  draw_spheres(f);
  draw_background(f);
}

renderer::renderer() : impl_(std::make_unique<impl>()) {}

renderer::~renderer() = default;  // (here, where impl is complete)

bool renderer::init(std::string& error) {
  if (!impl_->load_programs(error))
    return false;
  if (!impl_->load_cloth_texture(error))
    return false;
  impl_->create_static_buffers();
  const glm::vec3 clear = horizon_colour;
  glClearColor(clear.r, clear.g, clear.b, 1.0f);
  return true;
}

void renderer::draw(const single_spring& stage, const camera& view, const render_settings& settings,
                    int width, int height, int left) {
  const frame f = impl_->begin_frame(view, left, width, height);
  impl_->draw_chain(f, stage.particles(), stage.springs(), stage.parameters.dynamics,
                    stage.parameters.stiffness, settings.show_ground);
  glDisable(GL_SCISSOR_TEST);
}

void renderer::draw(const coupled_springs& stage, const camera& view,
                    const render_settings& settings, int width, int height, int left) {
  const frame f = impl_->begin_frame(view, left, width, height);
  impl_->draw_chain(f, stage.particles(), stage.springs(), stage.parameters.dynamics,
                    stage.parameters.stiffness, settings.show_ground);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace clothlab
