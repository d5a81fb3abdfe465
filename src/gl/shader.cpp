#include "gl/shader.hpp"

#include "core/executable_path.hpp"

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

// The first lines of every shader. The files of shaders/ begin without a #version line, so that
// one file serves both GL dialects: they are written in the subset common to GLSL 3.30 core and
// GLSL ES 3.00 (docs/gpu.md). The desktop compiles them as GLSL 3.30 core (OpenGL 3.3), and its
// compute shaders as 4.30 core (OpenGL 4.3). The web build compiles them as GLSL ES 3.00
// (WebGL2), where precisions are declared: float has no default in a fragment shader, int there
// defaults to mediump, sampler2D to lowp, and usampler2D has none. Its header gives every type
// the shaders use highp, the desktop's precision (a shader using another sampler type needs its
// line here). tests/render/check_shader_dialects.py reads these three strings from here and
// checks every shader with each (glslangValidator).
[[maybe_unused]] constexpr std::string_view desktop_header = "#version 330 core\n";
[[maybe_unused]] constexpr std::string_view desktop_compute_header = "#version 430 core\n";
[[maybe_unused]] constexpr std::string_view web_header =
    "#version 300 es\n"
    "precision highp float;\n"
    "precision highp int;\n"
    "precision highp sampler2D;\n"
    "precision highp usampler2D;\n";
#if defined(CLOTHLAB_GL_WEB)
constexpr std::string_view vertex_and_fragment_header = web_header;
#else
constexpr std::string_view vertex_and_fragment_header = desktop_header;
#endif

std::filesystem::path executable_directory() {
  return executable_path().parent_path();
}

bool read_text(const std::filesystem::path& path, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return false;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  text = buffer.str();
  return true;
}

// The line numbers of the n-th included file start at n * included_lines (10001, 20001, ...),
// its source-string number n: some compilers (Mesa) report every message of the syntax tree as
// string 0, so the line number alone must tell the files apart.
constexpr long included_lines = 10000;

// Replaces each line `#include "FILE"` of a shader by FILE (from the shaders folder), so that
// what the two GPU paths share is written once (gpu_cloth_common.glsl). The lines of the n-th
// included file are numbered from n * included_lines + 1 in source string n (#line), and
// `files` gets its name at index n (index 0: the shader's own); a #line directive after them
// gives the including file its own line numbers back. One level only: an included file
// includes none.
bool expand_includes(const std::filesystem::path& path, std::string& source,
                     std::vector<std::string>& files, std::string& error) {
  std::istringstream lines(source);
  std::ostringstream out;
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    const std::string directive = "#include \"";
    const std::size_t end = line.find('"', directive.size());
    if (line.rfind(directive, 0) != 0 || end == std::string::npos) {
      out << line << '\n';
      continue;
    }
    const std::string name = line.substr(directive.size(), end - directive.size());
    const auto included = shader_path(name);
    std::string text;
    if (!read_text(included, text)) {
      error = included.string() + colon() +
              format(tr("cannot read the shader file (included by %s)"), path.string().c_str());
      return false;
    }
    if (text.find("\n#include") != std::string::npos || text.rfind("#include", 0) == 0) {
      error = included.string() + colon() +
              tr("an included shader file includes another (one level only)");
      return false;
    }
    files.push_back("shaders/" + name);
    const long n = static_cast<long>(files.size()) - 1;
    out << "#line " << n * included_lines + 1 << " " << n << "\n"
        << text << (text.ends_with('\n') ? "" : "\n") << "#line " << number + 1 << " 0\n";
  }
  source = out.str();
  return true;
}

// The compiler's log with each message's place written as the file and its line: "0:10074(2):
// error: ..." (Mesa), "ERROR: 1:10074: ..." (ANGLE, glslang) and "1(10074) : error ..." (NVIDIA)
// become "shaders/gpu_cloth_common.glsl:74(2): error: ...", and so on.
std::string name_source_strings(const std::string& log, const std::vector<std::string>& files) {
  std::istringstream lines(log);
  std::string named;
  const auto digits_from = [](const std::string& text, std::size_t at) {
    while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])) != 0)
      ++at;
    return at;
  };
  for (std::string line; std::getline(lines, line);) {
    std::size_t start = 0;
    for (const std::string_view prefix : {"ERROR: ", "WARNING: "}) {
      if (line.starts_with(prefix))
        start = prefix.size();
    }
    const std::size_t string_end = digits_from(line, start);
    const std::size_t line_end =
        string_end + 1 < line.size() ? digits_from(line, string_end + 1) : 0;
    if (string_end > start && line_end > string_end + 1 &&
        (line[string_end] == ':' || line[string_end] == '(')) {
      const long string_number = std::stol(line.substr(start, string_end - start));
      const long number = std::stol(line.substr(string_end + 1, line_end - string_end - 1));
      const long file = number > included_lines ? number / included_lines : string_number;
      if (file < static_cast<long>(files.size())) {
        const std::string place =
            files[static_cast<std::size_t>(file)] + line[string_end] +
            std::to_string(number > included_lines ? number % included_lines : number);
        line.replace(start, line_end - start, place);
      }
    }
    named += line + '\n';
  }
  if (!log.ends_with('\n') && !named.empty())
    named.pop_back();
  return named;
}

