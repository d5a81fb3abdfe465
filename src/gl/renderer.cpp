#include "gl/renderer.hpp"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <span>
#include <vector>

#include "gl/render_geometry.hpp"
#include "gl/shader.hpp"

namespace clothlab {
namespace {

// The look of the scene, in one place.
const glm::vec3 horizon_colour = {0.90f, 0.91f, 0.92f};
const glm::vec3 sky_colour = {0.60f, 0.72f, 0.85f};
const glm::vec3 light_tile_colour = {0.80f, 0.79f, 0.76f};
const glm::vec3 dark_tile_colour = {0.66f, 0.65f, 0.63f};
constexpr float tile_size = 0.25f;      // m: four tiles along the 1 m cloth
constexpr float ground_extent = 40.0f;  // m, half side of the ground square
constexpr float fade_start = 4.0f;      // m, from the scene's centre
constexpr float fade_end = 16.0f;       // m
const glm::vec3 light_direction = glm::normalize(glm::vec3(-0.25f, 0.6f, 0.85f));  // to the light
const glm::vec3 cloth_back_tint = {0.78f, 0.84f, 0.95f};  // the back side is slightly bluer
const glm::vec3 mass_colour = {0.16f, 0.50f, 0.78f};
const glm::vec3 fixed_point_colour = {0.55f, 0.55f, 0.57f};
const glm::vec3 pin_colour = {0.25f, 0.25f, 0.28f};
const glm::vec3 obstacle_colour = {0.78f, 0.36f, 0.24f};  // the sphere the cloth drapes over
// The cloth rests with its particles on the obstacle sphere, and its flat triangles cut under
// the surface between them (by up to a fifth of a cell on a stretched cloth): the sphere is drawn
// a little smaller and its depth pushed back by a fraction of the cloth's spacing h.
constexpr float obstacle_drawn_fraction = 0.99f;
constexpr float obstacle_depth_push = 0.4f;  // of h, at most a fifth of the radius
const glm::vec4 coil_colour = {0.22f, 0.24f, 0.28f, 1.0f};
constexpr float light_fraction_in_shadow = 0.62f;  // of the ground's colour, under the cloth
const glm::vec4 wireframe_colour = {0.10f, 0.08f, 0.08f, 0.55f};
// The springs overlay of the cloth, indexed by spring_family: structural, shear, bending.
const std::array<glm::vec4, 3> spring_family_colours = {
    glm::vec4{0.05f, 0.25f, 0.85f, 0.90f},  // structural: blue
    glm::vec4{0.05f, 0.60f, 0.20f, 0.80f},  // shear: green
    glm::vec4{0.98f, 0.60f, 0.02f, 0.75f}   // bending: amber
};
const glm::vec4 wind_arrow_colour = {0.10f, 0.30f, 0.70f, 1.0f};
constexpr double wind_arrow_height = 0.35;        // m, above the cloth's highest particle
constexpr float mass_radius = chain_mass_radius;  // m, as drawn
constexpr float fixed_point_radius = chain_fixed_point_radius;  // m
constexpr float pin_radius = 0.022f;                            // m
constexpr int sphere_slices = 24;
constexpr int sphere_stacks = 16;
constexpr int floats_per_sphere = 7;  // per instance: centre xyz, radius, colour rgb

void set_uniform(const shader_program& program, const char* name, const glm::mat4& value) {
  glUniformMatrix4fv(program.uniform(name), 1, GL_FALSE, glm::value_ptr(value));
}
void set_uniform(const shader_program& program, const char* name, const glm::vec4& value) {
  glUniform4fv(program.uniform(name), 1, glm::value_ptr(value));
}
void set_uniform(const shader_program& program, const char* name, const glm::vec3& value) {
  glUniform3fv(program.uniform(name), 1, glm::value_ptr(value));
}
void set_uniform(const shader_program& program, const char* name, const glm::vec2& value) {
  glUniform2fv(program.uniform(name), 1, glm::value_ptr(value));
}
void set_uniform(const shader_program& program, const char* name, float value) {
  glUniform1f(program.uniform(name), value);
}
void set_uniform(const shader_program& program, const char* name, int value) {
  glUniform1i(program.uniform(name), value);
}

template <typename Contiguous>
GLsizeiptr byte_size(const Contiguous& data) {
  return static_cast<GLsizeiptr>(std::span(data).size_bytes());
}

// Converts the simulation's doubles to the floats GL draws with, into a reused buffer.
void convert_to_float(std::span<const double> source, std::vector<float>& target) {
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

}  // namespace

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
    set_uniform(*program, "cloth_texture", cloth_texture_unit);
    set_uniform(*program, "position_texture", position_texture_unit);
    set_uniform(*program, "normal_texture", normal_texture_unit);
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
    error = path.string() + ": cannot load the cloth texture: " + stbi_failure_reason();
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

// The sky, after the opaque geometry and before anything blended: it lies on the far plane and
// is drawn only where nothing else is (depth test, no depth write), so that no pixel is shaded
// twice (on a software rasteriser the background and the ground are most of a frame's work).
void renderer::impl::draw_background(const frame& f) {
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_LEQUAL);
  background_program.use();
  set_uniform(background_program, "inverse_view_projection", glm::inverse(f.view_projection));
  set_uniform(background_program, "horizon_colour", horizon_colour);
  set_uniform(background_program, "sky_colour", sky_colour);
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
}

void renderer::impl::set_ground_uniforms(const shader_program& program, const frame& f,
                                         float height, const glm::vec2& centre,
                                         float light_fraction) {
  program.use();
  set_uniform(program, "view_projection", f.view_projection);
  set_uniform(program, "ground_height", height);
  set_uniform(program, "tile_size", tile_size);
  set_uniform(program, "light_tile_colour", light_tile_colour);
  set_uniform(program, "dark_tile_colour", dark_tile_colour);
  set_uniform(program, "horizon_colour", horizon_colour);
  set_uniform(program, "fade_centre", centre);
  set_uniform(program, "fade_start", fade_start);
  set_uniform(program, "fade_end", fade_end);
  set_uniform(program, "light_fraction", light_fraction);
  // For the cloth's shadow, whose vertex shader squashes the cloth onto the ground.
  set_uniform(program, "project_onto_ground", 1);
  set_uniform(program, "light_direction", light_direction);
}

// Polygon offsets (glPolygonOffset's units, the depth buffer's smallest step) of what lies on
// the ground plane, from the nearest: the cloth's back side (a folded layer, back up, wins a tie
// with the layer under it), its front side, the cloth's shadow, the ground (factor 2). The
// ground lies far behind the shadow: its one large quad and the shadow's small triangles
// interpolate depth differently, by several units on SwiftShader (the browser's WebGL on the
// CPU), where a gap of 2 units let the ground show through the shadow in patches.
constexpr float back_offset_units = 1.0f;
constexpr float front_offset_units = 4.0f;
constexpr float shadow_offset_units = 6.0f;
constexpr float ground_offset_units = 32.0f;

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
  set_uniform(flat_program, "view_projection", f.view_projection);
  set_uniform(flat_program, "project_onto_ground", 0);
  set_uniform(flat_program, "flat_colour", wind_arrow_colour);
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
  set_uniform(blob_shadow_program, "view_projection", f.view_projection);
  set_uniform(blob_shadow_program, "ground_height", height);
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
  set_uniform(spheres_program, "view_projection", f.view_projection);
  set_uniform(spheres_program, "depth_push", depth_push);
  set_uniform(spheres_program, "use_texture", 0);
  set_uniform(spheres_program, "light_direction", light_direction);
  set_uniform(spheres_program, "eye_position", f.eye);
  set_uniform(spheres_program, "back_tint", glm::vec3(1.0f));
  set_uniform(spheres_program, "shininess", 60.0f);
  set_uniform(spheres_program, "specular_strength", 0.45f);
  glBindVertexArray(sphere_vao);
  glDrawElementsInstanced(GL_TRIANGLES, sphere_index_count, GL_UNSIGNED_INT, nullptr,
                          static_cast<GLsizei>(instances.size() / floats_per_sphere));
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
  set_uniform(flat_program, "view_projection", f.view_projection);
  set_uniform(flat_program, "project_onto_ground", 0);
  set_uniform(flat_program, "flat_colour", coil_colour);
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
  set_uniform(surface, "view_projection", f.view_projection);
  set_uniform(surface, "use_texture", 1);
  set_uniform(surface, "light_direction", light_direction);
  set_uniform(surface, "eye_position", f.eye);
  set_uniform(surface, "back_tint", cloth_back_tint);
  set_uniform(surface, "shininess", 24.0f);
  set_uniform(surface, "specular_strength", 0.12f);
  // Surfaces are pushed back in depth so that lines lying on them are drawn in front.
  // Two layers of a cloth folded flat on the ground lie at z = z_g exactly (the ground contact
  // puts every particle below it there): their depths tie, and the rasteriser's rounding picked
  // the layer pixel by pixel, differently from frame to frame as the cloth moved (they
  // flickered through each other). The tie is broken the same way everywhere: the side facing
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
  set_uniform(flat, "view_projection", f.view_projection);
  set_uniform(flat, "project_onto_ground", 0);

