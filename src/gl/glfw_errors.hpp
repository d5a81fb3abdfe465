// GLFW reports its errors through a callback: the last one is kept, as words, for the messages
// of the two contexts that GLFW makes (the window's, window/glfw_context.cpp, and the hidden
// window's off-screen one, hidden_window_context.cpp). Include after gl/gl.hpp (GLEW must come
// before GLFW).
#pragma once

#include <string>

#include <GLFW/glfw3.h>

namespace clothlab {

// The last error GLFW reported: "<its description> (GLFW error <code>)".
inline std::string& last_glfw_error() {
  static std::string error;
  return error;
}

// Sets GLFW's error callback to keep its errors in last_glfw_error(); call before glfwInit.
inline void keep_glfw_errors() {
  glfwSetErrorCallback([](int code, const char* description) {
    last_glfw_error() = description ? description : "unknown GLFW error";
    last_glfw_error() += " (GLFW error " + std::to_string(code) + ")";
  });
}

}  // namespace clothlab
