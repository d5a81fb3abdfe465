// Question 9: the plane z = z_g, on the CPU (apply_ground_contact) and on the GPU (ground_contact
// in shaders/gpu_cloth_common.glsl). After the integrator, a vertex below it is put back on it
// and slides with its tangential velocity damped by fluid friction. The handout leaves the rest
// of the velocity rule to the student, and the tests accept every rule that keeps a contact
// vertex on the plane without pushing it into the ground or throwing it off:
//  - a vertex that falls onto the plane stops falling: v_z = 0 (neither < 0, into the ground,
//    nor > 0, a bounce);
//  - a vertex below the plane that already moves up may keep v_z (v_z = max(v_z, 0)) or stop
//    (v_z = 0);
//  - the fluid friction of rate mu_g multiplies (v_x, v_y) over one step by exp(-mu_g dt) or by
//    its first order, 1 - mu_g dt, or by anything between them and their O((mu_g dt)^2)
//    neighbours (1 / (1 + mu_g dt), ...): the tests allow (mu_g dt)^2 around 1 - mu_g dt.
// Other tolerances: float_rounding of the values (lab_check.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gl_fixture.hpp"
#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::apply_ground_contact;
using student::gpu_cloth;
using student::particle_system;
using student::spring_mesh;

// z_g = -1, mu_g = 2, dt = 0.01: first-order factor 1 - mu_g dt = 0.98, exact exp(-0.02) =
// 0.980199; the friction may be either, within (mu_g dt)^2 = 4e-4.
constexpr double mu_g_dt = 2.0 * 0.01;
constexpr double friction_factor = 1 - mu_g_dt;
constexpr double friction_tolerance = mu_g_dt * mu_g_dt;

// The checks of a vertex that ended a step below the plane and was put back on it: `before` is
// its velocity before the contact, `after` the one the answer left.
void expect_contact_velocity(const glm::dvec3& before, const glm::dvec3& after, double rounding,
                             const std::string& where) {
  const glm::dvec3 tangential(before.x, before.y, 0.0);
  const glm::dvec3 slid(after.x, after.y, 0.0);
  LAB_EXPECT_VEC(
      slid, friction_factor * tangential, friction_tolerance * glm::length(tangential) + rounding,
      format(tr("Q9%s: a vertex in contact with the ground slides with a fluid friction of rate "
                "mu_g = 2 (like the damping of equation 3, along the plane): over dt = 0.01 s its "
                "(v_x, v_y) = %s shrinks by exp(-mu_g dt) = 0.9802, or by the first order 1 - "
                "mu_g dt = 0.98"),
             where.c_str(), lab::text(tangential).c_str()));
  if (before.z < 0) {
    LAB_EXPECT_TRUE(lab::near(after.z, 0.0, rounding),
                    after.z < 0
                        ? format(tr("Q9%s: a vertex that falls onto the ground (v_z = %s) stops "
                                    "falling: its v_z must become 0, not stay negative: it would "
                                    "go on into the ground"),
                                 where.c_str(), lab::number(before.z).c_str())
                        : format(tr("Q9%s: a vertex that falls onto the ground (v_z = %s) stops "
                                    "falling: its v_z must become 0, not positive: the plane "
                                    "holds it, it does not throw it off (no bounce)"),
                                 where.c_str(), lab::number(before.z).c_str()))
        << lab::difference(after.z, 0.0, rounding);
  } else {
    LAB_EXPECT_TRUE(lab::near(after.z, before.z, rounding) || lab::near(after.z, 0.0, rounding),
                    after.z < 0
                        ? format(tr("Q9%s: a vertex below the ground that already moves up "
                                    "(v_z = %s) may keep its v_z or stop (v_z = 0), but not be "
                                    "sent down into the ground"),
                                 where.c_str(), lab::number(before.z).c_str())
                        : format(tr("Q9%s: a vertex below the ground that already moves up "
                                    "(v_z = %s) may keep its v_z or stop (v_z = 0), but the "
                                    "friction slows its sliding only"),
                                 where.c_str(), lab::number(before.z).c_str()))
        << format(tr("; got v_z = %s"), lab::number(after.z, 17).c_str());
  }
}

