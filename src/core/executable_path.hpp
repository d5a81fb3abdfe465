// Where the running program's file is: clothlab finds its shaders and assets, and the programs
// it hands a run over to, beside it.
#pragma once

#include <filesystem>

namespace clothlab {

// The running program's file, with links resolved; empty where the system does not say
// (then the callers fall back on the folder fixed at build time, or the current one).
std::filesystem::path executable_path();

}  // namespace clothlab
