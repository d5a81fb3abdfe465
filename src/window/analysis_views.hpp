// The panel's views of what the run does, each for a question of the lab: the stability map and
// the energy plot (question 4), the single spring's motion against the exact solution (question
// 2), the anatomy of the last frame (questions 1 and 3).
#pragma once

#include "window/panel.hpp"
#include "window/scene.hpp"

namespace clothlab {

// Question 4: the map of stable and diverged runs over dt x K around the current values.
void show_stability_map(scene& the_scene);
// Question 4: the kinetic, gravity, spring and total energy over the last frames.
void show_energy(const scene& the_scene);
// Question 2: the spring's extension, simulated and exact, and their difference; the 1D start's
// checkbox (which resets the stage through `actions`).
void show_spring_motion(scene& the_scene, user_actions& actions);
// Questions 1 and 3: what ran in the last frame and how long each phase took.
void show_frame_anatomy(const scene& the_scene);

}  // namespace clothlab
