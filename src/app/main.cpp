// clothlab: the command line of docs/cli.md. With --headless it runs here, in an off-screen
// OpenGL context when one is needed (--png, --backend gpu or gpu-compute). Without it, it hands
// over to the interactive window, clothlab-window, built beside it from the same sources with
// GLFW and GLEW (one process cannot hold both the GLX and the OSMesa OpenGL libraries: see
// README). The same way, --gl chooses between this program (OSMesa) and clothlab-egl (EGL),
// built from the same sources: --gl auto takes EGL only where a hardware GPU is there.
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "gl_context.hpp"
#include "headless.hpp"
#include "options.hpp"

namespace {

// The stop signals' handlers are the first thing installed, before the shared libraries'
// initialisers (LLVM's, through OSMesa, take milliseconds) and before main: a signal in the
// first milliseconds is reported like any other (docs/limits.md), not fatal. Only the dynamic
// loader's own start, about a millisecond, comes before it.
void install_first(int, char**, char**) {
  clothlab::install_stop_handlers();
}
[[gnu::section(".preinit_array"),
  gnu::used]] void (*const install_first_entry)(int, char**, char**) = install_first;

// Replaces this process by the program `name` beside it, with the same arguments (and `extra`).
// The stop signals are held back across the exec (a signal then waits for the new program's
// handlers), except for the window, which handles them its own way: they get their default
// action back.
int hand_over(const char* name, int argc, char** argv, const char* extra = nullptr) {
  const bool window = std::string_view(name) == "clothlab-window";
  if (window) {
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction before {};
      sigaction(signal_number, nullptr, &before);
      if (before.sa_handler != SIG_IGN)
        std::signal(signal_number, SIG_DFL);
    }
  } else {
    clothlab::block_stop_signals(true);
  }
  // A signal that came before is reported here (after the change above, none can be lost).
  if (const int status = clothlab::interrupted_before_the_run(); status != 0)
    return status;
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const auto program = (ec ? std::filesystem::path(".") : self.parent_path()) / name;
  std::vector<char*> args(argv, argv + argc);
  std::string extra_arguments = extra ? extra : "";
  if (extra != nullptr) {
    args.push_back(extra_arguments.data());
  }
  args.push_back(nullptr);
  ::execv(program.c_str(), args.data());
  if (!window)
    clothlab::block_stop_signals(false);
  std::fprintf(stderr, "clothlab: cannot start %s: %s\n", program.c_str(), std::strerror(errno));
  return 1;
}

#if !defined(CLOTHLAB_EGL_PROGRAM)
// A GPU's device node: Linux's DRM render nodes, or NVIDIA's. Without one, EGL has only Mesa's
// software renderer to offer, which OSMesa is too.
bool gpu_device_node_present() {
  std::error_code ec;
  if (std::filesystem::exists("/dev/nvidia0", ec))
    return true;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/dri", ec)) {
    if (entry.path().filename().string().rfind("renderD", 0) == 0)
      return true;
  }
  return false;
}
#endif

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
    if (o.gl == gl_choice::egl || (o.gl == gl_choice::automatic && gpu_device_node_present()))
      return hand_over("clothlab-egl", argc, argv);
#endif
  }
  return clothlab::run_headless(o);
}
