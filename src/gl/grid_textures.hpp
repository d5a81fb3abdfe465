// The GL objects of the fragment path (gpu_cloth): N x N textures read with texelFetch, one
// texel per particle, the framebuffers that render into them, the full-screen pass that runs a
// fragment shader once per texel, and the read-back of one texel.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "gl/gl.hpp"

namespace clothlab {

// An N x N texture read with texelFetch (nearest filtering, no mipmaps), filled from `data`.
GLuint create_grid_texture(int n, GLint internal_format, GLenum format, GLenum type,
                           const void* data);

// An N x N GL_RGBA32F texture holding `texels` (4 floats per texel, texel (ku, kv) at
// 4 (ku + N kv)).
GLuint create_state_texture(int n, const std::vector<float>& texels);

// The N x N GL_R32UI spring mask (gpu_cloth.hpp), texel (ku, kv) = masks[ku + N kv].
GLuint create_mask_texture(int n, const std::vector<std::uint32_t>& masks);

// A framebuffer rendering into `targets` (attachment i = targets[i]); 0 and an error if the
// driver cannot render into them.
GLuint create_framebuffer(std::initializer_list<GLuint> targets, std::string& error);

// Binds `texture` (2D) to texture unit `unit`.
void bind_texture(GLuint unit, GLuint texture);

// Runs the bound program once per texel of the bound N x N framebuffer (the viewport set to
// N x N by the caller, once for all the passes of a batch).
void draw_full_screen_pass();

// Reads one texel (x, y) of attachment `attachment` of `framebuffer` into 4 floats, leaving the
// caller's read framebuffer and pixel pack buffer bound as they were.
void read_texel(GLuint framebuffer, GLenum attachment, int x, int y, float* rgba);

}  // namespace clothlab
