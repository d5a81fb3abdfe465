// Stage 3, the cloth (model.md): grid layout, the three spring families, Newton's third law,
// rest, pins, ground contact, normals and wind, each against a hand computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <set>
#include <utility>

#include "spring_mesh.hpp"

namespace clothlab {
namespace {

struct grid_offset {
  int du;
  int dv;
};

// (ku, kv) of particle k = ku + N kv.
grid_offset grid_coordinates(std::uint32_t k, int n) {
  return {static_cast<int>(k) % n, static_cast<int>(k) / n};
}

spring_mesh make_cloth(int n, pin_mode pins) {
  cloth_parameters parameters;
  parameters.grid_size = n;
  parameters.pins = pins;
  spring_mesh cloth(parameters);
  cloth.load_model();
  return cloth;
}

TEST(SpringMesh, IndexIsKuPlusNTimesKv) {
  EXPECT_EQ(spring_mesh::index(0, 0, 5), 0u);
  EXPECT_EQ(spring_mesh::index(4, 0, 5), 4u);
  EXPECT_EQ(spring_mesh::index(0, 1, 5), 5u);
  EXPECT_EQ(spring_mesh::index(2, 3, 5), 17u);
}

// p(ku, kv) = (-S/2 + ku h, -S/2 + kv h, 0), h = S/(N-1): N = 4, S = 2 gives h = 2/3.
TEST(SpringMesh, InitialGridIsFlatAtRestInTheIndexLayout) {
  cloth_parameters parameters;
  parameters.grid_size = 4;
  parameters.side_length = 2.0;
  spring_mesh cloth(parameters);
  cloth.load_model();
  EXPECT_EQ(cloth.grid_size(), 4);
  const particle_system& particles = cloth.particles();
  ASSERT_EQ(particles.size(), 16u);
  for (int kv = 0; kv < 4; ++kv) {
    for (int ku = 0; ku < 4; ++ku) {
      const std::size_t k = static_cast<std::size_t>(ku + 4 * kv);
      EXPECT_DOUBLE_EQ(particles.position[3 * k], -1.0 + ku * (2.0 / 3.0)) << ku << "," << kv;
      EXPECT_DOUBLE_EQ(particles.position[3 * k + 1], -1.0 + kv * (2.0 / 3.0)) << ku << "," << kv;
      EXPECT_EQ(particles.position[3 * k + 2], 0.0);
      EXPECT_EQ(particles.get_velocity(k), glm::dvec3(0.0));
    }
  }
}

// Structural: N-1 horizontal pairs on each of N rows, and as many vertical: 2 N (N-1).
// Shear: two diagonals per cell: 2 (N-1)^2. Bending: N-2 pairs per row and column: 2 N (N-2).
TEST(SpringMesh, SpringCountsMatchTheGrid) {
  for (const int n : {2, 3, 4, 7, 20}) {
    const spring_mesh cloth = make_cloth(n, pin_mode::corners);
    EXPECT_EQ(cloth.springs(spring_family::structural).size(),
              static_cast<std::size_t>(2 * n * (n - 1)))
        << "N = " << n;
    EXPECT_EQ(cloth.springs(spring_family::shear).size(),
              static_cast<std::size_t>(2 * (n - 1) * (n - 1)))
        << "N = " << n;
    EXPECT_EQ(cloth.springs(spring_family::bending).size(),
              static_cast<std::size_t>(2 * n * (n - 2)))
        << "N = " << n;
  }
}

// Every spring joins the neighbours of its family (figure 6), each pair once, with the rest
// length of the flat grid: structural (1,0)/(0,1) and h, shear (1,1)/(1,-1) and h sqrt 2,
// bending (2,0)/(0,2) and 2h. N = 5, S = 1.5: h = 0.375.
TEST(SpringMesh, SpringsJoinTheirFamilysNeighboursWithTheirRestLengths) {
  cloth_parameters parameters;
  parameters.grid_size = 5;
  parameters.side_length = 1.5;
  spring_mesh cloth(parameters);
  cloth.load_model();
  const double h = 0.375;
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const spring_family family : all_spring_families) {
    for (const spring& s : cloth.springs(family)) {
      ASSERT_LT(s.a, 25u);
      ASSERT_LT(s.b, 25u);
      const grid_offset a = grid_coordinates(s.a, 5);
      const grid_offset b = grid_coordinates(s.b, 5);
      const int du = std::abs(a.du - b.du);
      const int dv = std::abs(a.dv - b.dv);
      EXPECT_TRUE(pairs.insert(std::minmax(s.a, s.b)).second)
          << "spring " << s.a << "-" << s.b << " appears twice";
      switch (family) {
        case spring_family::structural:
          EXPECT_EQ(du + dv, 1) << s.a << "-" << s.b;
          EXPECT_DOUBLE_EQ(s.rest_length, h);
          break;
        case spring_family::shear:
          EXPECT_TRUE(du == 1 && dv == 1) << s.a << "-" << s.b;
          EXPECT_DOUBLE_EQ(s.rest_length, h * std::sqrt(2.0));
          break;
        case spring_family::bending:
          EXPECT_TRUE((du == 2 && dv == 0) || (du == 0 && dv == 2)) << s.a << "-" << s.b;
          EXPECT_DOUBLE_EQ(s.rest_length, 2.0 * h);
          break;
      }
    }
  }
}

TEST(SpringMesh, DefaultPinsAreTheCornersZeroZeroAndNMinusOneZero) {
  const spring_mesh cloth = make_cloth(6, pin_mode::corners);
  for (std::size_t k = 0; k < 36; ++k) {
    EXPECT_EQ(cloth.particles().is_fixed[k], (k == 0 || k == 5) ? 1 : 0) << "k = " << k;
  }
  const spring_mesh free_cloth = make_cloth(6, pin_mode::none);
  for (std::size_t k = 0; k < 36; ++k) {
    EXPECT_EQ(free_cloth.particles().is_fixed[k], 0) << "k = " << k;
  }
}

// Displace particle 3 = (1, 1) of a 2 x 2 cloth with S = 1 (h = 1) by 0.5 along z:
//  - structural springs 1-3 and 2-3: p3 - p1 = (0, 1, 0.5), p3 - p2 = (1, 0, 0.5), both of
//    length sqrt(1.25) and rest length 1, so F3 = K_struct (1 - sqrt 1.25)/sqrt 1.25 (1, 1, 1);
//  - shear spring 0-3: p3 - p0 = (1, 1, 0.5), length 1.5, rest length sqrt 2:
//    F3 = K_shear (sqrt 2 - 1.5)/1.5 (1, 1, 0.5);
//  - no bending spring in a 2 x 2 grid.
TEST(SpringMesh, StructuralAndShearSpringsUseTheirOwnStiffness) {
  cloth_parameters parameters;
  parameters.grid_size = 2;
  parameters.pins = pin_mode::none;
  parameters.structural_stiffness = 10.0;
  parameters.shear_stiffness = 3.0;
  parameters.bending_stiffness = 1000.0;
  spring_mesh cloth(parameters);
  cloth.load_model();
  cloth.particles().position[3 * 3 + 2] = 0.5;
  cloth.compute_force();
  const double structural = 10.0 * (1.0 - std::sqrt(1.25)) / std::sqrt(1.25);
  const double shear = 3.0 * (std::sqrt(2.0) - 1.5) / 1.5;
  const glm::dvec3 expected = structural * glm::dvec3(1, 1, 1) + shear * glm::dvec3(1, 1, 0.5);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(cloth.particles().force[9 + static_cast<std::size_t>(c)], expected[c], 1e-12)
        << "c = " << c;
  }
}

