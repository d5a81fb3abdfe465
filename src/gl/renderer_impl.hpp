// The renderer's inside (renderer.hpp's renderer::impl), shared by the files that draw: what
// every pass reads (colours, sizes, texture units, attribute locations), the buffers and
// programs the renderer owns, and its drawing functions. renderer.cpp sets them up and draws the
// spring stages, renderer_cloth.cpp draws the cloth, renderer_scenery.cpp what surrounds the
// stages (sky, ground, shadows, spheres, the wind's arrow). Only these files include it.
#pragma once

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <array>
#include <span>
#include <string>
#include <vector>

#include "gl/render_geometry.hpp"
#include "gl/renderer.hpp"
#include "gl/shader.hpp"

namespace clothlab {

// The look of the scene, in one place.
inline const glm::vec3 horizon_colour = {0.90f, 0.91f, 0.92f};
inline const glm::vec3 sky_colour = {0.60f, 0.72f, 0.85f};
inline const glm::vec3 light_tile_colour = {0.80f, 0.79f, 0.76f};
inline const glm::vec3 dark_tile_colour = {0.66f, 0.65f, 0.63f};
inline constexpr float tile_size = 0.25f;      // m: four tiles along the 1 m cloth
inline constexpr float ground_extent = 40.0f;  // m, half side of the ground square
inline constexpr float fade_start = 4.0f;      // m, from the scene's centre
inline constexpr float fade_end = 16.0f;       // m
inline const glm::vec3 light_direction =
    glm::normalize(glm::vec3(-0.25f, 0.6f, 0.85f));              // to the light
inline const glm::vec3 cloth_back_tint = {0.78f, 0.84f, 0.95f};  // the back side is slightly bluer
inline const glm::vec3 mass_colour = {0.16f, 0.50f, 0.78f};
inline const glm::vec3 fixed_point_colour = {0.55f, 0.55f, 0.57f};
inline const glm::vec3 pin_colour = {0.25f, 0.25f, 0.28f};
inline const glm::vec3 obstacle_colour = {0.78f, 0.36f, 0.24f};  // the sphere the cloth drapes over
// The cloth rests with its particles on the obstacle sphere, and its flat triangles cut under
// the surface between them (by up to a fifth of a cell on a stretched cloth): the sphere is drawn
// a little smaller and its depth pushed back by a fraction of the cloth's spacing h.
inline constexpr float obstacle_drawn_fraction = 0.99f;
inline constexpr float obstacle_depth_push = 0.4f;  // of h, at most a fifth of the radius
inline const glm::vec4 coil_colour = {0.22f, 0.24f, 0.28f, 1.0f};
inline constexpr float light_fraction_in_shadow = 0.62f;  // of the ground's colour, under the cloth
inline const glm::vec4 wireframe_colour = {0.10f, 0.08f, 0.08f, 0.55f};
// The springs overlay of the cloth, indexed by spring_family: structural, shear, bending.
inline const std::array<glm::vec4, 3> spring_family_colours = {
    glm::vec4{0.05f, 0.25f, 0.85f, 0.90f},  // structural: blue
    glm::vec4{0.05f, 0.60f, 0.20f, 0.80f},  // shear: green
    glm::vec4{0.98f, 0.60f, 0.02f, 0.75f}   // bending: amber
};
inline const glm::vec4 wind_arrow_colour = {0.10f, 0.30f, 0.70f, 1.0f};
inline constexpr double wind_arrow_height = 0.35;        // m, above the cloth's highest particle
inline constexpr float mass_radius = chain_mass_radius;  // m, as drawn
inline constexpr float fixed_point_radius = chain_fixed_point_radius;  // m
inline constexpr float pin_radius = 0.022f;                            // m
inline constexpr int sphere_slices = 24;
inline constexpr int sphere_stacks = 16;
inline constexpr int floats_per_sphere = 7;  // per instance: centre xyz, radius, colour rgb

// Polygon offsets (glPolygonOffset's units, the depth buffer's smallest step) of what lies on
// the ground plane, from the nearest: the cloth's back side (a folded layer, back up, wins a tie
// with the layer under it), its front side, the cloth's shadow, the ground (factor 2). The
// ground lies far behind the shadow: its one large quad and the shadow's small triangles
// interpolate depth differently, by several units on SwiftShader (the browser's WebGL on the
// CPU), where a gap of 2 units lets the ground show through the shadow in patches.
inline constexpr float back_offset_units = 1.0f;
inline constexpr float front_offset_units = 4.0f;
inline constexpr float shadow_offset_units = 6.0f;
inline constexpr float ground_offset_units = 32.0f;

template <typename Contiguous>
inline GLsizeiptr byte_size(const Contiguous& data) {
  return static_cast<GLsizeiptr>(std::span(data).size_bytes());
}

// Converts the simulation's doubles to the floats GL draws with, into a reused buffer.
inline void convert_to_float(std::span<const double> source, std::vector<float>& target) {
  target.resize(source.size());
  std::transform(source.begin(), source.end(), target.begin(),
                 [](double x) { return static_cast<float>(x); });
}

// Texture units, fixed for every program.
constexpr int cloth_texture_unit = 0;
constexpr int position_texture_unit = 1;
constexpr int normal_texture_unit = 2;
constexpr int spring_mask_texture_unit = 3;

// Attribute locations shared by the shaders (see shaders/draw_*.vert).
constexpr GLuint position_or_texel_location = 0;
constexpr GLuint normal_location = 1;
constexpr GLuint grid_coordinates_location = 2;
constexpr GLuint instance_centre_location = 1;
constexpr GLuint instance_colour_location = 2;

// A buffer that is rewritten every frame; its storage grows only when the data outgrows it.
struct streamed_buffer {
  GLuint id = 0;
  GLsizeiptr capacity = 0;  // bytes

