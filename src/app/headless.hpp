// The headless run of cli.md: run the chosen stage for --steps steps, write the CSV as it goes,
// then the OBJ and the PNG; or, with --sweep, the stability map (sweep_command.hpp). Returns the
// exit status (0, 1, 3, or 128 + a stop signal; usage errors are caught before, but for a sweep
// past its bounds: 2).
#pragma once

#include "app/options.hpp"

namespace clothlab {

int run_headless(const options& o);

// True when the run needs an off-screen OpenGL context (a GPU path or --png).
bool needs_opengl(const options& o);

}  // namespace clothlab
