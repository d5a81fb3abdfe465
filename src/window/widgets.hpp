// The control panel's generic Dear ImGui widgets: text held to a fixed number of lines, sliders
// that clamp what is typed, the collapsible sections, and the colours of the messages. Nothing
// here knows the lab; the panel's views (panel.cpp, stage_editors, analysis_views, gpu_section,
// scene_banners) are made of these.
#pragma once

#include <imgui.h>

#include <string>

#include "core/i18n.hpp"  // tr, format

namespace clothlab {

inline const ImVec4 warning_red = {1.0f, 0.35f, 0.3f, 1.0f};
inline const ImVec4 caution_yellow = {1.0f, 0.85f, 0.3f, 1.0f};
inline const ImVec4 quiet_green = {0.5f, 0.9f, 0.5f, 1.0f};

// The size of the panel's things relative to the default font: 1, or the screen's scale.
float ui_scale();

// Text broken into lines at spaces only (a number is never cut), in exactly `lines` lines of the
// panel, so that nothing below moves when the text changes length or appears. What does not fit
// ends in "..." and the whole text shows in a tooltip under the mouse.
enum class text_style { plain, disabled, coloured };
// width: of the lines, 0 for the panel's width.
void fixed_lines(const std::string& text, int lines, text_style style = text_style::plain,
                 const ImVec4& colour = {}, float width = 0.0f);

// A widget's label in the user's language, with the English text as its Dear ImGui id:
// "Réinitialiser (R)###Reset (R)". The widget keeps its id, and so its state (a section open, a
// slider being typed into), whatever the language. Valid until the language changes.
const char* ui_label(const char* english);

// Every slider clamps what is typed after Ctrl+click too, so that no value outside its range
// (a zero time step, a grid of 1) can reach the simulation.
bool slider(const char* label, double& value, double min, double max, const char* format,
            bool logarithmic = false);
bool slider(const char* label, int& value, int min, int max);

// A collapsible section of the panel, open at start.
bool section(const char* title);

}  // namespace clothlab
