// Question 9: the plane z = z_g, on the CPU (apply_ground_contact) and on the GPU (ground_contact
// in shaders/gpu_cloth_common.glsl). After the integrator, a vertex below it is put back on it,
// stops falling, and slides with its tangential velocity damped by fluid friction,
// (v_x, v_y) *= (1 - mu_g dt).
#include <gtest/gtest.h>

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

// z_g = -1, mu_g = 2, dt = 0.01: factor 1 - mu_g dt = 0.98.
//  0: below and falling:       z -> -1, v = (2, -4, -3) -> (1.96, -3.92, 0)
//  1: above the ground:        untouched
//  2: below and rising:        z -> -1, v_z = 1 kept, (v_x, v_y) damped
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
  LAB_EXPECT_VEC(particles.get_position(0), glm::dvec3(0.1, 0.2, -1.0), 1e-15,
                 "Q9: a vertex below the plane z = -1 should be put back on it (z = -1), its x "
                 "and y unchanged");
  LAB_EXPECT_VEC(particles.get_velocity(0), glm::dvec3(1.96, -3.92, 0.0), 1e-15,
                 "Q9: a vertex that hits the ground stops falling (v_z = 0) and slides with "
                 "(v_x, v_y) damped by (1 - mu_g dt) = 0.98");
  LAB_EXPECT_VEC(particles.get_position(1), glm::dvec3(0, 0, -0.5), 0.0,
                 "Q9: a vertex above the ground is not touched");
  LAB_EXPECT_VEC(particles.get_velocity(1), glm::dvec3(1, 1, -1), 0.0,
                 "Q9: a vertex above the ground keeps its velocity");
  LAB_EXPECT_VEC(particles.get_velocity(2), glm::dvec3(0.98, 0.49, 1.0), 1e-15,
                 "Q9: a vertex below the ground that already moves up keeps v_z (v_z = max(v_z, "
                 "0)); its sliding is still damped");
  LAB_EXPECT_VEC(particles.get_position(3), glm::dvec3(0, 0, -2), 0.0,
                 "Q9: a fixed vertex is never moved, not even by the ground");
}

// A cloth falls onto a ground 0.3 m below it: it reaches it (a free fall of 0.3 m takes 0.25 s,
// 125 steps) and no vertex ever ends a step under it.
TEST(Q9Ground, AFallingClothNeverEndsAStepUnderTheGround) {
  cloth_parameters p;
  p.grid_size = 8;
  p.ground_height = -0.3;
  spring_mesh cloth(p);
  bool touched = false;
  for (int s = 0; s < 400; ++s) {
    cloth.step();
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const double z = cloth.particles().position[3 * k + 2];
      LAB_ASSERT_TRUE(z >= -0.3, "Q9: vertex " + std::to_string(k) +
                                     " is under the ground z = -0.3 at step " +
                                     std::to_string(s + 1))
          << " (z = " << z << ")";
      touched = touched || z == -0.3;
    }
  }
  LAB_EXPECT_TRUE(touched, "Q9: the cloth should have reached the ground");
}

using Q9GpuGround = lab::OffscreenGl;

// A 2 x 2 cloth without springs, gravity, damping or pins (its one step is the integrator's
// p + dt v, then the ground), z_g = -1, mu_g = 2, dt = 0.01, factor 0.98:
//  0: (0.1, 0.2, -1.5), v (2, -4, -3): moves to z = -1.53, below: z -> -1, v -> (1.96, -3.92, 0)
//  1: (0, 0, -0.5), v (1, 1, -1): moves to (0.01, 0.01, -0.51), above: untouched
//  2: (0, 0, -1.02), v (1, 0.5, 1): moves to z = -1.01, below but rising: z -> -1, v_z = 1 kept,
//     (v_x, v_y) -> (0.98, 0.49)
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
  const double tolerance = 1e-6;  // single precision
  LAB_EXPECT_VEC(particles.get_position(0), glm::dvec3(0.12, 0.16, -1.0), tolerance,
                 "Q9 (GPU): a particle that moves below the plane z = -1 should be put back on "
                 "it (z = -1), its x and y as the integrator left them");
  LAB_EXPECT_VEC(particles.get_velocity(0), glm::dvec3(1.96, -3.92, 0.0), tolerance,
                 "Q9 (GPU): a particle that hits the ground stops falling (v_z = 0) and slides "
                 "with (v_x, v_y) damped by (1 - mu_g dt) = 0.98");
  LAB_EXPECT_VEC(particles.get_position(1), glm::dvec3(0.01, 0.01, -0.51), tolerance,
                 "Q9 (GPU): a particle above the ground only moves by dt v");
  LAB_EXPECT_VEC(particles.get_velocity(1), glm::dvec3(1, 1, -1), tolerance,
                 "Q9 (GPU): a particle above the ground keeps its velocity (no friction)");
  LAB_EXPECT_VEC(particles.get_position(2), glm::dvec3(0.01, 0.005, -1.0), tolerance,
                 "Q9 (GPU): a particle below the ground that moves up is put back on it too");
  LAB_EXPECT_VEC(particles.get_velocity(2), glm::dvec3(0.98, 0.49, 1.0), tolerance,
                 "Q9 (GPU): a particle below the ground that already moves up keeps v_z "
                 "(v_z = max(v_z, 0)); its sliding is still damped");
  LAB_EXPECT_VEC(particles.get_position(3), glm::dvec3(0, 0, -2), 0.0,
                 "Q9 (GPU): a pinned particle is never moved, not even by the ground");
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
                 "Q9 (GPU): with the ground off (ground_enabled false) a particle goes through "
                 "the plane z = -1");
  LAB_EXPECT_VEC(cloth.particles().get_velocity(0), glm::dvec3(2, -4, -3), 1e-6,
                 "Q9 (GPU): with the ground off a particle keeps its velocity (no friction)");
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
  bool touched = false;
  for (int s = 0; s < 400; ++s) {
    gpu.step(p);
    if (s % 50 != 49)
      continue;
    gpu.read_state(cloth);
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const double z = cloth.particles().position[3 * k + 2];
      LAB_ASSERT_TRUE(z >= ground, "Q9 (GPU): particle " + std::to_string(k) +
                                       " is under the ground z = -0.3 after " +
                                       std::to_string(s + 1) + " steps")
          << " (z = " << z << ")";
      touched = touched || z == ground;
    }
  }
  LAB_EXPECT_TRUE(touched, "Q9 (GPU): the cloth should have reached the ground");
}

}  // namespace
}  // namespace clothlab