// z_g = -1, mu_g = 2, dt = 0.01:
//  0: below and falling:       z -> -1, v = (2, -4, -3) -> ((2, -4) damped, 0)
//  1: above the ground:        untouched
//  2: below and rising:        z -> -1, v_z = 1 kept (or 0), (v_x, v_y) damped
//  3: fixed, below the ground: untouched
TEST(Q9Ground, ContactRuleMatchesTheHandComputation) {
  particle_system particles;
  particles.resize(4);
  particles.set_position(0, {0.1, 0.2, -1.5});
  particles.set_velocity(0, {2, -4, -3});
  particles.set_position(1, {0, 0, -0.5});
  particles.set_velocity(1, {1, 1, -1});
  particles.set_position(2, {0, 0, -1.01});
  particles.set_velocity(2, {1, 0.5, 1});
  particles.set_position(3, {0, 0, -2});
  particles.is_fixed[3] = 1;
  apply_ground_contact(-1.0, 2.0, 0.01, particles);
  const double rounding = lab::rounding(5.0);  // values of size 5 at most
  LAB_EXPECT_VEC(particles.get_position(0), glm::dvec3(0.1, 0.2, -1.0), rounding,
                 tr("Q9: a vertex below the plane z = -1 should be put back on it (z = -1), its "
                    "x and y unchanged"));
  expect_contact_velocity({2, -4, -3}, particles.get_velocity(0), rounding, "");
  LAB_EXPECT_VEC(particles.get_position(1), glm::dvec3(0, 0, -0.5), 0.0,
                 tr("Q9: a vertex above the ground is not touched"));
  LAB_EXPECT_VEC(particles.get_velocity(1), glm::dvec3(1, 1, -1), 0.0,
                 tr("Q9: a vertex above the ground keeps its velocity (no friction without "
                    "contact)"));
  LAB_EXPECT_VEC(particles.get_position(2), glm::dvec3(0, 0, -1.0), rounding,
                 tr("Q9: a vertex below the plane that already moves up is put back on it too: "
                    "no vertex may stay below it"));
  expect_contact_velocity({1, 0.5, 1}, particles.get_velocity(2), rounding, "");
  LAB_EXPECT_VEC(particles.get_position(3), glm::dvec3(0, 0, -2), 0.0,
                 tr("Q9: a fixed vertex is never moved, not even by the ground"));
}

// A cloth falls onto a ground 0.3 m below it: it reaches it (a free fall of 0.3 m takes 0.25 s,
// 125 steps) and no vertex ever ends a step under it (within the rounding of z_g in float).
TEST(Q9Ground, AFallingClothNeverEndsAStepUnderTheGround) {
  cloth_parameters p;
  p.grid_size = 8;
  p.ground_height = -0.3;
  spring_mesh cloth(p);
  const double rounding = lab::rounding(0.3);
  bool touched = false;
  for (int s = 0; s < 400; ++s) {
    cloth.step();
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const double z = cloth.particles().position[3 * k + 2];
      LAB_ASSERT_TRUE(
          z >= -0.3 - rounding,
          format(tr("Q9: vertex %zu is under the ground z = -0.3 at step %d"), k, s + 1))
          << " (z = " << lab::number(z, 17) << ")";
      touched = touched || lab::near(z, -0.3, rounding);
    }
  }
  LAB_EXPECT_TRUE(touched, tr("Q9: the cloth should have reached the ground"));
}

using Q9GpuGround = lab::OffscreenGl;

