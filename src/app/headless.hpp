// The headless run of cli.md: run the chosen stage for --steps steps, write the CSV as it goes,
// then the OBJ and the PNG. Returns the exit status (0, 1, 3, or 128 + a stop signal; usage
// errors are caught before, but for a sweep past its bounds: 2).
#pragma once

#include "options.hpp"

namespace clothlab {

int run_headless(const options& o);

// SIGINT, SIGTERM and SIGHUP (docs/limits.md): installs their handler (a signal ignored on entry,
// as under nohup, stays ignored) and unblocks them. main.cpp calls it before anything else, so
// that a signal from the first millisecond on is reported, not fatal.
void install_stop_handlers();
// Holds the three signals back (block) or lets them through: across an exec (main.cpp's
// hand-over to another program) a signal then waits for the new program's handler.
void block_stop_signals(bool block);
// When a stop signal came before the run started: says so and returns 128 + its number; else 0.
int interrupted_before_the_run();
// True when the run needs an off-screen OpenGL context (a GPU path or --png).
bool needs_opengl(const options& o);

}  // namespace clothlab