// Compiles one stage, the file after `header` (its #version line); returns 0 and sets error on
// failure.
GLuint compile(GLenum type, std::string_view header, std::string_view file_name,
               std::string& error) {
  const auto path = shader_path(file_name);
  std::string source;
  if (!read_text(path, source)) {
    error = path.string() + colon() + tr("cannot read the shader file");
    return 0;
  }
  if (source.starts_with("#version")) {
    error = path.string() + colon() +
            tr("begins with a #version line; remove it, the loader adds the version "
               "(src/gl/shader.cpp)");
    return 0;
  }
  std::vector<std::string> files = {"shaders/" + std::string(file_name)};
  if (!expand_includes(path, source, files, error))
    return 0;
  // "#line 1 0": the file's first line is line 1 in the compiler's messages, as in an editor.
  source = std::string(header) + "#line 1 0\n" + source;
  GLuint shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 1 ? length : 1), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    error = path.string() + colon() +
            tr("does not compile (each message names its file and line):") + "\n" +
            name_source_strings(log.c_str(), files);
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

}  // namespace

std::filesystem::path data_directory() {
  if (const char* env = std::getenv("CLOTHLAB_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  const auto beside = executable_directory() / "share" / "clothlab";
  std::error_code ec;
  if (std::filesystem::is_directory(beside / "shaders", ec))
    return beside;
  return CLOTHLAB_SOURCE_DATA_DIR;
}

std::filesystem::path shader_path(std::string_view file_name) {
  return data_directory() / "shaders" / file_name;
}

std::filesystem::path asset_path(std::string_view file_name) {
  return data_directory() / "assets" / file_name;
}

shader_program::~shader_program() {
  if (id_ != 0)
    glDeleteProgram(id_);
}

shader_program::shader_program(shader_program&& other) noexcept
    : id_(std::exchange(other.id_, 0)),
      work_group_size_(std::exchange(other.work_group_size_, glm::ivec2(1, 1))) {}

shader_program& shader_program::operator=(shader_program&& other) noexcept {
  if (this != &other) {
    if (id_ != 0)
      glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
    work_group_size_ = std::exchange(other.work_group_size_, glm::ivec2(1, 1));
  }
  return *this;
}

bool shader_program::load(std::string_view vertex_file, std::string_view fragment_file,
                          std::string& error) {
  GLuint vertex = compile(GL_VERTEX_SHADER, vertex_and_fragment_header, vertex_file, error);
  if (vertex == 0)
    return false;
  GLuint fragment = compile(GL_FRAGMENT_SHADER, vertex_and_fragment_header, fragment_file, error);
  if (fragment == 0) {
    glDeleteShader(vertex);
    return false;
  }
  return link({vertex, fragment},
              shader_path(vertex_file).string() + " + " + std::string(fragment_file), error);
}

bool shader_program::load_compute(std::string_view compute_file, std::string& error) {
#if defined(CLOTHLAB_GL_WEB)
  error = shader_path(compute_file).string() + colon() +
          tr("a compute shader needs OpenGL 4.3, and WebGL2 has no compute shaders");
  return false;
#else
  GLuint compute = compile(GL_COMPUTE_SHADER, desktop_compute_header, compute_file, error);
  if (compute == 0)
    return false;
  if (!link({compute}, shader_path(compute_file).string(), error))
    return false;
  GLint size[3] = {1, 1, 1};
  glGetProgramiv(id_, GL_COMPUTE_WORK_GROUP_SIZE, size);
  work_group_size_ = {size[0], size[1]};
  return true;
#endif
}

void shader_program::dispatch_over_grid(int n) const {
#if !defined(CLOTHLAB_GL_WEB)
  const auto groups = [n](int size) { return static_cast<GLuint>((n + size - 1) / size); };
  glDispatchCompute(groups(work_group_size_.x), groups(work_group_size_.y), 1);
#else
  (void)n;
#endif
}

bool shader_program::link(std::initializer_list<GLuint> shaders, const std::string& files,
                          std::string& error) {
  GLuint program = glCreateProgram();
  for (GLuint shader : shaders)
    glAttachShader(program, shader);
  glLinkProgram(program);
  for (GLuint shader : shaders)
    glDeleteShader(shader);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 1 ? length : 1), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    error = files + colon() + tr("do not link:") + "\n" + log.c_str();
    glDeleteProgram(program);
    return false;
  }
  *this = shader_program();
  id_ = program;
  return true;
}

}  // namespace clothlab