// 3 x 3 cloth, S = 2 (h = 1), only bending springs (K_bend = 7): lift (2, 0) = particle 2 to
// z = 1. Its bending springs go to (0, 0) and (2, 2): p2 - p0 = (2, 0, 1), p2 - p8 = (0, -2, 1),
// both of length sqrt 5 and rest length 2: F2 = 7 (2 - sqrt 5)/sqrt 5 (2, -2, 2).
TEST(SpringMesh, BendingSpringsSkipOneParticle) {
  cloth_parameters parameters;
  parameters.grid_size = 3;
  parameters.side_length = 2.0;
  parameters.pins = pin_mode::none;
  parameters.structural_stiffness = 0.0;
  parameters.shear_stiffness = 0.0;
  parameters.bending_stiffness = 7.0;
  spring_mesh cloth(parameters);
  cloth.load_model();
  cloth.particles().position[3 * 2 + 2] = 1.0;
  cloth.compute_force();
  const double magnitude = 7.0 * (2.0 - std::sqrt(5.0)) / std::sqrt(5.0);
  EXPECT_NEAR(cloth.particles().force[6], 2.0 * magnitude, 1e-12);
  EXPECT_NEAR(cloth.particles().force[7], -2.0 * magnitude, 1e-12);
  EXPECT_NEAR(cloth.particles().force[8], 2.0 * magnitude, 1e-12);
}

