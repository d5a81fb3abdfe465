// clothlab: the command line of docs/cli.md. With --headless it runs here, in an off-screen
// OpenGL context when one is needed (--png, --backend gpu or gpu-compute). Without it, it hands
// over to the interactive window, clothlab-window, built beside it from the same sources with
// GLFW and GLEW (one process cannot hold both the GLX and the OSMesa OpenGL libraries: see
// docs/architecture.md). The same way, --gl chooses between this program (OSMesa) and clothlab-egl
// (EGL), built from the same sources where both are found: --gl auto takes EGL only where a
// hardware GPU is there. A build with only one of them (or neither: a hidden window) runs every
// headless job here.
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "app/command_line.hpp"
#include "app/headless.hpp"
#include "app/run_control.hpp"
#include "core/i18n.hpp"
#include "gl/gl_context.hpp"
#include "gl/program_choice.hpp"

namespace {

// The stop signals' handlers are the first thing installed, before the shared libraries'
// initialisers (LLVM's, through OSMesa, take milliseconds) and before main: a signal in the
// first milliseconds is reported like any other (docs/limits.md), not fatal. Only the dynamic
// loader's own start, about a millisecond, comes before it.
// (ELF's pre-initialisers; elsewhere, macOS's Mach-O, a constructor, run before main too.)
#if defined(__ELF__)
void install_first(int, char**, char**) {
  clothlab::install_stop_handlers();
}
[[gnu::section(".preinit_array"),
  gnu::used]] void (*const install_first_entry)(int, char**, char**) = install_first;
#else
[[gnu::constructor]] void install_first() {
  clothlab::install_stop_handlers();
}
#endif

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
  std::vector<std::string> arguments(argv, argv + argc);
  if (extra != nullptr)
    arguments.emplace_back(extra);
  const int failed = clothlab::hand_over_to("clothlab", name, arguments);
  if (!window)
    clothlab::block_stop_signals(false);
  return failed;
}

// The off-screen context of a build that has only one kind (or none: a hidden window): a --gl
// that asks for a missing one is refused, with what this build has (exit status 1, as for any
// context that cannot be made).
[[maybe_unused]] int refuse_missing_context(clothlab::gl_choice choice) {
  using clothlab::gl_choice;
#if defined(CLOTHLAB_GL_OSMESA)
  const bool missing = choice == gl_choice::egl;
  const char* has = clothlab::tr("only OSMesa (CMake found no EGL, or CLOTHLAB_WITH_EGL=OFF)");
#elif defined(CLOTHLAB_GL_EGL)
  const bool missing = choice == gl_choice::osmesa;
  const char* has = clothlab::tr("only EGL (CMake found no OSMesa, or CLOTHLAB_WITH_OSMESA=OFF)");
#else
  const bool missing = choice != gl_choice::automatic;
  const char* has =
      clothlab::tr("neither OSMesa nor EGL: its off-screen runs use a hidden GLFW window");
#endif
  if (!missing)
    return 0;
  std::fprintf(stderr, clothlab::tr("clothlab: --gl %s: this build has %s; use --gl auto\n"),
               choice == gl_choice::egl ? "egl" : "osmesa", has);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  clothlab::start_messages();  // the user's language, before the first word (--lang may change it)
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
#elif defined(CLOTHLAB_EGL_BESIDE)
    if (o.gl == gl_choice::egl ||
        (o.gl == gl_choice::automatic && clothlab::gpu_device_node_present()))
      return hand_over("clothlab-egl", argc, argv);
#else
    if (const int status = refuse_missing_context(o.gl); status != 0)
      return status;
#endif
  }
  // Anything thrown past the run (the steps' own errors are reported by the run, naming the
  // function): exit 1 and one line, never std::terminate's abort.
  try {
    return clothlab::run_headless(o);
  } catch (const std::exception& error) {
    clothlab::report("%s", clothlab::one_line(error.what()).c_str());
  } catch (...) {
    clothlab::report("%s", clothlab::tr("stopped by an exception that is not a std::exception"));
  }
  return clothlab::exit_failure;
}
