// clothlab-window: the interactive demo of the lab. The same options as `clothlab`
// (docs/cli.md); it starts on --stage. The main loop below reads top to bottom in five phases:
// poll, UI, simulate, draw, swap.
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "gl/gl.hpp"  // GLEW, which must come before GLFW

#include <GLFW/glfw3.h>

#include "window/glfw_context.hpp"

#include "app/options.hpp"
#include "gl/renderer.hpp"
#include "window/panel.hpp"
#include "window/scene.hpp"

namespace {

using namespace clothlab;

constexpr int initial_width = 1280;  // screen coordinates
constexpr int initial_height = 800;
// A paused window draws a frame when an event comes (then a few more) or after this long (the
// readouts stay fresh); otherwise it sleeps instead of drawing the same frame again.
constexpr double idle_redraw_seconds = 0.5;
constexpr int frames_drawn_after_event = 3;

// Dear ImGui with its GLFW and OpenGL 3 backends, for the lifetime of the object.
class imgui_session {
 public:
  explicit imgui_session(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // write no imgui.ini into the working directory
    ImGui::StyleColorsDark();
    // HiDPI: the font made at the screen's scale (crisp, not stretched) and every size with it.
    float scale_x = 1.0f, scale_y = 1.0f;
    glfwGetWindowContentScale(window, &scale_x, &scale_y);
    const float scale = std::clamp(std::max(scale_x, scale_y), 1.0f, 4.0f);
    ImFontConfig font;
    font.SizePixels = std::round(13.0f * scale);  // Dear ImGui's default font is 13 px
    io.Fonts->AddFontDefault(&font);
    ImGui::GetStyle().ScaleAllSizes(scale);
    ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains to the window's own key callbacks
    ImGui_ImplOpenGL3_Init("#version 330");
  }
  ~imgui_session() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  imgui_session(const imgui_session&) = delete;
  imgui_session& operator=(const imgui_session&) = delete;
};

// The keys of the demo (the panel's buttons raise the same actions). None while Dear ImGui is
// using the keyboard (typing a value into a slider).
user_actions actions_from_keys(const std::vector<int>& pressed_keys) {
  user_actions actions;
  if (ImGui::GetIO().WantCaptureKeyboard)
    return actions;
  for (const int key : pressed_keys) {
    switch (key) {
      case GLFW_KEY_1:
        actions.select_stage = stage_kind::spring;
        break;
      case GLFW_KEY_2:
        actions.select_stage = stage_kind::coupled;
        break;
      case GLFW_KEY_3:
        actions.select_stage = stage_kind::cloth;
        break;
      case GLFW_KEY_SPACE:
        actions.toggle_running = !actions.toggle_running;
        break;
      case GLFW_KEY_N:
        actions.single_step = true;
        break;
      case GLFW_KEY_R:
        actions.reset = true;
        break;
      case GLFW_KEY_W:
        actions.toggle_wireframe = !actions.toggle_wireframe;
        break;
      case GLFW_KEY_P:
        actions.screenshot = true;
        break;
      case GLFW_KEY_H:
        actions.toggle_help = !actions.toggle_help;
        break;
      case GLFW_KEY_V:
        actions.reset_view = true;
        break;
      case GLFW_KEY_G:
        actions.switch_cloth_backend = !actions.switch_cloth_backend;
        break;
      case GLFW_KEY_M:
        actions.measure_backends = true;
        break;
      case GLFW_KEY_ESCAPE:
        actions.quit = true;
        break;
      default:
        break;
    }
  }
  return actions;
}

// The mouse, unless it is over the panel. A left drag that starts on the cloth (or on a mass of
// stages 1 and 2) grabs the particle under the cursor and pulls it (scene::grab_particle);
// Shift + left drag moves the cloth's sphere; any other left drag orbits. Right drag pans, the
// wheel zooms.
class mouse_control {
 public:
  void update(GLFWwindow* window, double scroll, scene& the_scene) {
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    const auto dx = static_cast<float>(x - last_x_);
    const auto dy = static_cast<float>(y - last_y_);
    last_x_ = x;
    last_y_ = y;
    int width = 0, height = 0;
    glfwGetWindowSize(window, &width, &height);
    int framebuffer_width = 0, framebuffer_height = 0;
    glfwGetFramebufferSize(window, &framebuffer_width, &framebuffer_height);
    // The cursor in framebuffer pixels (the scene's units; HiDPI screens have more of them).
    const double pixel_x = x * framebuffer_width / std::max(width, 1);
    const double pixel_y = y * framebuffer_height / std::max(height, 1);
    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool over_panel = ImGui::GetIO().WantCaptureMouse;

    if (left && left_drag_ == left_drag::none && !left_was_down_ && !over_panel) {
      left_drag_ = start_left_drag(window, the_scene, the_scene.ray_at(pixel_x, pixel_y));
      print_camera("started", the_scene.view);
    }
    if (left) {
      switch (left_drag_) {
        case left_drag::grab:
          the_scene.drag_grabbed(the_scene.ray_at(pixel_x, pixel_y));
          break;
        case left_drag::sphere:
          the_scene.move_sphere(the_scene.ray_at(pixel_x, pixel_y));
          break;
        case left_drag::orbit: {
          const float pixels = static_cast<float>(height > 0 ? height : 1);
          // a window height turns ~170 degrees
          the_scene.view.orbit(-3.0f * dx / pixels, 3.0f * dy / pixels);
          break;
        }
        case left_drag::none:
          break;
      }
    } else if (left_drag_ != left_drag::none) {
      end_left_drag(the_scene);
    }
    left_was_down_ = left;

    if (over_panel)
      return;
    const float pixels = static_cast<float>(height > 0 ? height : 1);
    if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
      the_scene.view.pan(-0.85f * dx / pixels, 0.85f * dy / pixels);  // follows the cursor
    if (scroll != 0.0)
      the_scene.view.zoom(static_cast<float>(std::pow(0.9, scroll)));
  }

