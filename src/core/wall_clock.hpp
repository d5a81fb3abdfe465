// Wall-clock time, for what clothlab measures of itself (rates, the frame anatomy, question 12's
// timings), never for the physics.
#pragma once

#include <chrono>

namespace clothlab {

using wall_clock = std::chrono::steady_clock;

// Seconds of wall-clock time since `start`.
inline double seconds_since(wall_clock::time_point start) {
  return std::chrono::duration<double>(wall_clock::now() - start).count();
}

}  // namespace clothlab
