// The additions of docs/model.md ("Interaction and contacts"): the mouse drag, the sphere,
// self-collision and tearing, each rule against a hand computation, then invariants over runs.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "core/contacts.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {
namespace {

void expect_near(const glm::dvec3& got, const glm::dvec3& expected, double tolerance,
                 const char* what) {
  EXPECT_LE(glm::length(got - expected), tolerance)
      << what << ": expected (" << expected.x << ", " << expected.y << ", " << expected.z
      << "), got (" << got.x << ", " << got.y << ", " << got.z << ")";
}

// Sphere c = 0, r = 1, mu_s = 2, dt = 0.1 (factor 0.8).
//  0: at (0, 0.3, 0.4), |p| = 0.5 inside, n = (0, 0.6, 0.8): p -> (0, 0.6, 0.8);
//     v = (1, 0, -1), v.n = -0.8: v -> (1, 0.48, -0.36), whose v.n = 0, all tangential: *0.8
//     -> (0.8, 0.384, -0.288).
//  1: at (0, 0, 0.5) moving out, v = (0, 0, 1): p -> (0, 0, 1), v kept (no tangential part).
//  2: at the centre: n = (0, 0, 1), p -> (0, 0, 1).
//  3: outside: untouched.  4: fixed, inside: untouched.
TEST(SphereContact, ContactRuleMatchesTheHandComputation) {
  particle_system particles;
  particles.resize(5);
  particles.set_position(0, {0, 0.3, 0.4});
  particles.set_velocity(0, {1, 0, -1});
  particles.set_position(1, {0, 0, 0.5});
  particles.set_velocity(1, {0, 0, 1});
  particles.set_position(2, {0, 0, 0});
  particles.set_position(3, {2, 0, 0});
  particles.set_velocity(3, {-1, 0, 0});
  particles.set_position(4, {0.1, 0, 0});
  particles.is_fixed[4] = 1;
  apply_sphere_contact({.enabled = true, .centre = {0, 0, 0}, .radius = 1.0, .friction = 2.0}, 0.1,
                       particles);
  expect_near(particles.get_position(0), {0, 0.6, 0.8}, 1e-15, "pushed out along n");
  expect_near(particles.get_velocity(0), {0.8, 0.384, -0.288}, 1e-15,
              "inward normal velocity removed, tangential damped");
  expect_near(particles.get_position(1), {0, 0, 1}, 1e-15, "pushed out");
  expect_near(particles.get_velocity(1), {0, 0, 1}, 1e-15, "outward velocity kept");
  expect_near(particles.get_position(2), {0, 0, 1}, 1e-15, "at the centre: n = (0, 0, 1)");
  expect_near(particles.get_position(3), {2, 0, 0}, 0.0, "outside: untouched");
  expect_near(particles.get_velocity(3), {-1, 0, 0}, 0.0, "outside: untouched");
  expect_near(particles.get_position(4), {0.1, 0, 0}, 0.0, "fixed: untouched");
}

spring_mesh flat_cloth(int n, double side = 1.0) {
  cloth_parameters p;
  p.grid_size = n;
  p.side_length = side;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  return spring_mesh(p);
}

// The drag spring of rest length 0: F_d = K_d (q - p). The flat 3 x 3 cloth of side 2 at rest
// (no spring force): s(1, 1) = (0, 0, 0) pulled towards q = (0.5, -1, 2) with K_d = 40 feels
// (20, -40, 80); nothing else does.
TEST(Drag, DragForceIsKdTimesTargetMinusPosition) {
  spring_mesh cloth = flat_cloth(3, 2.0);
  cloth.parameters.drag = {
      .enabled = true, .ku = 1, .kv = 1, .target = {0.5, -1, 2}, .stiffness = 40};
  // The drag alone: what add_drag_force adds to compute_force's forces (springs at rest, and
  // m g where an answer to question 8 adds gravity, as the handout's section 4.1 does).
  cloth.compute_force();
  const glm::dvec3 before_4 = cloth.particles().get_force(4);
  const glm::dvec3 before_0 = cloth.particles().get_force(0);
  cloth.add_drag_force();
  expect_near(cloth.particles().get_force(4) - before_4, {20, -40, 80}, 1e-12, "F_d on s(1, 1)");
  expect_near(cloth.particles().get_force(0) - before_0, {0, 0, 0}, 0.0, "no drag on s(0, 0)");
}

TEST(Drag, APinnedParticleCannotBeDragged) {
  spring_mesh cloth = flat_cloth(3, 2.0);
  cloth.particles().is_fixed[0] = 1;
  cloth.parameters.drag = {.enabled = true, .ku = 0, .kv = 0, .target = {5, 5, 5}, .stiffness = 40};
  cloth.compute_force();
  const glm::dvec3 before = cloth.particles().get_force(0);
  cloth.add_drag_force();
  expect_near(cloth.particles().get_force(0) - before, {0, 0, 0}, 0.0, "a pinned particle");
}

// A dragged free corner follows its target: after 6 s the corner of a 5 x 5 cloth without
// gravity, damped, comes to rest on q: nothing else pulls the cloth, which follows it.
TEST(SolutionDrag, ADraggedCornerFollowsTheTarget) {
  cloth_parameters p;
  p.grid_size = 5;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.dynamics.gravity = 0.0;
  p.dynamics.damping = 2.0;
  p.drag = {.enabled = true, .ku = 4, .kv = 4, .target = {0.7, 0.6, 0.3}, .stiffness = 20000};
  spring_mesh cloth(p);
  for (int s = 0; s < 3000; ++s)  // 6 s: the damping leaves exp(-12) of any motion
    cloth.step();
  expect_near(cloth.particles().get_position(24), p.drag.target, 1e-3, "the dragged corner");
}

// Tearing, strain 0.1 on a 3 x 3 cloth of side 2 (h = 1): the structural spring s(0,0)-s(1,0)
// stretched to 1.099 stays; to 1.101 it tears, and so do the triangles that used it.
// spring_intact answers for every (ku, kv, du, dv): false past the border of the grid (no
// spring there) and for an offset that is no neighbour, never a throw; true inside the grid
// while nothing tore.
TEST(Tearing, SpringIntactIsFalseOutsideTheGridAndNeverThrows) {
  spring_mesh cloth = flat_cloth(3, 2.0);
  EXPECT_TRUE(cloth.spring_intact(0, 0, 1, 0));
  EXPECT_TRUE(cloth.spring_intact(2, 2, -2, 0));
  EXPECT_TRUE(cloth.spring_intact(1, 1, -1, -1));
  EXPECT_FALSE(cloth.spring_intact(2, 0, 1, 0)) << "s(3, 0) is past the border of the 3 x 3 grid";
  EXPECT_FALSE(cloth.spring_intact(0, 0, -1, 0)) << "s(-1, 0)";
  EXPECT_FALSE(cloth.spring_intact(0, 2, 0, 1)) << "s(0, 3)";
  EXPECT_FALSE(cloth.spring_intact(0, 0, 0, -2)) << "s(0, -2)";
  EXPECT_FALSE(cloth.spring_intact(5, 5, 0, 1)) << "s(5, 5) is not in the grid";
  EXPECT_FALSE(cloth.spring_intact(0, 0, 3, 0)) << "three vertices away: no spring";
}

TEST(Tearing, ASpringTearsJustOverTheStrainAndNotUnder) {
  for (const double length : {1.099, 1.101}) {
    spring_mesh cloth = flat_cloth(3, 2.0);
    cloth.particles().set_position(0, {-length, -1, 0});  // s(1, 0) is at (0, -1, 0)
    const std::size_t torn = cloth.tear_springs(0.1);
    const bool should_tear = length > 1.1;
    EXPECT_EQ(torn, should_tear ? 1u : 0u) << "length " << length;
    EXPECT_EQ(cloth.springs(spring_family::structural).size(), should_tear ? 11u : 12u);
    EXPECT_EQ(cloth.triangle_intact(0, 0, false), !should_tear) << "length " << length;
    EXPECT_TRUE(cloth.triangle_intact(0, 0, true)) << "the upper triangle keeps its springs";
  }
}

// A torn spring exerts no force and stays torn when the cloth comes back together. Strain 0.2,
// 3 x 3 cloth of side 2 (h = 1): s(0, 0) moved to (-1.3, -1, 0) stretches only its spring to
// s(1, 0) past 1.2 (to s(0, 1): 1.044; shear to s(1, 1): 1.640 < 1.697; bending: 2.3, 2.022 <
// 2.4). Back at rest, with s(1, 0) pushed to (-0.5, -1, 0), s(0, 0) feels nothing: its other
// springs are at rest and the one that would push it is gone.
TEST(SolutionTearing, TornSpringsNeverComeBack) {
  spring_mesh cloth = flat_cloth(3, 2.0);
  cloth.particles().set_position(0, {-1.3, -1, 0});
  EXPECT_EQ(cloth.tear_springs(0.2), 1u);
  cloth.particles().set_position(0, {-1, -1, 0});  // back at rest
  EXPECT_EQ(cloth.tear_springs(0.2), 0u);
  EXPECT_EQ(cloth.springs(spring_family::structural).size(), 11u);
  cloth.particles().set_position(1, {-0.5, -1, 0});
  cloth.parameters.dynamics.gravity = 0.0;  // the springs alone, wherever an answer adds m g
  cloth.compute_force();
  expect_near(cloth.particles().get_force(0), {0, 0, 0}, 1e-9,
              "s(0, 0) without its torn spring to s(1, 0)");
  EXPECT_GT(glm::length(cloth.particles().get_force(1)), 1000.0)
      << "s(1, 0) still feels its intact springs";
}

// Self-collision, d = 0.05, on a 6 x 6 cloth: s(0, 0) and s(5, 5) (far apart in the grid) put
// L = 0.01 apart along x: c = (d - L)/2 = 0.02, u = (1, 0, 0); approaching at w = -2:
// p_i += 0.02 u, p_j -= 0.02 u; v_i += 1 u, v_j -= 1 u.
TEST(SelfCollision, ACloseNonNeighbourPairIsPushedApartByHalfTheOverlapEach) {
  spring_mesh cloth = flat_cloth(6);
  particle_system& particles = cloth.particles();
  particles.set_position(0, {3.01, 3, 3});
  particles.set_position(35, {3.00, 3, 3});
  particles.set_velocity(0, {-1, 0, 0});
  particles.set_velocity(35, {1, 0, 0});
  self_collision pass;
  EXPECT_EQ(pass.apply(6, 0.05, particles), 1u);
  expect_near(particles.get_position(0), {3.03, 3, 3}, 1e-12, "p_i += c u");
  expect_near(particles.get_position(35), {2.98, 3, 3}, 1e-12, "p_j -= c u");
  expect_near(particles.get_velocity(0), {0, 0, 0}, 1e-12, "v_i -= (w/2) u");
  expect_near(particles.get_velocity(35), {0, 0, 0}, 1e-12, "v_j += (w/2) u");
}

TEST(SelfCollision, APinnedParticleLeavesBothHalvesToTheOther) {
  spring_mesh cloth = flat_cloth(6);
  particle_system& particles = cloth.particles();
  particles.set_position(0, {3.01, 3, 3});
  particles.set_position(35, {3.00, 3, 3});
  particles.is_fixed[35] = 1;
  self_collision pass;
  pass.apply(6, 0.05, particles);
  expect_near(particles.get_position(0), {3.05, 3, 3}, 1e-12, "p_i += 2 c u");
  expect_near(particles.get_position(35), {3.00, 3, 3}, 0.0, "the pinned one stays");
}

TEST(SelfCollision, GridNeighboursWithinTwoStepsAreLeftToTheirSprings) {
  spring_mesh cloth = flat_cloth(6);
  particle_system& particles = cloth.particles();
  particles.set_position(0, {3.01, 3, 3});
  particles.set_position(14, {3.00, 3, 3});  // s(2, 2): |du| = |dv| = 2
  self_collision pass;
  EXPECT_EQ(pass.apply(6, 0.05, particles), 0u);
  expect_near(particles.get_position(0), {3.01, 3, 3}, 0.0, "untouched");
}

// The spatial hash finds exactly the pairs that a check of every pair finds: a crumpled 12 x 12
// cloth (random positions in a 0.3 m box), d = 0.04.
TEST(SelfCollision, TheSpatialHashFindsEveryCloseNonNeighbourPair) {
  spring_mesh cloth = flat_cloth(12);
  particle_system& particles = cloth.particles();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> in_box(-0.15, 0.15);
  for (std::size_t k = 0; k < particles.size(); ++k)
    particles.set_position(k, {in_box(random), in_box(random), in_box(random)});
  std::size_t expected = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    for (std::size_t j = i + 1; j < particles.size(); ++j) {
      const double L = glm::length(particles.get_position(i) - particles.get_position(j));
      const bool neighbours =
          std::abs(int(i % 12) - int(j % 12)) <= 2 && std::abs(int(i / 12) - int(j / 12)) <= 2;
      expected += L > 0 && L < 0.04 && !neighbours;
    }
  }
  ASSERT_GT(expected, 10u);
  self_collision pass;
  EXPECT_EQ(pass.apply(12, 0.04, particles), expected);
}

