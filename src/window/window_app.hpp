// The window's program, whatever the platform: Dear ImGui, the keys, the mouse, and one frame of
// the main loop, which reads top to bottom in five phases: poll, UI, simulate, draw, swap.
// A platform file owns the context and the loop around it, and nothing else:
//  - window_main.cpp, the desktop: the command line, a while loop that sleeps while the window
//    is idle, --frames; P writes a PNG file;
//  - web_main.cpp, the browser (WebAssembly + WebGL2): one frame per animation frame of the
//    page; P downloads the PNG.
#pragma once

#include <memory>
#include <string>

#include "app/options.hpp"
#include "window/glfw_context.hpp"
#include "window/scene.hpp"

namespace clothlab {

class window_app {
 public:
  // The scene of `start`, its renderer, its model and the panel, in `context` (current). Returns
  // null and sets error (a sentence) when the renderer cannot start.
  static std::unique_ptr<window_app> create(glfw_context& context, const options& start,
                                            std::string& error);
  ~window_app();
  window_app(const window_app&) = delete;
  window_app& operator=(const window_app&) = delete;

  // One frame, from the input gathered since the last one: the UI, the actions of keys and
  // buttons, the steps, the drawing, the swap. Escape asks the context to close.
  void frame(const window_input& input);
  // After the loop slept through a minimised window: the next frame does not count that time
  // as simulated time.
  void restart_clock();

  const scene& the_scene() const { return scene_; }

 private:
  class imgui_session;
  class mouse_control;
  window_app(glfw_context& context, const options& start);

  glfw_context& context_;
  scene scene_;
  std::unique_ptr<imgui_session> ui_;
  std::unique_ptr<mouse_control> mouse_;
  bool show_help_ = false;
  double previous_time_ = 0.0;
};

// The platform's part of the P key: the frame in the back buffer, panel included, width x
// height pixels, read before the swap. The desktop writes
// clothlab-YYYYMMDD-HHMMSS-<stage>.png in the working directory; the browser downloads it.
void deliver_screenshot(stage_kind stage, int width, int height);

}  // namespace clothlab