// Spring forces come in opposite pairs, so on a free cloth (no wind) they sum to zero, and since
// each pair lies along the line joining its particles their torques sum to zero too.
TEST(SpringMesh, SpringForcesObeyNewtonsThirdLaw) {
  spring_mesh cloth = make_cloth(8, pin_mode::none);
  std::mt19937 generator(12345);
  std::uniform_real_distribution<double> perturbation(-0.03, 0.03);
  for (double& coordinate : cloth.particles().position) {
    coordinate += perturbation(generator);
  }
  cloth.compute_force();
  const particle_system& particles = cloth.particles();
  glm::dvec3 total_force(0.0);
  glm::dvec3 total_torque(0.0);
  double magnitude = 0.0;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const glm::dvec3 f = {particles.force[3 * k], particles.force[3 * k + 1],
                          particles.force[3 * k + 2]};
    total_force += f;
    total_torque += glm::cross(particles.get_position(k), f);
    magnitude += std::abs(f.x) + std::abs(f.y) + std::abs(f.z);
  }
  ASSERT_GT(magnitude, 1.0) << "the perturbation must stretch the springs";
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(total_force[c], 0.0, 1e-12 * magnitude) << "c = " << c;
    EXPECT_NEAR(total_torque[c], 0.0, 1e-12 * magnitude) << "c = " << c;
  }
}

// Every spring at its rest length exerts no force; without gravity nothing moves, bit for bit.
TEST(SpringMesh, FlatClothAtRestWithoutGravityStaysExactlyAtRest) {
  for (const pin_mode pins : {pin_mode::corners, pin_mode::none}) {
    cloth_parameters parameters;
    parameters.grid_size = 10;
    parameters.pins = pins;
    parameters.dynamics.gravity = 0.0;
    spring_mesh cloth(parameters);
    cloth.load_model();
    const std::vector<double> initial = cloth.particles().position;
    for (int s = 0; s < 500; ++s) {
      cloth.step();
    }
    EXPECT_EQ(cloth.particles().position, initial);
    EXPECT_TRUE(std::all_of(cloth.particles().velocity.begin(), cloth.particles().velocity.end(),
                            [](double v) { return v == 0.0; }));
  }
}

