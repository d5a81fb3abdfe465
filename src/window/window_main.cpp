// clothlab-window on the desktop: the platform file of the window (window_app.hpp). The same
// options as `clothlab` (docs/cli.md); it starts on --stage. It opens the GLFW window, runs the
// frames of window_app in a loop that sleeps while the window is idle, and writes P's
// screenshots as files.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "gl/gl.hpp"  // GLEW, which must come before GLFW

#include <GLFW/glfw3.h>

#include "app/command_line.hpp"
#include "gl/renderer.hpp"
#include "window/glfw_context.hpp"
#include "window/layout_probe.hpp"
#include "window/window_app.hpp"

namespace clothlab {
namespace {

constexpr int initial_width = 1280;  // screen coordinates
constexpr int initial_height = 800;
// A paused window draws a frame when an event comes (then a few more) or after this long (the
// readouts stay fresh); otherwise it sleeps instead of drawing the same frame again.
constexpr double idle_redraw_seconds = 0.5;
constexpr int frames_drawn_after_event = 3;

// clothlab-YYYYMMDD-HHMMSS-<stage>.png in the working directory (-2, -3... if taken).
std::filesystem::path screenshot_path(stage_kind stage) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
  const std::string stem = std::string("clothlab-") + stamp + "-" + std::string(stage_name(stage));
  std::filesystem::path path = stem + ".png";
  for (int i = 2; std::filesystem::exists(path); ++i)
    path = stem + "-" + std::to_string(i) + ".png";
  return std::filesystem::absolute(path);
}

// --frames COUNT: counts the frames and, after the last one, prints the mean frame time and the
// steps per second over them.
class frame_counter {
 public:
  frame_counter(long frames, double start_seconds, long start_steps)
      : frames_(frames), start_seconds_(start_seconds), start_steps_(start_steps) {}

  // Called after each frame's swap; true after the last frame (never when frames is 0).
  bool frame_done(double now_seconds, long steps) {
    if (frames_ <= 0 || ++done_ < frames_)
      return false;
    const double seconds = now_seconds - start_seconds_;
    const double steps_per_second =
        seconds > 0.0 ? static_cast<double>(steps - start_steps_) / seconds : 0.0;
    window_log("%ld frames in %.2f s: mean frame time %.2f ms (%.1f frames/s), %.0f steps/s", done_,
               seconds, 1000.0 * seconds / static_cast<double>(done_),
               static_cast<double>(done_) / seconds, steps_per_second);
    return true;
  }

 private:
  long frames_;
  double start_seconds_;
  long start_steps_;
  long done_ = 0;
};

// At exit, what question 2's plot holds: its samples are the steps, whatever the frames (the
// window tests check that a stalled frame left no gap wider than a step).
void print_spring_plot(const spring_motion& motion) {
  const std::vector<float>& times = motion.times();
  if (times.size() < 2)
    return;
  float widest_gap = 0.0f;
  for (std::size_t i = 1; i < times.size(); ++i)
    widest_gap = std::max(widest_gap, times[i] - times[i - 1]);
  window_log("the x(t) plot: %zu samples over %.2f s, widest gap %.4f s", times.size(),
             static_cast<double>(times.back() - times.front()), static_cast<double>(widest_gap));
}

}  // namespace

void deliver_screenshot(stage_kind stage, int width, int height) {
  const std::filesystem::path path = screenshot_path(stage);
  std::string error;
  if (save_framebuffer_png(path.string(), width, height, error))
    std::printf(tr("clothlab-window: screenshot %s\n"), path.c_str());
  else
    std::fprintf(stderr, tr("clothlab-window: screenshot failed: %s\n"), error.c_str());
  std::fflush(stdout);
}

}  // namespace clothlab

int main(int argc, char** argv) {
  using namespace clothlab;
  start_messages();  // the user's language, before the first word (--lang may change it)
  const parse_result parsed = parse_command_line(argc, argv);
  if (!parsed.parsed)
    return parsed.exit_code;
  const options& start = *parsed.parsed;

  std::string error;
  const auto context = glfw_context::create("clothlab", initial_width, initial_height, error);
  if (!context) {
    std::fprintf(stderr, tr("clothlab-window: %s\n"), error.c_str());
    return 1;
  }
  std::printf(tr("clothlab-window: %s, %s\n"), context->description().c_str(),
              context->origin().c_str());
  std::fflush(stdout);

  const auto app = window_app::create(*context, start, error);
  if (!app) {
    std::fprintf(stderr, tr("clothlab-window: %s\n"), error.c_str());
    return 1;
  }
  const scene& the_scene = app->the_scene();
  // --frames COUNT: the window's speed, measured by a script; without vsync, so that it measures
  // the program and not the screen's refresh rate.
  frame_counter measured_run(start.frames, glfwGetTime(), the_scene.steps_taken());
  if (start.frames > 0)
    context->set_vsync(false);

  // Frames still to draw at full rate after an event: Dear ImGui shows the effect of a click or a
  // hover a frame or two after the event.
  int frames_after_event = 0;

  while (!context->should_close()) {
    // Poll window events, keys, mouse (a paused, idle window sleeps until one comes)
    window_input input;
    if (the_scene.idle() && frames_after_event == 0 && start.frames == 0) {
      bool woke_early = false;
      input = context->wait_for_events(idle_redraw_seconds, woke_early);
      if (woke_early)
        frames_after_event = frames_drawn_after_event;
    } else {
      input = context->poll_events();
      frames_after_event = std::max(frames_after_event - 1, 0);
    }
    if (context->is_minimised()) {
      context->wait_events();  // nothing to draw: sleep until the window comes back
      app->restart_clock();
      continue;
    }
    app->frame(input);
    if (measured_run.frame_done(glfwGetTime(), the_scene.steps_taken()))
      break;
  }
  // The GPU paths' state comes back only for what the panel shows (scene.hpp).
  window_log("the GPU state was read back %ld times over %.1f s", the_scene.readbacks(),
             glfwGetTime());
  print_spring_plot(the_scene.motion());
  return 0;
}