  // Lines are hidden by the surface but not by each other (a bending spring runs along two
  // structural ones): they test depth without writing it.
  glDepthMask(GL_FALSE);
  if (settings.wireframe) {
    set_uniform(flat, "flat_colour", wireframe_colour);
    draw_range(GL_LINES, cloth_index_ranges.edges);
  }
  if (settings.show_springs) {
    // Bending first, so that the structural springs (the grid itself) are drawn on top.
    for (const spring_family family :
         {spring_family::bending, spring_family::shear, spring_family::structural}) {
      const auto i = static_cast<std::size_t>(family);
      set_uniform(flat, "flat_colour", spring_family_colours[i]);
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

renderer::renderer() : impl_(new impl) {}

renderer::~renderer() {
  delete impl_;
}

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
    set_uniform(*program, "spring_mask_texture", spring_mask_texture_unit);
    set_uniform(*program, "use_spring_mask", spring_mask_texture != 0 ? 1 : 0);
    set_uniform(*program, "grid_size", cloth.grid_size());
    set_uniform(*program, "triangles_from_vertex_id",
                program != &impl_->texture_cloth.lines ? 1 : 0);
  }
  impl_->draw_cloth(f, cloth, settings, impl_->texture_cloth, impl_->texture_cloth_vao);
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_SCISSOR_TEST);
}

