#include "window/window_app.hpp"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "gl/gl.hpp"  // GLEW on the desktop, which must come before GLFW

#include <GLFW/glfw3.h>

#include "window/layout_probe.hpp"
#include "window/panel.hpp"
#include "window/panel_font.hpp"

namespace clothlab {
namespace {

// The GLSL version line Dear ImGui's OpenGL 3 backend writes in its shaders.
#if defined(CLOTHLAB_GL_WEB)
constexpr const char* imgui_glsl_version = "#version 300 es";
#else
constexpr const char* imgui_glsl_version = "#version 330";
#endif

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

// Dear ImGui with its GLFW and OpenGL 3 backends, for the lifetime of the object.
class window_app::imgui_session {
 public:
  explicit imgui_session(glfw_context& context) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // write no imgui.ini into the working directory
    ImGui::StyleColorsDark();
    // HiDPI: the font made at the screen's scale (crisp, not stretched) and every size with it.
    const float scale = std::clamp(context.content_scale(), 1.0f, 4.0f);
    add_panel_font(std::round(13.0f * scale));  // the size of Dear ImGui's default font
    ImGui::GetStyle().ScaleAllSizes(scale);
    ImGui_ImplGlfw_InitForOpenGL(context.window(),
                                 true);  // chains to the window's own key callbacks
    ImGui_ImplOpenGL3_Init(imgui_glsl_version);
  }
  ~imgui_session() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  imgui_session(const imgui_session&) = delete;
  imgui_session& operator=(const imgui_session&) = delete;
};

// The mouse, unless it is over the panel. A left drag that starts on the cloth (or on a mass of
// stages 1 and 2) grabs the particle under the cursor and pulls it (scene::grab_particle);
// Shift + left drag moves the cloth's sphere; any other left drag orbits. Right drag pans, the
// wheel zooms.
class window_app::mouse_control {
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
      window_log("sphere moved to (%.3f, %.3f, %.3f)", c.x, c.y, c.z);
    }
    print_camera("ended", the_scene.view);
    left_drag_ = left_drag::none;
  }

  void print_camera(const char* when, const camera& view) const {
    const char* what = left_drag_ == left_drag::grab     ? "grab"
                       : left_drag_ == left_drag::sphere ? "sphere"
                                                         : "orbit";
    window_log("left drag %s (%s): camera yaw %.4f, pitch %.4f", when, what, view.yaw, view.pitch);
  }

  double last_x_ = 0.0;
  double last_y_ = 0.0;
  bool left_was_down_ = false;
  left_drag left_drag_ = left_drag::none;
};

std::unique_ptr<window_app> window_app::create(glfw_context& context, const options& start,
                                               std::string& error) {
  std::unique_ptr<window_app> app(new window_app(context, start));
  if (start.frames > 0) {  // measured from the first frame: no hold of the initial state
    app->scene_.control.start_hold_seconds = 0.0;
    app->scene_.control.start_hold_frames = 0;
  }
  if (!app->scene_.init_renderer(error))
    return nullptr;
  app->scene_.load_model();
  if (on_gpu(start.backend))
    app->scene_.switch_cloth_backend(start.backend);  // says why when it cannot
  app->ui_ = std::make_unique<imgui_session>(context);
  app->mouse_ = std::make_unique<mouse_control>();
  app->previous_time_ = glfwGetTime();
  return app;
}

window_app::window_app(glfw_context& context, const options& start)
    : context_(context), scene_(start.stage, start.spring, start.coupled, start.cloth) {
  scene_.spring_one_dimensional_start = start.spring_1d_start;
}

window_app::~window_app() = default;

void window_app::restart_clock() {
  previous_time_ = glfwGetTime();
}

void window_app::frame(const window_input& input) {
  // ---- 1. Poll (the platform polled): keys, mouse ----
  // (the frame anatomy's clock starts after the platform's sleep: questions 1 and 3,
  // frame_anatomy.hpp)
  const double now = glfwGetTime();
  const double frame_seconds = now - previous_time_;
  previous_time_ = now;
  const double frame_start = now;
  mouse_->update(context_.window(), input.scroll, scene_);

  // ---- 2. UI: the panel edits the parameters; actions from keys and buttons applied ----
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  // The keys after NewFrame: whether the panel has the keyboard (a value being typed) is then
  // that of the frame before, not of two frames ago (a key pressed just after a click on a
  // widget, whose release the frame before saw, was lost).
  user_actions actions = actions_from_keys(input.pressed_keys);
  const float panel_covered_width = build_control_panel(scene_, actions);
  draw_drag_line(scene_);
  if (show_help_)
    build_key_help(show_help_);
  ImGui::Render();
  apply_actions(actions, scene_, show_help_, context_);

  // ---- 3. Simulate and 4. draw: the handout's draw_scene, then the panel over it ----
  const int width = context_.framebuffer_width();
  const int height = context_.framebuffer_height();
  const ImVec2 pixels_per_unit = ImGui::GetIO().DisplayFramebufferScale;  // HiDPI
  const int scene_left =
      std::min(static_cast<int>(panel_covered_width * pixels_per_unit.x), width - 1);
  const double scene_start = glfwGetTime();
  scene_.draw_scene(frame_seconds, scene_left, width - scene_left, height);
  const double scene_end = glfwGetTime();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (actions.screenshot)
    deliver_screenshot(scene_.stage(), width, height);

  // ---- 5. Swap ----
  context_.swap_buffers();
  const double frame_end = glfwGetTime();
  scene_.finish_frame_anatomy(scene_start - frame_start, frame_end - scene_end,
                              frame_end - frame_start);
}

}  // namespace clothlab
