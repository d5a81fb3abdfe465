// The runs that both GPU paths repeat after the CPU (gpu_cloth_test.cpp), and that the float
// emulation of the CPU cloth checks the tolerances on (other_roundings_test.cpp): each case a
// small cloth (N = 12) with one feature of the model, under both integrators, and the tolerance
// of its comparison (single_precision.hpp).
#pragma once

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/spring_mesh.hpp"
#include "float_emulation.hpp"
#include "single_precision.hpp"

namespace clothlab {

inline constexpr int agreement_grid_size = 12;
// Semi-implicit Euler is stable at dt = 0.002 s: 300 steps, 0.6 s of simulated time.
inline constexpr int semi_implicit_steps = 300;
// Explicit Euler is unstable for this stiff cloth (handout question 4): a difference between
// two runs grows 74 times in 100 steps, 5 000 times in 200, and by 300 steps the run itself
// has blown up. The comparison is meaningful for 100 steps, 0.2 s.
inline constexpr int explicit_steps = 100;

// The N = 12 cloth without ground; its corners pinned.
inline cloth_parameters agreement_cloth() {
  cloth_parameters p;
  p.grid_size = agreement_grid_size;
  p.ground_enabled = false;
  return p;
}

struct agreement_case {
  const char* name;
  cloth_parameters parameters;
  int steps = 0;
};

inline agreement_case with_integrator(agreement_case c, integrator_kind integrator) {
  c.parameters.dynamics.integrator = integrator;
  c.steps = integrator == integrator_kind::explicit_euler ? explicit_steps : semi_implicit_steps;
  return c;
}

// The sphere of the case "Sphere": a free cloth falls 0.19 m onto the top of a sphere of radius
// 2 m (two times the cloth's side) and lies on it. A contact is decided per particle (|p - c| <
// r after the integrator), and a decision that a rounding could flip makes the two paths part
// (a particle in contact on one, not on the other, its inward velocity removed on one only), so
// the case is chosen where every decision is far from the surface:
//   - semi-implicit: the cloth lands on the sphere from step 99, the middle first, and lies on
//     it to the end (step 300), every particle pressed in by gravity, about dt^2 g cos(theta) =
//     3.7e-5 m per step (theta <= 20 degrees), with no rim where the cloth would leave it (the
//     sphere is wider than the cloth). Nearest decision to the surface: 3.1e-5 m (step 204),
//     three times the comparison's position tolerance.
//   - explicit: a particle on the sphere moves along it with its old velocity, whose inward part
//     the contact removed: it ends the next step outside by dt^2 v_t^2 / (2 r) only, which is
//     below the rounding when it slides slowly, so explicit Euler's resting contact sits on the
//     decision's boundary at every other step, and a flip leaves one path with the inward
//     velocity dt a_n that the other removed (0.1 m/s and more for a cloth pulled onto the
//     sphere: other_roundings_test.cpp). The explicit run ends at the step where the cloth first
//     touches the sphere: the four middle particles, 1.3e-3 m inside it or more; every other
//     decision (all steps) is 1.3e-3 m from the surface or more.
// The centre and radius are floats exactly (the GPU's uniforms): z = -(2 + 190/1024) m.
inline constexpr glm::dvec3 sphere_centre = {0.0, 0.0, -2.185546875};  // m
inline constexpr double sphere_radius = 2.0;                           // m

// The agreement cases: pins without wind, wind, ground contact, the drag, the sphere; each with
// both integrators.
inline std::vector<agreement_case> agreement_cases() {
  cloth_parameters pinned = agreement_cloth();  // the two corners pinned, no wind, no ground

  cloth_parameters wind = agreement_cloth();
  wind.wind_strength = 4.0;
  wind.wind_direction = {1.0, 2.0, 3.0};  // not unit: both paths normalise it

  // Hanging from its corners, the free edge swings down onto a ground close below. Its decisions
  // (z < z_g) are safe though some lie near the plane: a particle put on the plane is at z_g
  // exactly, with v_z = 0 exactly, on every path. Explicit Euler then leaves it at z_g exactly
  // (z_g + dt 0), an exact "not below"; every other explicit decision is 1.7e-5 m from the
  // plane or more. Semi-implicit moves it by dt^2 a_z, which is near zero where the cloth lifts
  // off (7e-7 m at the nearest): there a flip only removes the v_z = d / dt that took the
  // particle d below the plane, under 1e-3 m/s for d below the paths' 2e-6 m, and the friction's
  // 0.4 % of a slow sliding.
  cloth_parameters ground = agreement_cloth();
  ground.ground_enabled = true;
  ground.ground_height = -0.1;
  ground.wind_strength = 2.0;
  ground.wind_direction = {0.0, 1.0, 0.0};

  // The mouse drag (an addition): a free cloth falls while a corner is pulled up and away.
  cloth_parameters drag = agreement_cloth();
  drag.pins = pin_mode::none;
  drag.drag = {.enabled = true, .ku = 11, .kv = 11, .target = {0.6, 0.6, 0.2}, .stiffness = 1000.0};

  // The sphere (an addition), above.
  cloth_parameters sphere = agreement_cloth();
  sphere.pins = pin_mode::none;
  sphere.sphere = {.enabled = true, .centre = sphere_centre, .radius = sphere_radius};

  std::vector<agreement_case> cases;
  for (integrator_kind integrator :
       {integrator_kind::semi_implicit, integrator_kind::explicit_euler}) {
    cases.push_back(with_integrator({"PinsNoWind", pinned}, integrator));
    cases.push_back(with_integrator({"Wind", wind}, integrator));
    cases.push_back(with_integrator({"Ground", ground}, integrator));
    cases.push_back(with_integrator({"Drag", drag}, integrator));
    cases.push_back(with_integrator({"Sphere", sphere}, integrator));
  }
  return cases;
}

// The largest |coordinate| (m) of the cloth's particles, or so_far if larger: P of
// single_precision.hpp, taken over a run.
inline double largest_coordinate(const spring_mesh& cloth, double so_far = 0.0) {
  for (double x : cloth.particles().position)
    so_far = std::max(so_far, std::abs(x));
  return so_far;
}

// The bounds of single_precision.hpp for a case's run whose coordinates stayed below
// largest_coordinate (m): what the cloth of the handout's figure, hanging from the corners s(0, 0)
// and s(N-1, 0) and stretched by its pins, can drift by in float.
inline single_precision::bounds bound_of(const agreement_case& c, double largest) {
  return single_precision::after(c.steps, largest, c.parameters.dynamics.integrator,
                                 c.parameters.dynamics.time_step);
}

// The seeds of the float runs that a tolerance takes its spread from (other_roundings_test.cpp
// checks the tolerances on others).
inline constexpr std::uint32_t tolerance_seeds_from = 1000;
inline constexpr int tolerance_seeds = 4;

// The tolerance of a case's comparison: bound_of, or twice how far float runs of four other
// roundings drift from this cloth in double (float_emulation.hpp), if that is larger. The
// bounds assume a cloth that carries a difference without growing it (semi-implicit Euler's
// G = 1); the cloth that the student's questions build can carry it further: pinned at the
// opposite corners s(0, 0) and s(N-1, N-1) (question 7 allows any two), it folds across the
// diagonal, and float runs drift 40 times further from it than from the handout's cloth
// (PinsNoWind, semi-implicit: 1.3e-4 m against 3.1e-6 m). The tolerance follows the cloth the
// student built, however its corners are chosen; for the handout's cloth it is the bound.
inline single_precision::bounds tolerance_of(const agreement_case& c, double largest) {
  const single_precision::bounds bound = bound_of(c, largest);
  const float_spread spread =
      spread_of_float_runs(c.parameters, c.steps, tolerance_seeds_from, tolerance_seeds);
  return {std::max(bound.position, 2.0 * spread.position),
          std::max(bound.velocity, 2.0 * spread.velocity)};
}

// The particles of the cloth on the surface of its sphere, within 1e-9 m (put there by a contact).
inline int particles_on_sphere(const spring_mesh& cloth) {
  const sphere_parameters& sphere = cloth.parameters.sphere;
  int count = 0;
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    count += std::abs(glm::length(cloth.particles().get_position(k) - sphere.centre) -
                      sphere.radius) < 1e-9;
  }
  return count;
}

}  // namespace clothlab
