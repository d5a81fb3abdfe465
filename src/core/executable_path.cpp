#include "core/executable_path.hpp"

#if defined(__APPLE__)
#include <mach-o/dyld.h>

#include <cstdint>
#include <vector>
#endif

namespace clothlab {

std::filesystem::path executable_path() {
  std::error_code ec;
#if defined(__linux__)
  // Linux names it in /proc (what the kernel started, whatever argv[0] says).
  auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
#elif defined(__APPLE__)
  // macOS gives the path it was started by (possibly through a link): asked twice, for the size.
  std::uint32_t size = 0;
  _NSGetExecutablePath(nullptr, &size);
  std::vector<char> buffer(size + 1, '\0');
  if (_NSGetExecutablePath(buffer.data(), &size) != 0)
    return {};
  auto path = std::filesystem::canonical(buffer.data(), ec);
#else
  // Elsewhere (the browser build: the data is at a fixed place) nothing says.
  std::filesystem::path path;
#endif
  return ec ? std::filesystem::path() : path;
}

}  // namespace clothlab
