// GLSL programs loaded from the files of shaders/. A file that is missing or does not compile or
// link gives an error naming the file and carrying the compiler's log; nothing is drawn with it.
// The files have no #version line: the loader puts the one of the build's GL before them
// (shader.cpp), and the compiler's line numbers are those of the file.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gl/gl.hpp"

namespace clothlab {

// The folder of shaders/ and assets/: CLOTHLAB_DATA_DIR from the environment if set, else the
// folder beside the executable if it has shaders/ (an installed copy), else the source tree's,
// fixed at build time. Never the working directory.
std::filesystem::path data_directory();
std::filesystem::path shader_path(std::string_view file_name);  // data_directory()/shaders/...
std::filesystem::path asset_path(std::string_view file_name);   // data_directory()/assets/...

// Owns a linked GL program. Move-only.
class shader_program {
 public:
  shader_program() = default;
  ~shader_program();
  shader_program(shader_program&& other) noexcept;
  shader_program& operator=(shader_program&& other) noexcept;
  shader_program(const shader_program&) = delete;
  shader_program& operator=(const shader_program&) = delete;

  // Compiles shaders/<vertex_file> and shaders/<fragment_file> and links them. On failure returns
  // false and sets error to "shaders/<file>: <what> ... <info log>".
  bool load(std::string_view vertex_file, std::string_view fragment_file, std::string& error);
  // Compiles and links the compute shader shaders/<compute_file> (OpenGL 4.3); same errors. The
  // web build has no compute shaders (WebGL2): there it returns false with an error saying so.
  bool load_compute(std::string_view compute_file, std::string& error);

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }
  // A compute program's work group size (its layout(local_size_x, local_size_y)); (1, 1) for
  // any other program.
  glm::ivec2 work_group_size() const { return work_group_size_; }
  // glDispatchCompute of enough work groups to cover an n x n grid with one invocation per
  // cell; the program must be in use.
  void dispatch_over_grid(int n) const;
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }
  // Sets the uniform `name` of this program, which must be in use (use()); a name the program
  // does not have (or that its compiler removed as unused) is ignored, as GL does.
  void set(const char* name, const glm::mat4& value) const;
  void set(const char* name, const glm::vec4& value) const;
  void set(const char* name, const glm::vec3& value) const;
  void set(const char* name, const glm::vec2& value) const;
  void set(const char* name, float value) const;
  void set(const char* name, int value) const;

 private:
  // Links the compiled shaders (and deletes them); files names them in an error.
  bool link(std::initializer_list<GLuint> shaders, const std::string& files, std::string& error);
  GLuint id_ = 0;
  glm::ivec2 work_group_size_{1, 1};
};

}  // namespace clothlab
