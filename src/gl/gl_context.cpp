#include "gl/gl_context.hpp"

#include "gl/gl.hpp"

namespace clothlab {

std::string gl_context::description() const {
  auto text = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  return text(GL_RENDERER) + ", OpenGL " + text(GL_VERSION);
}

}  // namespace clothlab
