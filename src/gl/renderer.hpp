// Draws the three stages: springs as lines and masses as spheres or points (fixed ones marked);
// the cloth as a lit, textured, two-sided mesh with the ground plane, optional wireframe and
// springs coloured by family. The same code serves the window and the off-screen build.
// Display only: the renderer reads the simulation state, it never changes it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "core/coupled_springs.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"
#include "gl/camera.hpp"
#include "gl/gl.hpp"
#include "gl/png_capture.hpp"  // framebuffer_png, save_framebuffer_png

namespace clothlab {

struct render_settings {
  bool wireframe = false;     // the cloth as its triangle edges (key W)
  bool show_springs = false;  // the cloth's springs as lines, coloured by family
  bool show_ground = true;    // the ground plane, when the cloth's ground is enabled
  bool show_wind = false;     // an arrow along the wind beside the cloth, when there is wind
};

// The colour of a spring family in the springs overlay (for a legend): RGBA, 0..1.
glm::vec4 spring_family_colour(spring_family family);

class renderer {
 public:
  renderer();
  ~renderer();
  renderer(const renderer&) = delete;
  renderer& operator=(const renderer&) = delete;

  // Loads shaders/ and assets/cloth.png; needs a current GL 3.3 context. On failure returns
  // false with an error naming the file (and the compiler's log).
  bool init(std::string& error);

  // Each clears and draws into the currently bound framebuffer, in the width x height rectangle
  // whose lower-left corner is at (left, 0) (viewport and scissor: the window's part beside the
  // control panel); the rest of the framebuffer is left as it is.
  void draw(const single_spring& stage, const camera& view, const render_settings& settings,
            int width, int height, int left = 0);
  void draw(const coupled_springs& stage, const camera& view, const render_settings& settings,
            int width, int height, int left = 0);
  void draw(const spring_mesh& cloth, const camera& view, const render_settings& settings,
            int width, int height, int left = 0);
  // The GPU cloth (question 11): the CPU sends a flat N x N grid once; the vertex shader fetches
  // each vertex's position and normal from N x N RGBA32F textures (texel (ku, kv) = particle
  // ku + N kv). Lighting, texture, ground and wireframe as for the CPU cloth; the springs
  // overlay and the pins are taken from `cloth` (its parameters and topology, not its positions).
  // With a spring mask (gpu_cloth::spring_mask_texture) the triangles that lost a spring on the
  // GPU are left out, without reading the state back; without one (0), every triangle is drawn.
  void draw_from_textures(GLuint position_texture, GLuint normal_texture, const spring_mesh& cloth,
                          const camera& view, const render_settings& settings, int width,
                          int height, int left = 0, GLuint spring_mask_texture = 0);

  // The time the last draw(cloth) took to compute the cloth's vertex normals, s (the window's
  // frame anatomy, questions 1 and 3).
  double last_normals_seconds() const;

 private:
  struct impl;  // renderer_impl.hpp
  std::unique_ptr<impl> impl_;
};

}  // namespace clothlab
