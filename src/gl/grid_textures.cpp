#include "gl/grid_textures.hpp"

#include <cstdio>

#include "core/i18n.hpp"

namespace clothlab {

// An N x N texture read with texelFetch (nearest filtering, no mipmaps), filled from `data`.
GLuint create_grid_texture(int n, GLint internal_format, GLenum format, GLenum type,
                           const void* data) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, internal_format, n, n, 0, format, type, data);
  return texture;
}

// An N x N GL_RGBA32F texture holding `texels` (4 floats per texel, texel (ku, kv) at
// 4 (ku + N kv)).
GLuint create_state_texture(int n, const std::vector<float>& texels) {
  return create_grid_texture(n, GL_RGBA32F, GL_RGBA, GL_FLOAT, texels.data());
}

// The N x N GL_R32UI spring mask (gpu_cloth.hpp), texel (ku, kv) = masks[ku + N kv].
GLuint create_mask_texture(int n, const std::vector<std::uint32_t>& masks) {
  return create_grid_texture(n, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, masks.data());
}

// A framebuffer rendering into `targets` (attachment i = targets[i]); 0 and an error if the
// driver cannot render into them.
GLuint create_framebuffer(std::initializer_list<GLuint> targets, std::string& error) {
  GLuint framebuffer = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  std::vector<GLenum> draw_buffers;
  for (GLuint texture : targets) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(draw_buffers.size());
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, texture, 0);
    draw_buffers.push_back(attachment);
  }
  glDrawBuffers(static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char status_hex[16];
    std::snprintf(status_hex, sizeof status_hex, "0x%04X", status);
    error = format(tr("the GPU cloth needs to render into GL_RGBA32F and GL_R32UI textures, "
                      "which this OpenGL driver refuses (framebuffer status %s)"),
                   status_hex);
    glDeleteFramebuffers(1, &framebuffer);
    return 0;
  }
  return framebuffer;
}

void bind_texture(GLuint unit, GLuint texture) {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, texture);
}

void draw_full_screen_pass() {
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Reads one texel (x, y) of attachment `attachment` of `framebuffer` into 4 floats, leaving the
// caller's read framebuffer and pixel pack buffer bound as they were.
void read_texel(GLuint framebuffer, GLenum attachment, int x, int y, float* rgba) {
  GLint read_framebuffer = 0, pixel_pack_buffer = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pixel_pack_buffer);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glReadBuffer(attachment);
  glReadPixels(x, y, 1, 1, GL_RGBA, GL_FLOAT, rgba);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_framebuffer));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pixel_pack_buffer));
}

}  // namespace clothlab