// Issue 22: the distance is clamped to the shortest rest length h = side / (N - 1), so that one
// cell of the hash holds a bounded crowd (D = 0.436 at N = 200 took 38 s a step). A thickness
// past h steps the cloth exactly as h does.
TEST(SelfCollision, TheDistanceIsClampedToTheShortestRestLength) {
  cloth_parameters p;
  p.grid_size = 10;
  p.side_length = 0.9;
  p.self_collision_thickness = 1000.0;
  EXPECT_EQ(self_collision_distance(p), 0.1);
  p.self_collision_thickness = 0.05;
  EXPECT_EQ(self_collision_distance(p), 0.05);

  p.pins = pin_mode::none;
  p.wind_strength = 3.0;
  p.self_collision_thickness = 1000.0;
  spring_mesh asked(p);
  p.self_collision_thickness = 0.1;
  spring_mesh clamped(p);
  for (int s = 0; s < 50; ++s) {
    asked.step();
    clamped.step();
  }
  EXPECT_EQ(asked.particles().position, clamped.particles().position);
  EXPECT_EQ(asked.particles().velocity, clamped.particles().velocity);
}

}  // namespace
}  // namespace clothlab

namespace clothlab {
namespace {

// The drape: the default 20 x 20 cloth dropped without pins onto the sphere c =
// (0, 0, -0.6), r = 0.3, for 3000 steps (6 s). No particle ever ends a step inside the sphere,
// and the cloth comes to rest draped over it: the middle of the cloth on top of the sphere.
TEST(SolutionSphereContact, AClothDroppedOnTheSphereDrapesOverItAndNeverEntersIt) {
  cloth_parameters p;
  p.pins = pin_mode::none;
  p.sphere = {.enabled = true, .centre = {0, 0, -0.6}, .radius = 0.3};  // default friction
  spring_mesh cloth(p);
  double closest = 1e9;
  for (int s = 0; s < 3000; ++s) {
    cloth.step();
    for (std::size_t k = 0; k < cloth.particles().size(); ++k)
      closest = std::min(closest, glm::length(cloth.particles().get_position(k) - p.sphere.centre));
  }
  EXPECT_GE(closest, 0.3 - 1e-12) << "a particle ended a step inside the sphere";
  // The middle of the cloth: the four particles around the centre of the 20 x 20 grid.
  glm::dvec3 middle(0.0);
  double mean_speed = 0.0;
  for (int kv = 9; kv <= 10; ++kv)
    for (int ku = 9; ku <= 10; ++ku)
      middle += cloth.particles().get_position(spring_mesh::index(ku, kv, 20)) / 4.0;
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    mean_speed += glm::length(cloth.particles().get_velocity(k)) / 400.0;
  std::cout << "  middle of the cloth " << middle.x << " " << middle.y << " " << middle.z
            << ", mean speed " << mean_speed << " m/s\n";
  EXPECT_NEAR(middle.x, 0.0, 0.02);
  EXPECT_NEAR(middle.y, 0.0, 0.02);
  EXPECT_NEAR(middle.z, -0.3, 0.03) << "the middle of the cloth rests on top of the sphere";
  // It hit the sphere at sqrt(2 g0 0.3) = 2.4 m/s; its corners still sway a little.
  EXPECT_LT(mean_speed, 0.1) << "the cloth has (nearly) come to rest";
}

}  // namespace
}  // namespace clothlab
