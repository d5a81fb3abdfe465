// --sweep: the stability map of question 4 from the command line (cli.md): the cells of
// sweep.hpp run on worker threads, their CSV written whole, the map printed.
#pragma once

#include "app/options.hpp"

namespace clothlab {

// The exit status: 0, 1 (a file), 2 (a sweep past its bounds), or 128 + a stop signal.
int run_sweep_map(const options& o);

}  // namespace clothlab
