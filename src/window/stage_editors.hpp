// The panel's editors: the stage shown, the run's control (time mode, steps), every parameter of
// docs/model.md for each stage in sections named after the handout's questions, the presets of
// the cloth (drape, rip) and the display toggles. Parameters are edited in place in the scene;
// what needs the main loop (a reset, a new stage) comes back in `actions`.
#pragma once

#include "window/panel.hpp"
#include "window/scene.hpp"

namespace clothlab {

void edit_stage(scene& the_scene, user_actions& actions);
void edit_simulation_control(simulation_control& control, user_actions& actions);
// The sections of each stage, with its analysis views and (cloth) the GPU section among them.
void edit_single_spring(scene& the_scene, user_actions& actions);
void edit_coupled_springs(coupled_springs& stage, user_actions& actions);
void edit_cloth(scene& the_scene, user_actions& actions);
void edit_display(render_settings& display, user_actions& actions);

}  // namespace clothlab
