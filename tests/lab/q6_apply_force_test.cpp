// Question 6: spring_mesh::apply_force, the handout's explicit Euler in its code order (the
// pseudo-code of section 4.3): for every vertex k that is not fixed,
//   speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + g),   then   vertices[k] += dt speed[k].
// (Equation 6 taken literally, --integrator explicit, is clothlab's, built on this one:
// tests/core.) The forces are those of compute_force on the cloth at rest (no spring force:
// question 8 is not needed) plus forces set by hand, so that gravity may be added where the
// handout puts it (m g in compute_force) or as g in apply_force: the tests check the motion, not
// where the work is done. The ground is off. Tolerances: float_rounding of the values of a step
// (lab_check.hpp), per step for a run.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::spring_mesh;

// Stiffnesses 0 and no wind: compute_force gives no spring force, whatever question 8's answer.
cloth_parameters without_springs() {
  cloth_parameters p;
  p.structural_stiffness = 0.0;
  p.shear_stiffness = 0.0;
  p.bending_stiffness = 0.0;
  p.wind_strength = 0.0;
  return p;
}

// A 2 x 2 cloth without pins or ground: dt = 0.1 s, mu = 0.5 /s, m = 2 kg, g0 = 10 m/s^2.
spring_mesh small_cloth() {
  cloth_parameters p = without_springs();
  p.grid_size = 2;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.dynamics = {.time_step = 0.1, .damping = 0.5, .mass = 2.0, .gravity = 10.0};
  spring_mesh cloth(p);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    cloth.particles().is_fixed[k] = 0;  // whatever question 7 does
  return cloth;
}

// The values of one step of small_cloth are of size 10 at most (speeds, forces, positions).
constexpr double step_tolerance = 10 * lab::float_rounding;

// The forces of compute_force at the current positions (at rest: gravity's m g, if an answer
// puts it there, and nothing else), to which set_force adds forces by hand before apply_force.
void compute_rest_forces(spring_mesh& cloth) {
  cloth.compute_force();
}
void set_force(spring_mesh& cloth, std::size_t k, const glm::dvec3& f) {
  for (int c = 0; c < 3; ++c)
    cloth.particles().force[3 * k + c] += f[c];
}

// Vertex 3 moves at v = (1, 2, 3) under F = (4, -2, 6):
//   v' = (1 - 0.1 * 0.5) (1, 2, 3) + 0.1 ((2, -1, 3) + (0, 0, -10))
//      = (0.95, 1.9, 2.85) + (0.2, -0.1, -0.7) = (1.15, 1.8, 2.15).
TEST(Q6ApplyForce, VelocityIsDampedThenAcceleratedByForceOverMassPlusGravity) {
  spring_mesh cloth = small_cloth();
  compute_rest_forces(cloth);
  cloth.particles().set_velocity(3, {1, 2, 3});
  set_force(cloth, 3, {4, -2, 6});
  cloth.apply_force();
  LAB_EXPECT_VEC(cloth.particles().get_velocity(3), glm::dvec3(1.15, 1.8, 2.15), step_tolerance,
                 tr("Q6: speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + g) with dt = 0.1, "
                    "mu = 0.5, m = 2, g = (0, 0, -10), speed (1, 2, 3) and force (4, -2, 6). "
                    "Are the forces and the damping used?"));
}

// Then vertices[k] += dt speed[k] with the NEW speed: p' = (0.5, 0.5, 0) + 0.1 (1.15, 1.8, 2.15).
// When the position did move with the speed just computed but that speed is wrong (the test
// above says how), the message says so rather than blame the order.
TEST(Q6ApplyForce, PositionMovesWithTheNewVelocity) {
  spring_mesh cloth = small_cloth();
  compute_rest_forces(cloth);
  const glm::dvec3 p = cloth.particles().get_position(3);
  cloth.particles().set_velocity(3, {1, 2, 3});
  set_force(cloth, 3, {4, -2, 6});
  cloth.apply_force();
  const glm::dvec3 speed = cloth.particles().get_velocity(3);
  const glm::dvec3 expected_speed(1.15, 1.8, 2.15);
  const bool order_right =
      lab::near(cloth.particles().get_position(3), p + 0.1 * speed, step_tolerance);
  LAB_EXPECT_VEC(cloth.particles().get_position(3), p + 0.1 * expected_speed, step_tolerance,
                 order_right && !lab::near(speed, expected_speed, step_tolerance)
                     ? format(tr("Q6: the vertex moved by dt speed[k] with the speed just "
                                 "computed, as it should, but that speed is wrong (%s instead of "
                                 "%s): see speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + "
                                 "g)"),
                              lab::text(speed).c_str(), lab::text(expected_speed).c_str())
                     : std::string(tr("Q6: vertices[k] += dt speed[k], with the speed just "
                                      "computed (the handout's second loop)")));
}

