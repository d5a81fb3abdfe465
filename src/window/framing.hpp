// What the camera takes in, with no GL (tested without a window): the view of the whole chain,
// and whether a stage has fallen out of the view.
#pragma once

#include <span>

#include "core/coupled_springs.hpp"
#include "gl/camera.hpp"

namespace clothlab {

// The view that takes in the whole chain of stage 2 (key V, and at a reset or a change of n):
// from its fixed top p0 down to the floor drawn under it, below the lowest swing of a stable
// chain (chain_floor_height).
camera chain_view(const coupled_springs& chain);

// True when every point (xyz, 3 doubles each) is below the bottom edge of the view of aspect
// width / height: a stage that fell out of sight (a cloth that nothing holds up: no pins,
// springs nor ground, as in the student's copy before questions 6 to 9). False with no point,
// and for a point behind the eye or off to a side (the user turned the camera away).
bool fell_below_view(const camera& view, float aspect, std::span<const double> positions);

}  // namespace clothlab
