// clothlab: the command line of shared/cli.md. With --headless it runs here, in an off-screen
// OpenGL context when one is needed (--png, --backend gpu). Without it, it hands over to the
// interactive window, clothlab-window, built beside it from the same sources with GLFW and GLEW
// (one process cannot hold both the GLX and the OSMesa OpenGL libraries: see README).
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "headless.hpp"
#include "options.hpp"

namespace {

int open_window(int argc, char** argv) {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const auto window = (ec ? std::filesystem::path(".") : self.parent_path()) / "clothlab-window";
  std::vector<char*> args(argv, argv + argc);
  args.push_back(nullptr);
  ::execv(window.c_str(), args.data());
  std::fprintf(stderr, "clothlab: cannot start the window program %s: %s\n", window.c_str(),
               std::strerror(errno));
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  const clothlab::parse_result result = clothlab::parse_command_line(argc, argv);
  if (!result.parsed)
    return result.exit_code;
  if (!result.parsed->headless)
    return open_window(argc, argv);
  return clothlab::run_headless(*result.parsed);
}
