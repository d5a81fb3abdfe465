// Line plots with axes for the control panel, drawn with Dear ImGui's draw lists: a frame, ticks
// at round values (1, 2 or 5 times a power of ten) with their numbers on both axes, and one
// polyline per series. Display only: the data belongs to the scene.
#pragma once

#include <imgui.h>

#include <span>
#include <string>
#include <vector>

#include "window/ticks.hpp"  // nice_ticks, tick_labels

namespace clothlab {

struct plot_series {
  std::span<const float> x;  // as many as y, increasing
  std::span<const float> y;
  ImU32 colour = IM_COL32(230, 230, 230, 255);
  const char* name = "";  // in the tooltip
};

struct plot_style {
  float height = 80.0f;      // of the whole plot, numbers included, in ImGui units
  const char* x_unit = "";   // after the x numbers' line, e.g. "t (s)"
  const char* y_unit = "";   // after the values in the tooltip, e.g. "J" (the title says it too)
  bool x_numbers = true;     // false: ticks only (plots stacked over a shared time axis)
  bool y_from_zero = false;  // the y range includes 0
  float min_label_width = 0.0f;  // of the y numbers' column: plots stacked over one x axis align
  std::string title;             // in the top-right corner of the frame, e.g. "total 4.99 J"
};

// Draws the series in a box as wide as the panel and style.height high; the axes span the data
// (x: the union of the series' x; y: their y). A tooltip gives the values under the mouse.
void line_plot(const char* id, std::span<const plot_series> series, const plot_style& style);

}  // namespace clothlab