TEST(SpringMesh, PinnedCornersNeverMove) {
  spring_mesh cloth = make_cloth(10, pin_mode::corners);
  const glm::dvec3 corner_00 = cloth.particles().get_position(0);
  const glm::dvec3 corner_n0 = cloth.particles().get_position(9);
  for (int s = 0; s < 300; ++s) {
    cloth.step();
    ASSERT_EQ(cloth.particles().get_position(0), corner_00) << "step " << s + 1;
    ASSERT_EQ(cloth.particles().get_position(9), corner_n0) << "step " << s + 1;
    ASSERT_EQ(cloth.particles().get_velocity(0), glm::dvec3(0.0)) << "step " << s + 1;
    ASSERT_EQ(cloth.particles().get_velocity(9), glm::dvec3(0.0)) << "step " << s + 1;
  }
  // The rest of the cloth hangs below them.
  EXPECT_LT(cloth.particles().position[3 * 99 + 2], -0.1);
}

// Without pins (and without ground) every particle gets the same velocity and moves by the same
// amount, so the springs keep their rest lengths and the cloth falls as one free particle:
// v_s = (1 - mu dt) v_(s-1) - g0 dt, z_s = z_(s-1) + dt v_s (semi-implicit).
TEST(SpringMesh, WithoutPinsTheWholeClothFallsFreely) {
  cloth_parameters parameters;
  parameters.grid_size = 6;
  parameters.pins = pin_mode::none;
  parameters.ground_enabled = false;
  spring_mesh cloth(parameters);
  cloth.load_model();
  const double dt = parameters.dynamics.time_step;
  const double damping_factor = 1.0 - parameters.dynamics.damping * dt;
  double v = 0.0;
  double z = 0.0;
  for (int s = 0; s < 100; ++s) {
    cloth.step();
    v = damping_factor * v - parameters.dynamics.gravity * dt;
    z += dt * v;
  }
  ASSERT_LT(z, -0.15);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    EXPECT_NEAR(cloth.particles().position[3 * k + 2], z, 1e-12) << "k = " << k;
    EXPECT_NEAR(cloth.particles().velocity[3 * k + 2], v, 1e-12) << "k = " << k;
  }
}

TEST(SpringMesh, ExplicitIntegratorLeavesTheClothInPlaceOnItsFirstStep) {
  cloth_parameters parameters;
  parameters.grid_size = 4;
  parameters.pins = pin_mode::none;
  parameters.dynamics.integrator = integrator_kind::explicit_euler;
  spring_mesh cloth(parameters);
  cloth.load_model();
  const std::vector<double> initial = cloth.particles().position;
  cloth.step();
  EXPECT_EQ(cloth.particles().position, initial);
  // v = dt * (0, 0, -g0) = (0, 0, -0.0196) with dt = 0.002 and g0 = 9.8
  EXPECT_DOUBLE_EQ(cloth.particles().velocity[2], -0.0196);
}

// A cloth hanging from its two corners at z = 0 swings down onto a ground 0.3 m below them: it
// reaches it (after ~0.25 s) and no particle ever ends a step under it.
TEST(SpringMesh, SwingingClothNeverCrossesTheGround) {
  cloth_parameters parameters;
  parameters.grid_size = 8;
  parameters.pins = pin_mode::corners;
  parameters.ground_height = -0.3;
  spring_mesh cloth(parameters);
  cloth.load_model();
  bool touched = false;
  for (int s = 0; s < 400; ++s) {
    cloth.step();
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const double z = cloth.particles().position[3 * k + 2];
      ASSERT_GE(z, -0.3) << "particle " << k << " at step " << s + 1;
      touched = touched || z == -0.3;
    }
  }
  EXPECT_TRUE(touched);
}

TEST(SpringMesh, DisabledGroundLetsTheClothFallThrough) {
  cloth_parameters parameters;
  parameters.grid_size = 4;
  parameters.pins = pin_mode::none;
  parameters.ground_enabled = false;
  parameters.ground_height = -0.1;
  spring_mesh cloth(parameters);
  cloth.load_model();
  for (int s = 0; s < 200; ++s) {  // 0.4 s: a free fall of ~0.75 m
    cloth.step();
  }
  EXPECT_LT(cloth.particles().position[2], -0.5);
}

