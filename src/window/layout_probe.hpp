// What the window tests (tests/window) read of the window: its log (what the mouse did, the
// presets, the frames measured), and the panel's layout, printed only when the environment sets
// CLOTHLAB_PRINT_LAYOUT=1: where the dt slider is whenever it or the run's state changes (no
// status message may move a slider), and where each named widget is (the tests click it there,
// by the English name given here, whatever the panel's language). Without the variable no layout
// is printed and nothing is measured.
#pragma once

#include "window/scene.hpp"

namespace clothlab {

// One line of the window's log on standard output, "clothlab-window: ..." (docs/window.md). In
// English whatever the panel's language, like the numbers it carries: programs read it. What the
// user is told goes through tr() instead.
[[gnu::format(printf, 1, 2)]] void window_log(const char* format, ...);

// The last ImGui item is the dt slider of the stage shown: its top is remembered for log_layout.
void note_time_step_slider();

// Prints where the dt slider is, with the stage, the run's state (`state`, one word or a few),
// the time mode and the cloth's path, when that line differs from the last one printed.
void log_layout(const scene& the_scene, const char* state);

// Prints where the last ImGui item, called `name`, is in window pixels from the top-left corner,
// and whether it is whole in the panel's visible part, when that changes.
void log_widget(const char* name);

}  // namespace clothlab
