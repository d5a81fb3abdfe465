#include "gl/program_choice.hpp"

#include "core/executable_path.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/i18n.hpp"

namespace clothlab {

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

int hand_over_to(const char* who, const char* name, const std::vector<std::string>& arguments) {
  const auto self = executable_path();
  const auto program = (self.empty() ? std::filesystem::path(".") : self.parent_path()) / name;
  std::vector<std::string> copies = arguments;
  std::vector<char*> args;
  for (std::string& argument : copies)
    args.push_back(argument.data());
  args.push_back(nullptr);
  ::execv(program.c_str(), args.data());
  std::fprintf(stderr, "%s%s%s\n", who, colon(),
               format(tr("cannot start %s: %s"), program.c_str(), std::strerror(errno)).c_str());
  return 1;
}

}  // namespace clothlab
