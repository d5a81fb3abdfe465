// The view that takes in the whole chain of stage 2 (key V, and at a reset or a change of n):
// from its fixed top p0 down to the floor drawn under it, below the lowest swing of a stable
// chain (chain_floor_height). No GL here: tested without a window.
#pragma once

#include "camera.hpp"
#include "coupled_springs.hpp"

namespace clothlab {

camera chain_view(const coupled_springs& chain);

}  // namespace clothlab
