// The data files of a headless run, checked before it starts.
#pragma once

#include <string>

#include "app/options.hpp"

namespace clothlab {

// The data files (shaders, the cloth's texture) that the run will read, each checked before
// step 1 so that a missing one fails at once, before any output is opened (the files loaded by
// gpu_cloth.cpp, gpu_cloth_compute.cpp and renderer.cpp). False with a message naming the
// option that needs it.
bool data_files_present(const options& o, std::string& error);

}  // namespace clothlab