  void upload(std::span<const float> data) {
    glBindBuffer(GL_ARRAY_BUFFER, id);
    if (byte_size(data) > capacity) {
      capacity = byte_size(data);
      glBufferData(GL_ARRAY_BUFFER, capacity, data.data(), GL_DYNAMIC_DRAW);
    } else {
      glBufferSubData(GL_ARRAY_BUFFER, 0, byte_size(data), data.data());
    }
  }
};

// What every pass of one frame needs.
struct frame {
  glm::mat4 view_projection;
  glm::vec3 eye;
  float metres_per_pixel;  // at the target's distance
};

struct renderer::impl {
  shader_program background_program;
  shader_program ground_program;
  shader_program flat_program;  // lines of the spring stages
  shader_program spheres_program;
  shader_program blob_shadow_program;  // soft round shadows under the masses
  // The cloth's three passes (lit surface, shadow on the ground, lines), from CPU positions and
  // from the GPU state textures.
  struct cloth_programs {
    shader_program surface;
    shader_program shadow;
    shader_program lines;
  };
  cloth_programs cpu_cloth;
  cloth_programs texture_cloth;
  GLuint cloth_texture = 0;

  GLuint empty_vao = 0;  // the background triangle needs no vertex data
  GLuint ground_vao = 0;
  GLuint ground_vbo = 0;

  GLuint sphere_vao = 0;
  GLuint sphere_vbo = 0;
  GLuint sphere_ebo = 0;
  GLsizei sphere_index_count = 0;
  streamed_buffer sphere_instances;  // floats_per_sphere floats per sphere

  GLuint coil_vao = 0;
  streamed_buffer coil_points;

  GLuint blob_vao = 0;
  streamed_buffer blob_instances;  // one vec4 per shadow (blobs)

  // The cloth, built again when its grid size or springs change.
  int cloth_grid_size = 0;
  std::size_t cloth_spring_count = 0;
  cloth_indices cloth_index_ranges;
  GLuint cloth_vao = 0;          // CPU path: position, normal, grid coordinates
  GLuint texture_cloth_vao = 0;  // GPU path: texel, grid coordinates
  GLuint cloth_position_vbo = 0;
  GLuint cloth_normal_vbo = 0;
  GLuint cloth_grid_coordinates_vbo = 0;
  GLuint cloth_texel_vbo = 0;
  GLuint cloth_ebo = 0;

  // Scratch buffers kept between frames (no allocation per frame once grown).
  std::vector<double> normals;
  double normals_seconds = 0.0;  // of the last draw(cloth)
  std::vector<float> floats;
  std::vector<float> instances;
  std::vector<glm::vec4> blobs;  // soft round shadows under masses: x, y (m), radius (m), darkness
                                 // (0..1)

  ~impl();
  bool load_programs(std::string& error);
  bool load_cloth_texture(std::string& error);
  void create_static_buffers();
  void ensure_cloth_buffers(const spring_mesh& cloth);

  frame begin_frame(const camera& view, int left, int width, int height);
  void draw_background(const frame& f);
  void set_ground_uniforms(const shader_program& program, const frame& f, float height,
                           const glm::vec2& centre, float light_fraction);
  void draw_ground(const frame& f, float height, const glm::vec2& centre);
  void draw_blob_shadows(const frame& f, float height);
  void draw_spheres(const frame& f, float depth_push = 0.0f);
  void draw_chain(const frame& f, const particle_system& particles, std::span<const spring> springs,
                  const dynamics_parameters& dynamics, double stiffness, bool show_floor);
  void draw_cloth(const frame& f, const spring_mesh& cloth, const render_settings& settings,
                  const cloth_programs& programs, GLuint vao);
  void add_sphere(const glm::vec3& centre, float radius, const glm::vec3& colour);
  void draw_wind_arrow(const frame& f, const spring_mesh& cloth);
  void draw_obstacle_shadow(const frame& f, const sphere_parameters& sphere, float ground_height);
};

}  // namespace clothlab