bool framebuffer_png(int width, int height, std::vector<unsigned char>& png, std::string& error) {
  if (width < 1 || height < 1) {
    error = "cannot save a " + std::to_string(width) + "x" + std::to_string(height) + " image";
    return false;
  }
  const auto row_bytes = static_cast<std::size_t>(width) * 4;
  std::vector<unsigned char> pixels(row_bytes * static_cast<std::size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  // GL's rows go bottom-up, PNG's top-down. The image is opaque whatever alpha blending left.
  std::vector<unsigned char> image(pixels.size());
  for (int y = 0; y < height; ++y) {
    const auto source = pixels.begin() + static_cast<std::ptrdiff_t>(row_bytes * (height - 1 - y));
    std::copy(source, source + static_cast<std::ptrdiff_t>(row_bytes),
              image.begin() + static_cast<std::ptrdiff_t>(row_bytes * y));
  }
  for (std::size_t i = 3; i < image.size(); i += 4)
    image[i] = 255;
  // stb's encoder hands the PNG over in pieces, appended to `png`.
  png.clear();
  const auto append = [](void* context, void* data, int size) {
    auto& bytes = *static_cast<std::vector<unsigned char>*>(context);
    const auto* first = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), first, first + size);
  };
  if (stbi_write_png_to_func(append, &png, width, height, 4, image.data(),
                             static_cast<int>(row_bytes)) == 0) {
    error = "cannot encode the PNG image";
    return false;
  }
  return true;
}

bool save_framebuffer_png(const std::string& path, int width, int height, std::string& error) {
  std::vector<unsigned char> png;
  if (!framebuffer_png(width, height, png, error)) {
    error = path + ": " + error;
    return false;
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    error = path + ": cannot write the PNG image";
    return false;
  }
  // Every write checked: a full disk must not leave a truncated PNG behind.
  const bool written = std::fwrite(png.data(), 1, png.size(), file) == png.size();
  if (std::fclose(file) != 0 || !written) {
    std::error_code ignored;
    if (std::filesystem::is_regular_file(path, ignored))  // never a device such as /dev/full
      std::filesystem::remove(path, ignored);
    error = path + ": the PNG image could not be written whole (is the disk full?)";
    return false;
  }
  return true;
}

}  // namespace clothlab