 private:
  enum class left_drag { none, orbit, grab, sphere };
  static constexpr double pick_radius_pixels = 6.0;  // a press this near a particle grabs it

  static left_drag start_left_drag(GLFWwindow* window, scene& the_scene, const pick_ray& ray) {
    const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                       glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    const bool cloth = the_scene.stage() == stage_kind::cloth;
    if (shift && cloth && the_scene.cloth_stage.parameters.sphere.enabled) {
      the_scene.start_sphere_move(ray);
      return left_drag::sphere;
    }
    if (!shift && the_scene.grab_particle(ray, pick_radius_pixels * the_scene.radians_per_pixel()))
      return left_drag::grab;
    return left_drag::orbit;
  }

  // Ends the drag with a line saying what it did and where the camera is (the window tests read
  // it: a drag on the cloth or a mass leaves the camera where it was).
  void end_left_drag(scene& the_scene) {
    if (left_drag_ == left_drag::grab) {
      the_scene.release_grab();
    } else if (left_drag_ == left_drag::sphere) {
      const glm::dvec3& c = the_scene.cloth_stage.parameters.sphere.centre;
      std::printf("clothlab-window: sphere moved to (%.3f, %.3f, %.3f)\n", c.x, c.y, c.z);
    }
    print_camera("ended", the_scene.view);
    left_drag_ = left_drag::none;
  }

  void print_camera(const char* when, const camera& view) const {
    const char* what = left_drag_ == left_drag::grab     ? "grab"
                       : left_drag_ == left_drag::sphere ? "sphere"
                                                         : "orbit";
    std::printf("clothlab-window: left drag %s (%s): camera yaw %.4f, pitch %.4f\n", when, what,
                view.yaw, view.pitch);
    std::fflush(stdout);
  }

  double last_x_ = 0.0;
  double last_y_ = 0.0;
  bool left_was_down_ = false;
  left_drag left_drag_ = left_drag::none;
};

// While a particle or mass is grabbed: a thin line from it to the drag target, over the scene.
void draw_drag_line(scene& the_scene) {
  if (!the_scene.grabbing())
    return;
  const std::optional<glm::dvec2> from = the_scene.framebuffer_point(the_scene.grabbed_position());
  const std::optional<glm::dvec2> to = the_scene.framebuffer_point(the_scene.drag_target());
  if (!from || !to)
    return;
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;  // framebuffer -> ImGui units
  const ImVec2 a = {static_cast<float>(from->x) / scale.x, static_cast<float>(from->y) / scale.y};
  const ImVec2 b = {static_cast<float>(to->x) / scale.x, static_cast<float>(to->y) / scale.y};
  ImDrawList& draw = *ImGui::GetBackgroundDrawList();
  draw.AddLine(a, b, IM_COL32(255, 230, 60, 230), 2.0f);
  draw.AddCircleFilled(b, 4.0f, IM_COL32(255, 230, 60, 230));
}

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

// The frame as the user sees it, panel included, read from the back buffer before the swap.
void save_screenshot(stage_kind stage, int width, int height) {
  const std::filesystem::path path = screenshot_path(stage);
  std::string error;
  if (save_framebuffer_png(path.string(), width, height, error))
    std::printf("clothlab-window: screenshot %s\n", path.c_str());
  else
    std::fprintf(stderr, "clothlab-window: screenshot failed: %s\n", error.c_str());
  std::fflush(stdout);
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
    std::printf(
        "clothlab-window: %ld frames in %.2f s: mean frame time %.2f ms (%.1f frames/s), %.0f "
        "steps/s\n",
        done_, seconds, 1000.0 * seconds / static_cast<double>(done_),
        static_cast<double>(done_) / seconds, steps_per_second);
    std::fflush(stdout);
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
  std::printf("clothlab-window: the x(t) plot: %zu samples over %.2f s, widest gap %.4f s\n",
              times.size(), static_cast<double>(times.back() - times.front()),
              static_cast<double>(widest_gap));
}

void apply_actions(const user_actions& actions, scene& the_scene, bool& show_help,
                   glfw_context& context) {
  if (actions.select_stage)
    the_scene.select_stage(*actions.select_stage);
  if (actions.reset)
    the_scene.reset();
  if (actions.toggle_running)
    the_scene.toggle_running();
  if (actions.single_step)
    the_scene.single_step();
  if (actions.reset_view)
    the_scene.reset_view();
  if (actions.toggle_wireframe)
    the_scene.display.wireframe = !the_scene.display.wireframe;
  if (actions.toggle_help)
    show_help = !show_help;
  if (actions.switch_cloth_backend)
    the_scene.toggle_cloth_backend();
  if (actions.select_cloth_backend)
    the_scene.switch_cloth_backend(*actions.select_cloth_backend);
  if (actions.measure_backends)
    the_scene.measure_backends(steps_per_backend_measurement);
  if (actions.quit)
    context.request_close();
}

}  // namespace

