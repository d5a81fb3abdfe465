// An OpenGL 3.3 core context, current on the calling thread while the object lives.
// The implementations: the GLFW window (src/window), and off screen the OSMesa buffer
// (osmesa_context.cpp), the EGL pbuffer (egl_context.cpp) or, with neither, a hidden GLFW
// window (hidden_window_context.cpp). The rendering and GPU simulation
// code above it does not know which one it runs on; the context itself says (origin).
#pragma once

#include <memory>
#include <string>

namespace clothlab {

class gl_context {
 public:
  virtual ~gl_context() = default;
  // Size of the default framebuffer (framebuffer 0) in pixels.
  virtual int framebuffer_width() const = 0;
  virtual int framebuffer_height() const = 0;
  // "renderer, version" as the driver reports them (GL_RENDERER, GL_VERSION).
  std::string description() const;
  // Where the context comes from, as the program's first lines say it: "through OSMesa",
  // "through EGL (a hardware device)", "in a GLFW window"...
  virtual std::string origin() const = 0;
};

// An off-screen context whose default framebuffer is a width x height RGBA buffer in memory.
// Returns null and sets error (a full sentence) when it cannot be made.
std::unique_ptr<gl_context> create_offscreen_context(int width, int height, std::string& error);

#if defined(CLOTHLAB_GL_EGL)
// True when EGL lists a hardware device (a GPU's driver), not only Mesa's software one.
bool egl_hardware_device_available();
#endif

}  // namespace clothlab
