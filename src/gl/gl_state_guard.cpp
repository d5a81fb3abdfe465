#include "gl/gl_state_guard.hpp"

namespace clothlab {

#if !defined(CLOTHLAB_GL_WEB)
saved_polygon_mode::saved_polygon_mode() {
  glGetIntegerv(GL_POLYGON_MODE, mode_.data());
}

saved_polygon_mode::~saved_polygon_mode() {
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(mode_[0]));
}

void saved_polygon_mode::fill() {
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}
#endif

saved_gl_state::saved_gl_state() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
  glGetIntegerv(GL_VIEWPORT, viewport_.data());
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
  for (GLuint unit = 0; unit < texture_units; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_[unit]);
  }
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pixel_pack_buffer_);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &pixel_unpack_buffer_);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  for (std::size_t i = 0; i < capabilities.size(); ++i) {
    enabled_[i] = glIsEnabled(capabilities[i]);
  }
}

saved_gl_state::~saved_gl_state() {
  for (std::size_t i = 0; i < capabilities.size(); ++i) {
    if (enabled_[i] == GL_TRUE) {
      glEnable(capabilities[i]);
    } else {
      glDisable(capabilities[i]);
    }
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pixel_pack_buffer_));
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(pixel_unpack_buffer_));
  for (GLuint unit = 0; unit < texture_units; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(texture_[unit]));
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glBindVertexArray(static_cast<GLuint>(vertex_array_));
  glUseProgram(static_cast<GLuint>(program_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_framebuffer_));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_framebuffer_));
}

void saved_gl_state::set_pass_state() {
  for (GLenum capability : capabilities)
    glDisable(capability);
  saved_polygon_mode::fill();
}

#if !defined(CLOTHLAB_GL_WEB)
saved_storage_buffer::saved_storage_buffer() {
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &buffer_);
}

saved_storage_buffer::~saved_storage_buffer() {
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(buffer_));
}
#endif

}  // namespace clothlab