// Ground z_g = -1, mu_g = 2, dt = 0.01: factor 1 - mu_g dt = 0.98.
//  0: below and falling:      z -> -1, v = (2, -4, -3) -> (1.96, -3.92, 0)
//  1: above the ground:       untouched
//  2: below and rising:       z -> -1, v_z = 1 kept, (v_x, v_y) damped
//  3: fixed, below the ground: untouched
TEST(GroundContact, ContactRuleMatchesTheHandComputation) {
  particle_system particles;
  particles.resize(4);
  particles.set_position(0, {0.5, 0.25, -1.5});
  particles.set_velocity(0, {2.0, -4.0, -3.0});
  particles.set_position(1, {0.5, 0.25, -0.5});
  particles.set_velocity(1, {2.0, -4.0, -3.0});
  particles.set_position(2, {0.5, 0.25, -1.25});
  particles.set_velocity(2, {2.0, -4.0, 1.0});
  particles.set_position(3, {0.5, 0.25, -2.0});
  particles.is_fixed[3] = 1;
  apply_ground_contact(-1.0, 2.0, 0.01, particles);
  EXPECT_EQ(particles.get_position(0), glm::dvec3(0.5, 0.25, -1.0));
  EXPECT_DOUBLE_EQ(particles.velocity[0], 1.96);
  EXPECT_DOUBLE_EQ(particles.velocity[1], -3.92);
  EXPECT_EQ(particles.velocity[2], 0.0);
  EXPECT_EQ(particles.get_position(1), glm::dvec3(0.5, 0.25, -0.5));
  EXPECT_EQ(particles.get_velocity(1), glm::dvec3(2.0, -4.0, -3.0));
  EXPECT_EQ(particles.get_position(2), glm::dvec3(0.5, 0.25, -1.0));
  EXPECT_DOUBLE_EQ(particles.velocity[6], 1.96);
  EXPECT_DOUBLE_EQ(particles.velocity[7], -3.92);
  EXPECT_EQ(particles.velocity[8], 1.0);
  EXPECT_EQ(particles.get_position(3), glm::dvec3(0.5, 0.25, -2.0));
  EXPECT_EQ(particles.get_velocity(3), glm::dvec3(0.0));
}

// d_u = (2h, 0, 0) (or h on the border), d_v = (0, 2h, 0): n = (0, 0, 1) everywhere.
TEST(Normals, FlatClothNormalsPointUp) {
  spring_mesh cloth = make_cloth(5, pin_mode::corners);
  cloth.compute_normals();
  ASSERT_EQ(cloth.normals().size(), 75u);
  for (std::size_t k = 0; k < 25; ++k) {
    EXPECT_EQ(cloth.normals()[3 * k], 0.0) << k;
    EXPECT_EQ(cloth.normals()[3 * k + 1], 0.0) << k;
    EXPECT_DOUBLE_EQ(cloth.normals()[3 * k + 2], 1.0) << k;
  }
}

