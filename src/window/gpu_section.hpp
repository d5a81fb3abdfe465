// The panel's section of questions 11 and 12: which path runs the cloth and the switch between
// them, every path's measured speed, the OpenGL renderer, and the GPU's state textures as images.
#pragma once

#include "window/panel.hpp"
#include "window/scene.hpp"

namespace clothlab {

void show_gpu_path(scene& the_scene, user_actions& actions);

}  // namespace clothlab
