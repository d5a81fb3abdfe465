// What the window tests (tests/window) read of the panel's layout, printed only when the
// environment sets CLOTHLAB_PRINT_LAYOUT=1: where the dt slider is whenever it or the run's state
// changes (no status message may move a slider), and where each named widget is (the tests click
// it there). Without the variable nothing is printed and nothing is measured.
#pragma once

#include "window/scene.hpp"

namespace clothlab {

// The last ImGui item is the dt slider of the stage shown: its top is remembered for log_layout.
void note_time_step_slider();

// Prints where the dt slider is, with the stage, the run's state (`state`, one word or a few),
// the time mode and the cloth's path, when that line differs from the last one printed.
void log_layout(const scene& the_scene, const char* state);

// Prints where the last ImGui item, called `name`, is in window pixels from the top-left corner,
// and whether it is whole in the panel's visible part, when that changes.
void log_widget(const char* name);

}  // namespace clothlab
