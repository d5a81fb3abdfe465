// The window implementation of gl_context: a GLFW window with an OpenGL 3.3 core context whose
// functions are loaded by GLEW; in the browser build (CLOTHLAB_GL_WEB), emscripten's GLFW with
// the page's canvas as a WebGL2 context. It also gathers the keyboard and wheel input of the window
// between two polls, for the main loop to act on (src/window/window_main.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/i18n.hpp"
#include "gl/gl_context.hpp"

struct GLFWwindow;

namespace clothlab {

// What the user did since the last poll.
struct window_input {
  std::vector<int> pressed_keys;  // GLFW_KEY_* codes, in the order they were pressed
  double scroll = 0.0;            // wheel clicks, positive away from the user
};

class glfw_context final : public gl_context {
 public:
  // Opens a width x height window titled `title`, makes its OpenGL 3.3 core context current,
  // loads the GL functions with GLEW and turns vsync on. Returns null and sets error (a full
  // sentence) when there is no display or no such context.
  static std::unique_ptr<glfw_context> create(const std::string& title, int width, int height,
                                              std::string& error);
  ~glfw_context() override;
  glfw_context(const glfw_context&) = delete;
  glfw_context& operator=(const glfw_context&) = delete;

  // In pixels: larger than the window's size in screen coordinates on HiDPI screens.
  int framebuffer_width() const override;
  int framebuffer_height() const override;
#if defined(CLOTHLAB_GL_WEB)
  std::string origin() const override {
    return tr("in the page's WebGL2 canvas");
  }
#else
  std::string origin() const override {
    return tr("in a GLFW window");
  }
#endif

  GLFWwindow* window() const {
    return window_;
  }
  // The screen's scale: 1, or more on a HiDPI screen (the page's canvas: 1).
  float content_scale() const;
  bool should_close() const;
  void request_close();

  // Processes pending events and returns the input gathered since the last call.
  window_input poll_events();
  // The same, but first sleeps until an event comes or `seconds` pass (a paused, idle window).
  // woke_early tells which: true when an event ended the wait.
  window_input wait_for_events(double seconds, bool& woke_early);
  // True while the window is iconified or its framebuffer is 0 x 0: nothing can be drawn.
  bool is_minimised() const;
  // Sleeps until the next event (used while minimised, so that the loop does not spin).
  void wait_events();
  void swap_buffers();
  // Swaps wait for the screen's refresh (true, the default) or not.
  void set_vsync(bool on);

 private:
  explicit glfw_context(GLFWwindow* window);
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void on_scroll(GLFWwindow* window, double x_offset, double y_offset);

  GLFWwindow* window_;
  window_input input_;
};

}  // namespace clothlab
