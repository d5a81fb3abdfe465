// This build's lab runner, the default of CLOTHLAB_LAB_RUNNER. Only this small file is told the
// path, so that the checkers' other files compile alike in every checkout (ccache shares them).
namespace clothlab::lab {

extern const char* const default_runner_path;
const char* const default_runner_path = CLOTHLAB_LAB_RUNNER_PATH;

}  // namespace clothlab::lab
