// The headless run of cli.md: run the chosen stage for --steps steps, write the CSV as it goes,
// then the OBJ and the PNG. Returns the exit status (0, 1 or 3; usage errors are caught before).
#pragma once

#include "options.hpp"

namespace clothlab {

int run_headless(const options& o);
// True when the run needs an off-screen OpenGL context (a GPU path or --png).
bool needs_opengl(const options& o);

}  // namespace clothlab
