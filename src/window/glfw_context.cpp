#include "window/glfw_context.hpp"

#include <algorithm>
#include <cstdio>

#include "gl/gl.hpp"  // GLEW, which must come before GLFW

#include "core/i18n.hpp"
#include "gl/glfw_errors.hpp"  // GLFW

namespace clothlab {

std::unique_ptr<glfw_context> glfw_context::create(const std::string& title, int width, int height,
                                                   std::string& error) {
  keep_glfw_errors();
  if (glfwInit() != GLFW_TRUE) {
    error = format(tr("cannot open a window: %s. Is a display available? Run it under "
                      "`xvfb-run -a`, or use `clothlab --headless`."),
                   last_glfw_error().c_str());
    return nullptr;
  }
#if defined(CLOTHLAB_GL_WEB)
  // The browser: emscripten's GLFW makes the page's canvas a WebGL2 context (OpenGL ES 3.0).
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  const char* wanted = tr("cannot create a WebGL2 context: %s");
#else
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  const char* wanted = tr("cannot create a window with an OpenGL 3.3 core context: %s");
#endif
  GLFWwindow* window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window == nullptr) {
    error = format(wanted, last_glfw_error().c_str());
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(window);
#if !defined(CLOTHLAB_GL_WEB)  // (the browser's GL functions need no loading)
  glewExperimental = GL_TRUE;
  if (const GLenum status = glewInit(); status != GLEW_OK) {
    error = std::string(tr("GLEW cannot load the OpenGL functions:")) + " " +
            reinterpret_cast<const char*>(glewGetErrorString(status));
    glfwDestroyWindow(window);
    glfwTerminate();
    return nullptr;
  }
  glGetError();  // glewInit leaves GL_INVALID_ENUM behind in a core context: discard it
#endif
  glfwSwapInterval(1);

  auto context = std::unique_ptr<glfw_context>(new glfw_context(window));
  glfwSetWindowUserPointer(window, context.get());
  // Installed before Dear ImGui's, which calls them after its own handling.
  glfwSetKeyCallback(window, on_key);
  glfwSetScrollCallback(window, on_scroll);
  return context;
}

glfw_context::glfw_context(GLFWwindow* window) : window_(window) {}

glfw_context::~glfw_context() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

int glfw_context::framebuffer_width() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return width;
}

int glfw_context::framebuffer_height() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return height;
}

float glfw_context::content_scale() const {
  float x = 1.0f, y = 1.0f;
#if !defined(CLOTHLAB_GL_WEB)  // (emscripten's GLFW draws the canvas at one pixel a unit)
  glfwGetWindowContentScale(window_, &x, &y);
#endif
  return std::max(x, y);
}

bool glfw_context::should_close() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

void glfw_context::request_close() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

window_input glfw_context::poll_events() {
  glfwPollEvents();
  window_input gathered = std::move(input_);
  input_ = {};
  return gathered;
}

window_input glfw_context::wait_for_events(double seconds, bool& woke_early) {
  const double start = glfwGetTime();
  glfwWaitEventsTimeout(seconds);
  woke_early = glfwGetTime() - start < seconds;
  window_input gathered = std::move(input_);
  input_ = {};
  return gathered;
}

bool glfw_context::is_minimised() const {
  return glfwGetWindowAttrib(window_, GLFW_ICONIFIED) == GLFW_TRUE || framebuffer_width() == 0 ||
         framebuffer_height() == 0;
}

void glfw_context::wait_events() {
  glfwWaitEvents();
}

void glfw_context::swap_buffers() {
  glfwSwapBuffers(window_);
}

void glfw_context::set_vsync(bool on) {
  glfwSwapInterval(on ? 1 : 0);
}

void glfw_context::on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action != GLFW_PRESS)
    return;
  auto* self = static_cast<glfw_context*>(glfwGetWindowUserPointer(window));
  self->input_.pressed_keys.push_back(key);
}

void glfw_context::on_scroll(GLFWwindow* window, double /*x_offset*/, double y_offset) {
  auto* self = static_cast<glfw_context*>(glfwGetWindowUserPointer(window));
  self->input_.scroll += y_offset;
}

}  // namespace clothlab