// A bent 3 x 3 grid p(ku, kv) = (ku, kv, ku^2 + 2 kv), by hand with the central differences of
// model.md (one-sided on the border):
//  (1,1): d_u = p(2,1) - p(0,1) = (2, 0, 4), d_v = p(1,2) - p(1,0) = (0, 2, 4),
//         d_u x d_v = (-8, -8, 4) -> (-2, -2, 1)/3
//  (0,0): d_u = p(1,0) - p(0,0) = (1, 0, 1), d_v = p(0,1) - p(0,0) = (0, 1, 2),
//         d_u x d_v = (-1, -2, 1) -> (-1, -2, 1)/sqrt 6
//  (2,2): d_u = p(2,2) - p(1,2) = (1, 0, 3), d_v = p(2,2) - p(2,1) = (0, 1, 2),
//         d_u x d_v = (-3, -2, 1) -> (-3, -2, 1)/sqrt 14
//  (1,0): d_u = p(2,0) - p(0,0) = (2, 0, 4), d_v = p(1,1) - p(1,0) = (0, 1, 2),
//         d_u x d_v = (-4, -4, 2) -> (-2, -2, 1)/3
TEST(Normals, BentGridNormalsMatchTheHandComputation) {
  std::vector<double> position(27);
  for (int kv = 0; kv < 3; ++kv) {
    for (int ku = 0; ku < 3; ++ku) {
      const std::size_t k = static_cast<std::size_t>(ku + 3 * kv);
      position[3 * k] = ku;
      position[3 * k + 1] = kv;
      position[3 * k + 2] = ku * ku + 2 * kv;
    }
  }
  std::vector<double> normal(27, 0.0);
  compute_vertex_normals(3, position, normal);
  const auto expect_normal = [&](int ku, int kv, const glm::dvec3& expected) {
    const std::size_t k = static_cast<std::size_t>(ku + 3 * kv);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(normal[3 * k + static_cast<std::size_t>(c)], expected[c], 1e-15)
          << "(" << ku << "," << kv << ") c = " << c;
    }
  };
  expect_normal(1, 1, glm::dvec3(-2, -2, 1) / 3.0);
  expect_normal(0, 0, glm::dvec3(-1, -2, 1) / std::sqrt(6.0));
  expect_normal(2, 2, glm::dvec3(-3, -2, 1) / std::sqrt(14.0));
  expect_normal(1, 0, glm::dvec3(-2, -2, 1) / 3.0);
}

// F_w = K_w <n, u_w> n with u_w normalised: n = (0.6, 0, 0.8), direction (7, 0, 0) -> u_w =
// (1, 0, 0), K_w = 2: F = 2 * 0.6 * (0.6, 0, 0.8) = (0.72, 0, 0.96), added to the force already
// there. The opposite direction gives the opposite force.
TEST(Wind, WindForceMatchesTheHandComputation) {
  const std::vector<double> normal = {0.6, 0.0, 0.8, 0.6, 0.0, 0.8};
  std::vector<double> force = {1.0, 1.0, 1.0, 0.0, 0.0, 0.0};
  accumulate_wind_forces(2.0, {7.0, 0.0, 0.0}, normal, force);
  EXPECT_DOUBLE_EQ(force[0], 1.72);
  EXPECT_DOUBLE_EQ(force[1], 1.0);
  EXPECT_DOUBLE_EQ(force[2], 1.96);
  EXPECT_DOUBLE_EQ(force[3], 0.72);
  EXPECT_EQ(force[4], 0.0);
  EXPECT_DOUBLE_EQ(force[5], 0.96);
  std::vector<double> opposite(6, 0.0);
  accumulate_wind_forces(2.0, {-7.0, 0.0, 0.0}, normal, opposite);
  EXPECT_DOUBLE_EQ(opposite[0], -0.72);
  EXPECT_DOUBLE_EQ(opposite[2], -0.96);
}

// On the flat cloth at rest (no spring force), n = (0, 0, 1); the direction (0, 3, 4) normalises
// to (0, 0.6, 0.8), <n, u_w> = 0.8, so with K_w = 3 every particle feels F = (0, 0, 2.4).
TEST(Wind, FlatClothFeelsTheWindAlongItsNormal) {
  cloth_parameters parameters;
  parameters.grid_size = 5;
  parameters.wind_strength = 3.0;
  parameters.wind_direction = {0.0, 3.0, 4.0};
  spring_mesh cloth(parameters);
  cloth.load_model();
  cloth.compute_force();
  for (std::size_t k = 0; k < 25; ++k) {
    EXPECT_NEAR(cloth.particles().force[3 * k], 0.0, 1e-12) << k;
    EXPECT_NEAR(cloth.particles().force[3 * k + 1], 0.0, 1e-12) << k;
    EXPECT_NEAR(cloth.particles().force[3 * k + 2], 2.4, 1e-12) << k;
  }
}

}  // namespace
}  // namespace clothlab
