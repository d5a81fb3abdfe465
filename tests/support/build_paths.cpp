#include "build_paths.hpp"

namespace clothlab_test {

const char* const executable_path = CLOTHLAB_EXECUTABLE;
const char* const render_reference_directory = CLOTHLAB_RENDER_REFERENCE_DIR;

}  // namespace clothlab_test