int main(int argc, char** argv) {
  const parse_result parsed = parse_command_line(argc, argv);
  if (!parsed.parsed)
    return parsed.exit_code;
  const options& start = *parsed.parsed;

  std::string error;
  const auto context = glfw_context::create("clothlab", initial_width, initial_height, error);
  if (!context) {
    std::fprintf(stderr, "clothlab-window: %s\n", error.c_str());
    return 1;
  }
  std::printf("clothlab-window: %s, %s\n", context->description().c_str(),
              context->origin().c_str());
  std::fflush(stdout);

  scene the_scene(start);
  if (start.frames > 0) {  // measured from the first frame: no hold of the initial state
    the_scene.control.start_hold_seconds = 0.0;
    the_scene.control.start_hold_frames = 0;
  }
  if (!the_scene.init_renderer(error)) {
    std::fprintf(stderr, "clothlab-window: %s\n", error.c_str());
    return 1;
  }
  the_scene.load_model();
  if (on_gpu(start.backend))
    the_scene.switch_cloth_backend(start.backend);  // says why when it cannot

  const imgui_session ui(context->window());
  mouse_control mouse;
  bool show_help = false;
  double previous_time = glfwGetTime();
  // --frames COUNT: the window's speed, measured by a script; without vsync, so that it measures
  // the program and not the screen's refresh rate.
  frame_counter measured_run(start.frames, previous_time, the_scene.steps_taken());
  if (start.frames > 0)
    context->set_vsync(false);

  // Frames still to draw at full rate after an event: Dear ImGui shows the effect of a click or a
  // hover a frame or two after the event.
  int frames_after_event = 0;

  while (!context->should_close()) {
    // ---- 1. Poll: window events, keys, mouse (a paused, idle window sleeps until one comes) ----
    // (the frame anatomy's clock starts after the sleep: questions 1 and 3, frame_anatomy.hpp)
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
      previous_time = glfwGetTime();
      continue;
    }
    const double now = glfwGetTime();
    const double frame_seconds = now - previous_time;
    previous_time = now;
    const double frame_start = now;
    user_actions actions = actions_from_keys(input.pressed_keys);
    mouse.update(context->window(), input.scroll, the_scene);

    // ---- 2. UI: the panel edits the parameters; actions from keys and buttons applied ----
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    const float panel_covered_width = build_control_panel(the_scene, actions);
    draw_drag_line(the_scene);
    if (show_help)
      build_key_help(show_help);
    ImGui::Render();
    apply_actions(actions, the_scene, show_help, *context);

    // ---- 3. Simulate and 4. draw: the handout's draw_scene, then the panel over it ----
    const int width = context->framebuffer_width();
    const int height = context->framebuffer_height();
    const ImVec2 pixels_per_unit = ImGui::GetIO().DisplayFramebufferScale;  // HiDPI
    const int scene_left =
        std::min(static_cast<int>(panel_covered_width * pixels_per_unit.x), width - 1);
    const double scene_start = glfwGetTime();
    the_scene.draw_scene(frame_seconds, scene_left, width - scene_left, height);
    const double scene_end = glfwGetTime();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (actions.screenshot)
      save_screenshot(the_scene.stage(), width, height);

    // ---- 5. Swap ----
    context->swap_buffers();
    const double frame_end = glfwGetTime();
    the_scene.finish_frame_anatomy(scene_start - frame_start, frame_end - scene_end,
                                   frame_end - frame_start);
    if (measured_run.frame_done(glfwGetTime(), the_scene.steps_taken()))
      break;
  }
  // Issue 9: the GPU paths' state comes back only for what the panel shows (scene.hpp).
  std::printf("clothlab-window: the GPU state was read back %ld times over %.1f s\n",
              the_scene.readbacks(), glfwGetTime());
  print_spring_plot(the_scene.motion());
  return 0;
}
