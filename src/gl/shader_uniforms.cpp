// shader_program's uniform setters (shader.hpp), one per type the drawing passes use.
#include <glm/gtc/type_ptr.hpp>

#include "gl/shader.hpp"

namespace clothlab {

void shader_program::set(const char* name, const glm::mat4& value) const {
  glUniformMatrix4fv(uniform(name), 1, GL_FALSE, glm::value_ptr(value));
}
void shader_program::set(const char* name, const glm::vec4& value) const {
  glUniform4fv(uniform(name), 1, glm::value_ptr(value));
}
void shader_program::set(const char* name, const glm::vec3& value) const {
  glUniform3fv(uniform(name), 1, glm::value_ptr(value));
}
void shader_program::set(const char* name, const glm::vec2& value) const {
  glUniform2fv(uniform(name), 1, glm::value_ptr(value));
}
void shader_program::set(const char* name, float value) const {
  glUniform1f(uniform(name), value);
}
void shader_program::set(const char* name, int value) const {
  glUniform1i(uniform(name), value);
}

}  // namespace clothlab
