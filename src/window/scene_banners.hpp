// The banners the panel lays over the scene (right of the panel): what happened to the stage
// shown and what to do, when there is nothing to see there.
#pragma once

#include "window/scene.hpp"

namespace clothlab {

// Over the empty scene of a diverged stage. panel_covered_width: the width the panel covers at
// the window's left, in ImGui's (screen) units.
void show_divergence_banner(const run_status& status, float panel_covered_width);
// Over the scene of a stage that fell below the view.
void show_out_of_view_banner(stage_kind stage, float panel_covered_width);

}  // namespace clothlab