// Every vertex, not only the first: each gets its own force, F_k = (k, -k, 2k), from rest:
//   v_k = 0.1 ((k, -k, 2k) / 2 + (0, 0, -10)),  p_k += 0.1 v_k.
TEST(Q6ApplyForce, EveryVertexMovesUnderItsOwnForce) {
  spring_mesh cloth = small_cloth();
  compute_rest_forces(cloth);
  std::vector<glm::dvec3> start;
  for (std::size_t k = 0; k < 4; ++k) {
    const double s = double(k);
    set_force(cloth, k, {s, -s, 2 * s});
    start.push_back(cloth.particles().get_position(k));
  }
  cloth.apply_force();
  for (std::size_t k = 0; k < 4; ++k) {
    const double s = double(k);
    const glm::dvec3 v = 0.1 * (glm::dvec3(s, -s, 2 * s) / 2.0 + glm::dvec3(0, 0, -10));
    LAB_EXPECT_VEC(cloth.particles().get_velocity(k), v, step_tolerance,
                   format(tr("Q6: vertex %zu should be accelerated by its own force forces[k] / "
                             "m plus gravity"),
                          std::size_t(k)));
    LAB_EXPECT_VEC(cloth.particles().get_position(k), start[k] + 0.1 * v, step_tolerance,
                   format(tr("Q6: vertex %zu should move by dt speed[k]"), std::size_t(k)));
  }
}

// A fixed vertex is never updated: it keeps its position and its zero velocity, whatever force.
TEST(Q6ApplyForce, FixedVerticesAreNeverUpdated) {
  spring_mesh cloth = small_cloth();
  compute_rest_forces(cloth);
  cloth.particles().is_fixed[1] = 1;
  const glm::dvec3 p = cloth.particles().get_position(1);
  set_force(cloth, 1, {100, 100, 100});
  cloth.apply_force();
  LAB_EXPECT_VEC(cloth.particles().get_position(1), p, 0.0,
                 tr("Q6: a fixed vertex (is_fixed[k] == 1) must never move"));
  LAB_EXPECT_VEC(cloth.particles().get_velocity(1), glm::dvec3(0.0), 0.0,
                 tr("Q6: a fixed vertex keeps a zero speed"));
}

// Without pins, springs at rest length and no ground, every vertex gets the same velocity and the
// cloth falls as one particle: v_s = (1 - mu dt) v_(s-1) - g0 dt, z_s = z_(s-1) + dt v_s.
TEST(Q6ApplyForce, AFreeClothFallsWithTheDampedFreeFallOfOneParticle) {
  cloth_parameters p = without_springs();
  p.grid_size = 5;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.dynamics.damping = 0.5;
  p.dynamics.time_step = 0.002;
  spring_mesh cloth(p);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    cloth.particles().is_fixed[k] = 0;
  double v = 0.0, z = 0.0;
  for (int s = 0; s < 100; ++s) {
    compute_rest_forces(cloth);
    cloth.apply_force();
    v = (1 - 0.5 * 0.002) * v - 9.8 * 0.002;
    z = z + 0.002 * v;
  }
  // Every vertex falls alike: one message, for the first vertex that does not. Tolerance: the
  // rounding of 100 steps of values of size 2 (v_z reaches -1.9 m/s).
  const double tolerance = 100 * lab::rounding(2.0);
  std::size_t wrong = 0, first = 0;
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    const double v_k = cloth.particles().velocity[3 * k + 2];
    const double z_k = cloth.particles().position[3 * k + 2];
    if (!(lab::near(v_k, v, tolerance) && lab::near(z_k, z, tolerance)) && wrong++ == 0)
      first = k;
  }
  const double v_first = cloth.particles().velocity[3 * first + 2];
  const double z_first = cloth.particles().position[3 * first + 2];
  LAB_EXPECT_TRUE(wrong == 0,
                  tr("Q6: a free cloth (no pins, no spring force, no ground) falls as one "
                     "particle: after 100 steps of dt = 0.002 s with damping mu = 0.5, every "
                     "vertex should move at v_z = (1 - dt mu) v_z - g0 dt and z = z + dt v_z"))
      << format(tr("; vertex %zu (%zu of %zu vertices are wrong):"), std::size_t(first),
                std::size_t(wrong), std::size_t(cloth.particles().size()))
      << (lab::near(v_first, v, tolerance) ? ""
                                           : "\n    v_z:" + lab::difference(v_first, v, tolerance))
      << (lab::near(z_first, z, tolerance) ? ""
                                           : "\n    z:" + lab::difference(z_first, z, tolerance));
}

}  // namespace
}  // namespace clothlab
