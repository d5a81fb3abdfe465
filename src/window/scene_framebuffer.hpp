// An off-screen colour + depth framebuffer for the scene. The renderer draws from the viewport's
// origin; drawing into this framebuffer and copying it beside the control panel frames the scene
// in the part of the window that the panel leaves free.
#pragma once

#include "gl.hpp"

namespace clothlab {

class scene_framebuffer {
 public:
  scene_framebuffer() = default;
  ~scene_framebuffer();
  scene_framebuffer(const scene_framebuffer&) = delete;
  scene_framebuffer& operator=(const scene_framebuffer&) = delete;

  // Binds a width x height framebuffer for drawing, made again when the size changes. False
  // (nothing bound) when the driver cannot make it complete.
  bool bind(int width, int height);
  // Copies it into the window's framebuffer with its left edge at x (the rest cleared), then
  // binds the window's framebuffer.
  void copy_to_window(int x);

 private:
  void release();

  GLuint framebuffer_ = 0;
  GLuint colour_ = 0;  // renderbuffers
  GLuint depth_ = 0;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace clothlab
