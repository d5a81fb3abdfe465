// How far a correct single-precision run of the cloth (either GPU path, on any GPU) can stray
// from the double-precision CPU run of the same cloth: the tolerances of the GPU tests, from
// float's rounding, the size of the coordinates, the number of steps and how the integrator
// carries a difference from one step to the next.
//
// Every step, a float path rounds each coordinate it stores and computes: at most u |x| for a
// coordinate x, u = 2^-24 (round to nearest, 24-bit significand), so at most u P for
// coordinates below P metres. A difference made at one step is multiplied by the integrator's
// growth per step G at every later step, so after n steps the positions differ by at most
//   u P (1 + G + G^2 + ... + G^(n-1)),
// and the velocities by omega times that, a difference of positions in a mode of angular
// frequency omega coming with omega times it in velocities (the stiffest modes, omega below).
//   - Semi-implicit Euler turns every mode of the cloth without growing it (its amplification
//     has modulus 1 while omega dt < 2, times the damping's 1 - mu dt): G = 1, the bound is n u P.
//     Measured: a 1e-9 m nudge is still 1.0e-9 m apart after 300 steps.
//   - Explicit Euler multiplies a mode by sqrt(1 + (omega dt)^2) per step (handout question 4):
//     G = 1.044 for the stiffest modes at dt = 0.002 s, 74 times over 100 steps.
// These are bounds, the errors of every step adding up with the same sign; measured on llvmpipe
// and in a float emulation of the CPU cloth with other roundings (other_roundings_test.cpp), the
// differences stay 3 to 60 times below them. They hold where no decision of the run (a contact,
// a tear) sits within a rounding of its threshold: the cases are chosen, and checked, so.
#pragma once

#include <cmath>

#include "core/parameters.hpp"

namespace clothlab::single_precision {

// u: a float holds x to within u |x|.
inline constexpr double unit_roundoff = 0x1p-24;  // 6.0e-8

// omega of the test cloth's stiffest modes (N = 12, K_struct = 5000 N/m, K_shear = 2000 N/m,
// m = 1 kg): about 150 rad/s, measured as explicit Euler's growth of a small difference,
// 72 times over 100 steps at dt = 0.002 s = sqrt(1 + (omega dt)^2)^100; below the bound
// sqrt(4 (K_struct + K_shear) / m) = 167 rad/s of a particle whose neighbours all move against it.
inline constexpr double stiffest_mode = 150.0;  // rad/s

struct bounds {
  double position;  // m
  double velocity;  // m/s
};

// The growth of a difference per step, G above.
inline double growth_per_step(integrator_kind integrator, double time_step) {
  if (integrator == integrator_kind::explicit_euler)
    return std::sqrt(1.0 + std::pow(stiffest_mode * time_step, 2));
  return 1.0;
}

// The bounds after `steps` steps of `integrator` (time step dt, s) on coordinates below
// `largest_coordinate` (m).
inline bounds after(int steps, double largest_coordinate, integrator_kind integrator,
                    double time_step) {
  const double growth = growth_per_step(integrator, time_step);
  double carried = 0.0;  // 1 + G + ... + G^(steps - 1)
  for (int s = 0; s < steps; ++s)
    carried = carried * growth + 1.0;
  const double position = unit_roundoff * largest_coordinate * carried;
  return {position, stiffest_mode * position};
}

}  // namespace clothlab::single_precision
