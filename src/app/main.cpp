// clothlab: the command line of docs/cli.md. With --headless it runs here, in an off-screen
// OpenGL context when one is needed (--png, --backend gpu or gpu-compute). Without it, it hands
// over to the interactive window, clothlab-window, built beside it from the same sources with
// GLFW and GLEW (one process cannot hold both the GLX and the OSMesa OpenGL libraries: see
// README). The same way, --gl chooses between this program (OSMesa) and clothlab-egl (EGL),
// built from the same sources: --gl auto takes EGL only where a hardware GPU is there.
#include <string>
#include <vector>

#include "gl_context.hpp"
#include "headless.hpp"
#include "options.hpp"
#include "program_choice.hpp"

namespace {

// Replaces this process by the program `name` beside it, with the same arguments (and `extra`).
int hand_over(const char* name, int argc, char** argv, const char* extra = nullptr) {
  std::vector<std::string> arguments(argv, argv + argc);
  if (extra != nullptr)
    arguments.emplace_back(extra);
  return clothlab::hand_over_to("clothlab", name, arguments);
}

}  // namespace

int main(int argc, char** argv) {
  const clothlab::parse_result result = clothlab::parse_command_line(argc, argv);
  if (!result.parsed)
    return result.exit_code;
  const clothlab::options& o = *result.parsed;
  if (!o.headless)
    return hand_over("clothlab-window", argc, argv);
  if (clothlab::needs_opengl(o)) {
    using clothlab::gl_choice;
#if defined(CLOTHLAB_EGL_PROGRAM)
    if (o.gl == gl_choice::osmesa)
      return hand_over("clothlab", argc, argv);
    if (o.gl == gl_choice::automatic && !clothlab::egl_hardware_device_available())
      return hand_over("clothlab", argc, argv, "--gl=osmesa");
#else
    if (o.gl == gl_choice::egl ||
        (o.gl == gl_choice::automatic && clothlab::gpu_device_node_present()))
      return hand_over("clothlab-egl", argc, argv);
#endif
  }
  return clothlab::run_headless(o);
}
