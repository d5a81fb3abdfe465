// The off-screen gl_context where the system has neither OSMesa nor EGL (macOS): the OpenGL
// core context of a GLFW window that is never shown, its functions loaded by GLEW. It needs a
// display (macOS always has one; on Linux, xvfb-run -a). The default framebuffer of the hidden
// window is the off-screen buffer, of exactly the size asked (no HiDPI scaling).
#include <string>

#include "gl/gl.hpp"  // GLEW, which must come before GLFW
#include "gl/gl_context.hpp"

#include "core/i18n.hpp"
#include "gl/glfw_errors.hpp"  // GLFW

namespace clothlab {
namespace {

class hidden_window_context final : public gl_context {
 public:
  explicit hidden_window_context(GLFWwindow* window) : window_(window) {}
  ~hidden_window_context() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  hidden_window_context(const hidden_window_context&) = delete;
  hidden_window_context& operator=(const hidden_window_context&) = delete;

  int framebuffer_width() const override { return size().first; }
  int framebuffer_height() const override { return size().second; }
  std::string origin() const override { return tr("in a hidden GLFW window (no OSMesa, no EGL)"); }

 private:
  std::pair<int, int> size() const {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    return {width, height};
  }
  GLFWwindow* window_;
};

}  // namespace

std::unique_ptr<gl_context> create_offscreen_context(int width, int height, std::string& error) {
  if (width < 1 || height < 1) {
    error =
        format(tr("off-screen buffer %dx%d: both sides must be at least 1 pixel"), width, height);
    return nullptr;
  }
  keep_glfw_errors();
  // (macOS: the working directory stays where the output files are written.)
  glfwInitHint(GLFW_COCOA_CHDIR_RESOURCES, GLFW_FALSE);
  if (glfwInit() != GLFW_TRUE) {
    error =
        format(tr("this build renders off screen in a hidden GLFW window (it has neither OSMesa "
                  "nor EGL), which needs a display: %s. Under Linux, run it with `xvfb-run -a`."),
               last_glfw_error().c_str());
    return nullptr;
  }
  // 4.3 core (compute shaders) where the driver has it, else 3.3 core (macOS: 4.1).
  GLFWwindow* window = nullptr;
  for (const int version : {43, 33}) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_COCOA_RETINA_FRAMEBUFFER, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, version / 10);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, version % 10);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    window = glfwCreateWindow(width, height, "clothlab (off screen)", nullptr, nullptr);
    if (window != nullptr)
      break;
  }
  if (window == nullptr) {
    error = format(tr("cannot create a hidden window with an OpenGL 3.3 core context: %s"),
                   last_glfw_error().c_str());
    glfwTerminate();
    return nullptr;
  }
  auto result = std::make_unique<hidden_window_context>(window);
  glfwMakeContextCurrent(window);
  glewExperimental = GL_TRUE;
  if (const GLenum status = glewInit(); status != GLEW_OK) {
    error = std::string(tr("GLEW cannot load the OpenGL functions:")) + " " +
            reinterpret_cast<const char*>(glewGetErrorString(status));
    return nullptr;
  }
  glGetError();  // glewInit leaves GL_INVALID_ENUM behind in a core context: discard it
  return result;
}

}  // namespace clothlab
