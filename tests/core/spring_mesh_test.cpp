// Stage 3, the cloth (model.md): grid layout, the spring list of the three families, rest,
// the explicit scheme, a disabled ground and normals, each against a hand computation. The code
// the lab asks students to write (forces, integration, pins, ground, wind) is graded in tests/lab.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <set>
#include <utility>

#include "core/spring_mesh.hpp"

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

// Every spring at its rest length exerts no force; without gravity nothing moves. How still
// depends on how question 8 writes the rest lengths: measured from the initial positions they
// make the forces exactly zero; h sqrt 2 written out differs from the measured length by a
// rounding, 1e-16 m in double and 1e-8 m in float temporaries, and moves the cloth by that
// much, back and forth: the tolerance is float rounding of the cloth's size (1 m), 1e-6 m.
TEST(SolutionSpringMesh, FlatClothAtRestWithoutGravityStaysAtRest) {
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
    double moved = 0.0, speed = 0.0;
    for (std::size_t i = 0; i < initial.size(); ++i) {
      moved = std::max(moved, std::abs(cloth.particles().position[i] - initial[i]));
      speed = std::max(speed, std::abs(cloth.particles().velocity[i]));
    }
    EXPECT_LE(moved, 1e-6) << "the cloth at rest moved (largest coordinate change, m)";
    EXPECT_LE(speed, 1e-6 / parameters.dynamics.time_step)
        << "the cloth at rest moves (largest speed, m/s)";
  }
}

// --integrator explicit, equation 6 taken literally, is built on question 6's apply_force: the
// speeds it computes, each vertex moved by its speed at the start of the step. A cloth without
// springs, damping, pins or ground, each vertex with its own speed, one step: p' = p + dt v and
// v' = v + dt g (the stub of the student copy and every answer alike). Tolerance: float
// rounding of values of size 2 (an answer may compute in single precision).
TEST(SpringMesh, ExplicitEulerMovesEveryVertexWithItsSpeedAtTheStartOfTheStep) {
  cloth_parameters parameters;
  parameters.grid_size = 3;
  parameters.pins = pin_mode::none;
  parameters.ground_enabled = false;
  parameters.structural_stiffness = parameters.shear_stiffness = 0.0;
  parameters.bending_stiffness = 0.0;
  parameters.dynamics.damping = 0.0;
  parameters.dynamics.integrator = integrator_kind::explicit_euler;
  spring_mesh cloth(parameters);
  const double dt = parameters.dynamics.time_step;
  particle_system& particles = cloth.particles();
  std::vector<glm::dvec3> p, v;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    particles.set_velocity(k, {0.1 * double(k), 1.0 - 0.2 * double(k), 0.5});
    p.push_back(particles.get_position(k));
    v.push_back(particles.get_velocity(k));
  }
  cloth.step();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    EXPECT_LE(glm::length(particles.get_position(k) - (p[k] + dt * v[k])), 2e-6) << "vertex " << k;
    const glm::dvec3 g = {0.0, 0.0, -parameters.dynamics.gravity};
    EXPECT_LE(glm::length(particles.get_velocity(k) - (v[k] + dt * g)), 2e-6) << "vertex " << k;
  }
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

}  // namespace
}  // namespace clothlab