// A 2 x 2 cloth without springs, gravity, damping or pins (its one step is the integrator's
// p + dt v, then the ground), z_g = -1, mu_g = 2, dt = 0.01, factor 0.98:
//  0: (0.1, 0.2, -1.5), v (2, -4, -3): moves to z = -1.53, below: z -> -1, v_z -> 0, (v_x, v_y)
//     damped
//  1: (0, 0, -0.5), v (1, 1, -1): moves to (0.01, 0.01, -0.51), above: untouched
//  2: (0, 0, -1.02), v (1, 0.5, 1): moves to z = -1.01, below but rising: z -> -1, v_z = 1 kept
//     (or 0), (v_x, v_y) damped
//  3: pinned at (0, 0, -2): never moves
TEST_F(Q9GpuGround, TheGpuContactRuleMatchesTheHandComputation) {
  cloth_parameters p;
  p.grid_size = 2;
  p.structural_stiffness = p.shear_stiffness = p.bending_stiffness = 0.0;
  p.pins = pin_mode::none;
  p.ground_enabled = true;
  p.ground_height = -1.0;
  p.ground_friction = 2.0;
  p.dynamics = {.time_step = 0.01, .damping = 0.0, .mass = 1.0, .gravity = 0.0};
  spring_mesh cloth(p);
  particle_system& particles = cloth.particles();
  particles.set_position(0, {0.1, 0.2, -1.5});
  particles.set_velocity(0, {2, -4, -3});
  particles.set_position(1, {0, 0, -0.5});
  particles.set_velocity(1, {1, 1, -1});
  particles.set_position(2, {0, 0, -1.02});
  particles.set_velocity(2, {1, 0.5, 1});
  particles.set_position(3, {0, 0, -2});
  particles.is_fixed[3] = 1;
  gpu_cloth gpu;
  std::string error;
  const bool loaded = gpu.load(cloth, error);
  LAB_ASSERT_TRUE(loaded, error);
  gpu.step(p);
  gpu.read_state(cloth);
  const double tolerance = lab::rounding(5.0);  // single precision, values of size 5 at most
  LAB_EXPECT_VEC(particles.get_position(0), glm::dvec3(0.12, 0.16, -1.0), tolerance,
                 tr("Q9 (GPU): a particle that moves below the plane z = -1 should be put back "
                    "on it (z = -1), its x and y as the integrator left them"));
  expect_contact_velocity({2, -4, -3}, particles.get_velocity(0), tolerance, " (GPU)");
  LAB_EXPECT_VEC(particles.get_position(1), glm::dvec3(0.01, 0.01, -0.51), tolerance,
                 tr("Q9 (GPU): a particle above the ground only moves by dt v"));
  LAB_EXPECT_VEC(particles.get_velocity(1), glm::dvec3(1, 1, -1), tolerance,
                 tr("Q9 (GPU): a particle above the ground keeps its velocity (no friction)"));
  LAB_EXPECT_VEC(particles.get_position(2), glm::dvec3(0.01, 0.005, -1.0), tolerance,
                 tr("Q9 (GPU): a particle below the ground that moves up is put back on it too"));
  expect_contact_velocity({1, 0.5, 1}, particles.get_velocity(2), tolerance, " (GPU)");
  LAB_EXPECT_VEC(particles.get_position(3), glm::dvec3(0, 0, -2), 0.0,
                 tr("Q9 (GPU): a pinned particle is never moved, not even by the ground"));
}

// With the ground off (ground_enabled false), a GPU particle goes through the plane: the 2 x 2
// cloth of the test above, particle 0 only, one step: (0.1, 0.2, -1.5) + 0.01 (2, -4, -3).
TEST_F(Q9GpuGround, NoGroundWhenItIsOff) {
  cloth_parameters p;
  p.grid_size = 2;
  p.structural_stiffness = p.shear_stiffness = p.bending_stiffness = 0.0;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.ground_height = -1.0;
  p.ground_friction = 2.0;
  p.dynamics = {.time_step = 0.01, .damping = 0.0, .mass = 1.0, .gravity = 0.0};
  spring_mesh cloth(p);
  cloth.particles().set_position(0, {0.1, 0.2, -1.5});
  cloth.particles().set_velocity(0, {2, -4, -3});
  gpu_cloth gpu;
  std::string error;
  const bool loaded = gpu.load(cloth, error);
  LAB_ASSERT_TRUE(loaded, error);
  gpu.step(p);
  gpu.read_state(cloth);
  LAB_EXPECT_VEC(cloth.particles().get_position(0), glm::dvec3(0.12, 0.16, -1.53), 1e-6,
                 tr("Q9 (GPU): with the ground off (ground_enabled false) a particle goes "
                    "through the plane z = -1"));
  LAB_EXPECT_VEC(cloth.particles().get_velocity(0), glm::dvec3(2, -4, -3), 1e-6,
                 tr("Q9 (GPU): with the ground off a particle keeps its velocity (no "
                    "friction)"));
}

// The GPU cloth falls onto a ground 0.3 m below it: it reaches it and no particle is ever seen
// under it (read back every 50 steps).
TEST_F(Q9GpuGround, AFallingGpuClothNeverEndsAStepUnderTheGround) {
  cloth_parameters p;
  p.grid_size = 8;
  p.ground_height = -0.3;
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  const bool loaded = gpu.load(cloth, error);
  LAB_ASSERT_TRUE(loaded, error);
  const double ground = static_cast<float>(p.ground_height);  // z_g as the GPU holds it
  const double rounding = lab::rounding(0.3);
  bool touched = false;
  for (int s = 0; s < 400; ++s) {
    gpu.step(p);
    if (s % 50 != 49)
      continue;
    gpu.read_state(cloth);
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const double z = cloth.particles().position[3 * k + 2];
      LAB_ASSERT_TRUE(z >= ground - rounding,
                      format(tr("Q9 (GPU): particle %zu is under the ground z = -0.3 after %d "
                                "steps"),
                             std::size_t(k), s + 1))
          << " (z = " << lab::number(z, 17) << ")";
      touched = touched || lab::near(z, ground, rounding);
    }
  }
  LAB_EXPECT_TRUE(touched, tr("Q9 (GPU): the cloth should have reached the ground"));
}

}  // namespace
}  // namespace clothlab
