// The RAII guard of the GL state: what a GPU path changes to run its passes (framebuffers,
// viewport, program, vertex array, textures, pixel buffers, blending, culling, tests, polygon
// mode) is saved on construction and restored on destruction, so that the renderer's drawing
// around a step, or the caller's own state, is not disturbed. Every GL path that runs between
// two drawings holds one: the fragment path (gpu_cloth) and the compute path (gpu_cloth_compute,
// which also holds saved_storage_buffer).
#pragma once

#include <array>

#include "gl/gl.hpp"

namespace clothlab {

#if defined(CLOTHLAB_GL_WEB)
// WebGL2 has no polygon mode: triangles are always filled, there is nothing to save.
struct saved_polygon_mode {
  static void fill() {}
};
#else
// The polygon mode: a caller may be drawing in outline (GL_LINE); the passes fill.
class saved_polygon_mode {
 public:
  saved_polygon_mode();
  ~saved_polygon_mode();
  saved_polygon_mode(const saved_polygon_mode&) = delete;
  saved_polygon_mode& operator=(const saved_polygon_mode&) = delete;
  static void fill();

 private:
  std::array<GLint, 2> mode_{GL_FILL, GL_FILL};
};
#endif

class saved_gl_state {
 public:
  // Saves the state, then binds no pixel pack or unpack buffer (glReadPixels and glTexImage2D
  // use client memory while the guard lives).
  saved_gl_state();
  ~saved_gl_state();
  saved_gl_state(const saved_gl_state&) = delete;
  saved_gl_state& operator=(const saved_gl_state&) = delete;

  // For the passes: every fragment written as computed, no blending, culling or testing.
  static void set_pass_state();

  static constexpr GLuint texture_units = 4;  // the passes read at most four textures

 private:
  static constexpr std::array<GLenum, 5> capabilities = {GL_BLEND, GL_CULL_FACE, GL_DEPTH_TEST,
                                                         GL_SCISSOR_TEST, GL_STENCIL_TEST};
  GLint draw_framebuffer_ = 0;
  GLint read_framebuffer_ = 0;
  std::array<GLint, 4> viewport_{};
  GLint program_ = 0;
  GLint vertex_array_ = 0;
  GLint active_texture_ = GL_TEXTURE0;
  std::array<GLint, texture_units> texture_{};
  // The polygon mode, saved and restored by itself (WebGL2 has none).
#if !defined(CLOTHLAB_GL_WEB)
  saved_polygon_mode polygon_mode_;
#endif
  GLint pixel_pack_buffer_ = 0;
  GLint pixel_unpack_buffer_ = 0;
  std::array<GLboolean, capabilities.size()> enabled_{};
};

#if !defined(CLOTHLAB_GL_WEB)
// The generic shader storage buffer binding (OpenGL 4.3), which the compute path changes to
// upload and read its buffers. Only in a 4.3 context: saved_gl_state leaves it alone, so that it
// serves older contexts too.
class saved_storage_buffer {
 public:
  saved_storage_buffer();
  ~saved_storage_buffer();
  saved_storage_buffer(const saved_storage_buffer&) = delete;
  saved_storage_buffer& operator=(const saved_storage_buffer&) = delete;

 private:
  GLint buffer_ = 0;
};
#endif

}  // namespace clothlab
