// Question 12: the spring forces in the GPU step shader (shaders/gpu_step.frag). One GPU step,
// without gravity, damping, wind or ground, from a state set by hand and at rest: each particle's
// new velocity is dt F / m, F the sum of equation 2 over the springs of its up to 12 neighbours.
// The GPU's force is read back as F = m v / dt and compared with equation 2 computed here in
// double precision for the pairs named in each comment. Every case of question 8's CPU tests
// (q8_compute_force_test.cpp) is checked here too: each family alone, its stiffness and rest
// length, the reaction on the other end, the corners and borders, the sum and the torque. The
// GPU computes in single precision: a spring force rounds by float_rounding K |p| at most
// (lab_check.hpp), however the shader writes it. Whether a spring exists is the answer's to
// decide (joined(k, i), or a border test of its own): tearing, which needs joined, is clothlab's
// addition and is not graded here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gl_fixture.hpp"
#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::spring_mesh;

using Q12GpuSprings = lab::OffscreenGl;

constexpr double dt = 0.01;  // s

// The rounding of the force of `springs` springs of stiffness K between positions of size
// `size`, in single precision (lab_check.hpp); F = m v / dt adds a rounding of its own size.
double force_tolerance(int springs, double K, double size) {
  return springs * K * lab::rounding(size);
}

// What a force of the wrong sign says.
// (`where` and `springs` already in the student's language; `springs` empty: all of them.)
std::string reversed(const std::string& where, const std::string& springs = "") {
  return format(tr("Q12: %s feels its %s with the wrong sign (pushed where a stretched spring "
                   "pulls, and pulled where a compressed one pushes): equation 2, "
                   "spring_force(p_i, p_j, K, L0), is the force ON p_i; which of the two is this "
                   "texel's position p?"),
                where.c_str(), springs.empty() ? tr("springs") : springs.c_str());
}

// A still N x N cloth of side S with the given stiffnesses (0 turns a family off); no gravity,
// damping, pins, ground or wind; m = 1.
cloth_parameters still_cloth(int n, double side, double k_structural, double k_shear,
                             double k_bending) {
  cloth_parameters p;
  p.grid_size = n;
  p.side_length = side;
  p.structural_stiffness = k_structural;
  p.shear_stiffness = k_shear;
  p.bending_stiffness = k_bending;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.wind_strength = 0.0;
  p.dynamics = {.time_step = dt, .damping = 0.0, .mass = 1.0, .gravity = 0.0};
  return p;
}

int grid(const spring_mesh& cloth) {
  return cloth.grid_size();
}
glm::dvec3 position_of(const spring_mesh& cloth, int ku, int kv) {
  return cloth.particles().get_position(spring_mesh::index(ku, kv, grid(cloth)));
}
void move(spring_mesh& cloth, int ku, int kv, const glm::dvec3& p) {
  cloth.particles().set_position(spring_mesh::index(ku, kv, grid(cloth)), p);
}

using lab::gpu_forces;  // one GPU step's force on each texel (gl_fixture.hpp)

glm::dvec3 at(const std::vector<glm::dvec3>& force, const spring_mesh& cloth, int ku, int kv) {
  return force[spring_mesh::index(ku, kv, grid(cloth))];
}

// "(2, 1)"
std::string texel(int ku, int kv) {
  return "(" + std::to_string(ku) + ", " + std::to_string(kv) + ")";
}

// The force on s(ku, kv) by hand, family by family: equation 2 for each of the 12 neighbours of
// figure 6 that is inside the N x N grid, with its family's stiffness and rest length (h,
// h sqrt 2, 2h).
std::vector<lab::force_part> family_forces(const spring_mesh& cloth, int ku, int kv, double h,
                                           double k_structural, double k_shear, double k_bending) {
  struct neighbour {
    int du, dv, family;
  };
  const double r2 = std::sqrt(2.0);
  const double K[] = {k_structural, k_shear, k_bending}, L0[] = {h, h * r2, 2 * h};
  const neighbour neighbours[] = {{1, 0, 0}, {-1, 0, 0},  {0, 1, 0},  {0, -1, 0},
                                  {1, 1, 1}, {-1, -1, 1}, {1, -1, 1}, {-1, 1, 1},
                                  {2, 0, 2}, {-2, 0, 2},  {0, 2, 2},  {0, -2, 2}};
  const int n = grid(cloth);
  std::vector<lab::force_part> parts = {{tr("structural springs"), glm::dvec3(0.0)},
                                        {tr("shear springs"), glm::dvec3(0.0)},
                                        {tr("bending springs"), glm::dvec3(0.0)}};
  for (const neighbour& o : neighbours) {
    const int u = ku + o.du, v = kv + o.dv;
    if (u >= 0 && u < n && v >= 0 && v < n)
      parts[std::size_t(o.family)].force += spring_force(
          position_of(cloth, ku, kv), position_of(cloth, u, v), K[o.family], L0[o.family]);
  }
  return parts;
}

glm::dvec3 expected_force(const spring_mesh& cloth, int ku, int kv, double h, double k_structural,
                          double k_shear, double k_bending) {
  glm::dvec3 f(0.0);
  for (const lab::force_part& part :
       family_forces(cloth, ku, kv, h, k_structural, k_shear, k_bending))
    f += part.force;
  return f;
}

// The message of a force test of texel (ku, kv), whose springs of several families are summed:
// `what`, or, when the answer has one family's force reversed, that family's sign error.
std::string family_message(const glm::dvec3& got, const spring_mesh& cloth, int ku, int kv,
                           double h, double k_structural, double k_shear, double k_bending,
                           double tolerance, const std::string& where, const std::string& what) {
  const std::string family = lab::reversed_part(
      got, expected_force(cloth, ku, kv, h, k_structural, k_shear, k_bending),
      family_forces(cloth, ku, kv, h, k_structural, k_shear, k_bending), tolerance);
  return family.empty() ? what : reversed(where, family);
}

// Every texel of an N x N cloth (S = N - 1, h = 1) moved off its place by a smooth,
// non-symmetric offset: every spring is stretched or compressed by its own amount.
void deform(spring_mesh& cloth, double amplitude) {
  const int n = grid(cloth);
  for (int kv = 0; kv < n; ++kv)
    for (int ku = 0; ku < n; ++ku)
      move(cloth, ku, kv,
           position_of(cloth, ku, kv) + amplitude * glm::dvec3(std::sin(ku + 2.0 * kv),
                                                               std::cos(3.0 * ku - kv),
                                                               (ku * kv % 3) - 0.7 * ku));
}

// What kind of place s(ku, kv) is on an N x N grid, for the messages.
std::string place(int ku, int kv, int n) {
  const bool u_border = ku == 0 || ku == n - 1, v_border = kv == 0 || kv == n - 1;
  if (u_border && v_border)
    return format(tr("the corner %s"), texel(ku, kv).c_str());
  if (u_border || v_border)
    return format(tr("the border texel %s"), texel(ku, kv).c_str());
  return format(tr("the inner texel %s"), texel(ku, kv).c_str());
}

// 5 x 5, S = 4 (h = 1), the three families with their own stiffnesses; the centre s(2, 2) moved.
constexpr double K_structural = 100.0, K_shear = 50.0, K_bending = 20.0;  // N/m

spring_mesh displaced_centre(const glm::dvec3& c) {
  spring_mesh cloth(still_cloth(5, 4.0, K_structural, K_shear, K_bending));
  move(cloth, 2, 2, c);
  return cloth;
}

TEST_F(Q12GpuSprings, TheDisplacedCentreFeelsAllTwelveSprings) {
  const glm::dvec3 c = {0.3, -0.2, 0.5};
  const spring_mesh cloth = displaced_centre(c);
  const auto force = gpu_forces(cloth, still_cloth(5, 4.0, K_structural, K_shear, K_bending));
  const double tolerance = force_tolerance(12, K_structural, 2.5);
  LAB_EXPECT_FORCE(at(force, cloth, 2, 2),
                   expected_force(cloth, 2, 2, 1.0, K_structural, K_shear, K_bending), tolerance,
                   family_message(at(force, cloth, 2, 2), cloth, 2, 2, 1.0, K_structural, K_shear,
                                  K_bending, tolerance, tr("the centre texel (2, 2)"),
                                  tr("Q12: the centre texel (2, 2), moved off its rest place, "
                                     "should be pulled back by the springs to its 12 neighbours "
                                     "(4 structural, 4 shear, 4 bending): its new velocity is "
                                     "dt F / m. Does the velocity shader add the spring forces?")),
                   reversed(tr("the centre texel (2, 2), moved off its rest place,")));
}

TEST_F(Q12GpuSprings, EachNeighbourFeelsItsSpringToTheCentre) {
  const glm::dvec3 c = {0.3, -0.2, 0.5};
  const spring_mesh cloth = displaced_centre(c);
  const auto force = gpu_forces(cloth, still_cloth(5, 4.0, K_structural, K_shear, K_bending));
  const struct {
    int ku, kv;
    const char* family;
  } neighbours[] = {
      // TRANSLATORS: a spring of a family, in "texel (3, 2) should feel its structural spring".
      {3, 2, N_("structural spring")}, {2, 1, N_("structural spring")},
      {3, 3, N_("shear spring")},      {1, 3, N_("shear spring")},
      {4, 2, N_("bending spring")},    {2, 0, N_("bending spring")}};
  for (const auto& n : neighbours) {
    const double tolerance = force_tolerance(12, K_structural, 2.5);
    LAB_EXPECT_FORCE(
        at(force, cloth, n.ku, n.kv),
        expected_force(cloth, n.ku, n.kv, 1.0, K_structural, K_shear, K_bending), tolerance,
        family_message(at(force, cloth, n.ku, n.kv), cloth, n.ku, n.kv, 1.0, K_structural, K_shear,
                       K_bending, tolerance, format(tr("texel %s"), texel(n.ku, n.kv).c_str()),
                       format(tr("Q12: texel %s should feel its %s to the displaced centre "
                                 "(2, 2), and nothing else"),
                              texel(n.ku, n.kv).c_str(), tr(n.family))),
        reversed(format(tr("texel %s"), texel(n.ku, n.kv).c_str())));
  }
}

// Question 8's cases, one family at a time, on the GPU. 3 x 3, S = 2 (h = 1):
// s(ku, kv) = (-1 + ku, -1 + kv, 0). Structural only, K = 100: s(2, 1) pulled from (1, 0, 0) to
// (1.5, 0, 0) feels (-50, 0, 0) from s(1, 1) and, from s(2, 0) and s(2, 2),
// F_x = 2 * 100 (1 - sqrt 1.25) / sqrt 1.25 * 0.5; s(1, 1) feels the reaction (50, 0, 0).
TEST_F(Q12GpuSprings, StructuralSpringsPullAStretchedTexelBack) {
  const cloth_parameters p = still_cloth(3, 2.0, 100.0, 0.0, 0.0);
  spring_mesh cloth(p);
  move(cloth, 2, 1, {1.5, 0, 0});
  const auto force = gpu_forces(cloth, p);
  const double side = 100.0 * (1 - std::sqrt(1.25)) / std::sqrt(1.25);
  LAB_EXPECT_FORCE(at(force, cloth, 2, 1), glm::dvec3(-50 + side, 0, 0),
                   force_tolerance(3, 100.0, 1.5),
                   tr("Q12, structural springs: texel (2, 1), pulled 0.5 m away from (1, 1), "
                      "should be pulled back (towards -x) by its structural springs to (1, 1), "
                      "(2, 0) and (2, 2), of family 0, stiffness[0] and rest length "
                      "rest_length[0] = h"),
                   reversed(tr("texel (2, 1), pulled 0.5 m away from (1, 1),")));
  LAB_EXPECT_FORCE(at(force, cloth, 1, 1), glm::dvec3(50, 0, 0), force_tolerance(4, 100.0, 1.5),
                   tr("Q12, structural springs: texel (1, 1) should feel the stretched spring to "
                      "its neighbour (ku+1, kv) = (2, 1), pulling it towards +x: on the GPU each "
                      "texel gathers its own springs, so the other end of every spring must add "
                      "it too"),
                   reversed(format(tr("texel %s"), "(1, 1)")));
}

// Shear only, K = 100: the centre s(1, 1) moved to c = (0.3, 0.2, 0.4) is held by its four
// diagonals (rest length sqrt 2); the corner s(0, 0) feels only its one diagonal, to the centre.
TEST_F(Q12GpuSprings, ShearSpringsHoldTheDiagonals) {
  const cloth_parameters p = still_cloth(3, 2.0, 0.0, 100.0, 0.0);
  spring_mesh cloth(p);
  const glm::dvec3 c = {0.3, 0.2, 0.4};
  move(cloth, 1, 1, c);
  const auto force = gpu_forces(cloth, p);
  const double L0 = std::sqrt(2.0);
  glm::dvec3 expected(0.0);
  for (const glm::dvec3 corner :
       {glm::dvec3(-1, -1, 0), glm::dvec3(1, -1, 0), glm::dvec3(1, 1, 0), glm::dvec3(-1, 1, 0)})
    expected += spring_force(c, corner, 100.0, L0);
  LAB_EXPECT_FORCE(at(force, cloth, 1, 1), expected, force_tolerance(4, 100.0, 1.5),
                   tr("Q12, shear springs: the centre texel (1, 1), moved off its place, should "
                      "be held by its four diagonal springs to (ku+-1, kv+-1), of family 1 "
                      "(stiffness[1], rest length rest_length[1] = h sqrt 2)"),
                   reversed(tr("the centre texel (1, 1), moved off its place,")));
  LAB_EXPECT_FORCE(at(force, cloth, 0, 0), spring_force(glm::dvec3(-1, -1, 0), c, 100.0, L0),
                   force_tolerance(1, 100.0, 1.5),
                   tr("Q12, shear springs: the corner texel (0, 0) should feel its one diagonal "
                      "spring, to (1, 1)"),
                   reversed(tr("the corner texel (0, 0)")));
}

// Bending only, K = 7: s(2, 0) lifted from (1, -1, 0) to (1, -1, 1). Its bending springs go two
// texels away, to s(0, 0) and s(2, 2): d = (2, 0, 1) and (0, -2, 1), both of length sqrt 5 and
// rest length 2: F = 7 (2 - sqrt 5) / sqrt 5 (2, -2, 2).
TEST_F(Q12GpuSprings, BendingSpringsSkipOneTexel) {
  const cloth_parameters p = still_cloth(3, 2.0, 0.0, 0.0, 7.0);
  spring_mesh cloth(p);
  move(cloth, 2, 0, {1, -1, 1});
  const auto force = gpu_forces(cloth, p);
  const double scale = 7.0 * (2 - std::sqrt(5.0)) / std::sqrt(5.0);
  LAB_EXPECT_FORCE(at(force, cloth, 2, 0), scale * glm::dvec3(2, -2, 2),
                   force_tolerance(2, 7.0, 1.5),
                   tr("Q12, bending springs: texel (2, 0), lifted out of the plane, should be "
                      "pulled back (down) by its bending springs to (ku-2, kv) and (ku, kv+2), of "
                      "family 2 (stiffness[2], rest length rest_length[2] = 2h)"),
                   reversed(tr("texel (2, 0), lifted out of the plane,")));
  LAB_EXPECT_FORCE(at(force, cloth, 0, 0), spring_force({-1, -1, 0}, {1, -1, 1}, 7.0, 2.0),
                   force_tolerance(2, 7.0, 1.5),
                   tr("Q12, bending springs: texel (0, 0) should feel the bending spring to "
                      "(ku+2, kv) = (2, 0)"),
                   reversed(format(tr("texel %s"), "(0, 0)")));
}

// 2 x 2, S = 1 (h = 1), the three families with different stiffnesses: s(1, 1) lifted by 0.5
// feels its structural springs to s(0, 1) and s(1, 0) (K_struct = 300, rest 1) and its shear
// spring to s(0, 0) (K_shear = 70, rest sqrt 2).
TEST_F(Q12GpuSprings, EachFamilyUsesItsOwnStiffness) {
  const cloth_parameters p = still_cloth(2, 1.0, 300.0, 70.0, 11.0);
  spring_mesh cloth(p);
  const glm::dvec3 lifted = position_of(cloth, 1, 1) + glm::dvec3(0, 0, 0.5);
  move(cloth, 1, 1, lifted);
  const auto force = gpu_forces(cloth, p);
  const glm::dvec3 expected = spring_force(lifted, position_of(cloth, 0, 1), 300.0, 1.0) +
                              spring_force(lifted, position_of(cloth, 1, 0), 300.0, 1.0) +
                              spring_force(lifted, position_of(cloth, 0, 0), 70.0, std::sqrt(2.0));
  const double tolerance = force_tolerance(3, 300.0, 1.0);
  LAB_EXPECT_FORCE(at(force, cloth, 1, 1), expected, tolerance,
                   family_message(at(force, cloth, 1, 1), cloth, 1, 1, 1.0, 300.0, 70.0, 11.0,
                                  tolerance, tr("texel (1, 1), lifted by 0.5 m,"),
                                  tr("Q12: with K_struct = 300 and K_shear = 70, texel (1, 1) "
                                     "lifted by 0.5 m should feel two structural springs with "
                                     "stiffness[0] and one shear spring with stiffness[1]: the "
                                     "family of neighbour i is neighbours[i].z")),
                   reversed(tr("texel (1, 1), lifted by 0.5 m,")));
}

// 5 x 5, S = 4: the corner s(0, 0) moved to (-2.4, -2.3, 0.2) has five springs, structural to
// s(1, 0) and s(0, 1), shear to s(1, 1), bending to s(2, 0) and s(0, 2).
TEST_F(Q12GpuSprings, ACornerTexelReadsNoNeighbourOutsideTheGrid) {
  const cloth_parameters p = still_cloth(5, 4.0, K_structural, K_shear, K_bending);
  spring_mesh cloth(p);
  const glm::dvec3 corner = {-2.4, -2.3, 0.2};
  move(cloth, 0, 0, corner);
  const auto force = gpu_forces(cloth, p);
  const glm::dvec3 f = spring_force(corner, position_of(cloth, 1, 0), K_structural, 1) +
                       spring_force(corner, position_of(cloth, 0, 1), K_structural, 1) +
                       spring_force(corner, position_of(cloth, 1, 1), K_shear, std::sqrt(2.0)) +
                       spring_force(corner, position_of(cloth, 2, 0), K_bending, 2) +
                       spring_force(corner, position_of(cloth, 0, 2), K_bending, 2);
  const double tolerance = force_tolerance(5, K_structural, 2.5);
  LAB_EXPECT_FORCE(at(force, cloth, 0, 0), f, tolerance,
                   family_message(at(force, cloth, 0, 0), cloth, 0, 0, 1.0, K_structural, K_shear,
                                  K_bending, tolerance, tr("the corner texel (0, 0)"),
                                  tr("Q12: the corner texel (0, 0) has springs to (1, 0), (0, 1), "
                                     "(1, 1), (2, 0) and (0, 2) only: texels outside the N x N "
                                     "grid must be skipped")),
                   reversed(tr("the corner texel (0, 0)")));
}

// A 4 x 4 cloth (S = 3, h = 1), every texel moved, every family on: each texel, corners and
// borders included, feels exactly the springs to its neighbours inside the grid.
TEST_F(Q12GpuSprings, EveryTexelFeelsOnlyTheSpringsInsideTheGrid) {
  const cloth_parameters p = still_cloth(4, 3.0, 40.0, 30.0, 20.0);
  spring_mesh cloth(p);
  deform(cloth, 0.1);
  const auto force = gpu_forces(cloth, p);
  LAB_EXPECT_EVERY_FORCE(
      k, 4 * 4, at(force, cloth, int(k % 4), int(k / 4)),
      expected_force(cloth, int(k % 4), int(k / 4), 1.0, 40.0, 30.0, 20.0),
      force_tolerance(12, 40.0, 2.0),
      family_message(at(force, cloth, int(k % 4), int(k / 4)), cloth, int(k % 4), int(k / 4), 1.0,
                     40.0, 30.0, 20.0, force_tolerance(12, 40.0, 2.0),
                     place(int(k % 4), int(k / 4), 4),
                     format(tr("Q12: %s of a deformed 4 x 4 cloth should feel the springs to its "
                               "neighbours inside the grid, and none to texels outside it "
                               "(int(k %% 4) or int(k / 4) < 0 or > N-1 = 3: skip them, "
                               "joined(k, i) says which)"),
                            place(int(k % 4), int(k / 4), 4).c_str())),
      reversed(place(int(k % 4), int(k / 4), 4)));
}

// Spring forces come in opposite pairs along the line of their two ends: their sum and their
// total torque are zero. A deformed 5 x 5 cloth (S = 4), every family on.
TEST_F(Q12GpuSprings, SpringForcesSumToZeroAndExertNoTorque) {
  const cloth_parameters p = still_cloth(5, 4.0, 500.0, 200.0, 50.0);
  spring_mesh cloth(p);
  deform(cloth, 0.05);
  const auto force = gpu_forces(cloth, p);
  glm::dvec3 sum(0.0), torque(0.0), largest(0.0);
  for (int kv = 0; kv < 5; ++kv) {
    for (int ku = 0; ku < 5; ++ku) {
      const glm::dvec3 f = at(force, cloth, ku, kv);
      sum += f;
      torque += glm::cross(position_of(cloth, ku, kv), f);
      largest = glm::max(largest, glm::abs(f));
    }
  }
  LAB_EXPECT_TRUE(largest.x + largest.y + largest.z > 1.0,
                  tr("Q12: a deformed cloth with stiff springs should feel spring forces on the "
                     "GPU"));
  // Tolerance: the rounding of every spring force at both of its ends (80 structural ends of
  // K = 500, 64 shear ends of K = 200, 60 bending ends of K = 50; positions of size 2.5), and for
  // the torque, times the size of the positions.
  const double tolerance = lab::rounding(2.5 * (80 * 500.0 + 64 * 200.0 + 60 * 50.0));
  LAB_EXPECT_VEC(sum, glm::dvec3(0.0), tolerance,
                 tr("Q12: the spring forces should sum to zero (the two ends of a spring feel "
                    "opposite forces): does every texel add each of its springs once, with "
                    "spring_force(p, p_j, ...) on itself?"));
  LAB_EXPECT_VEC(torque, glm::dvec3(0.0), 2.5 * tolerance,
                 tr("Q12: the spring forces should exert no total torque (each pair lies along "
                    "its spring)"));
}

// At rest, every spring at its rest length: no force anywhere (a wrong rest length shows here).
TEST_F(Q12GpuSprings, AClothAtRestFeelsNoSpringForce) {
  const cloth_parameters p = still_cloth(5, 4.0, 500.0, 200.0, 50.0);
  const spring_mesh cloth(p);
  const auto force = gpu_forces(cloth, p);
  LAB_EXPECT_EVERY_VEC(
      k, 5 * 5, at(force, cloth, int(k % 5), int(k / 5)), glm::dvec3(0.0),
      force_tolerance(12, 500.0, 2.0),
      format(tr("Q12: on the flat cloth at rest every spring has its rest length (h, h sqrt 2 or "
                "2h for its family): %s should feel no spring force"),
             place(int(k % 5), int(k / 5), 5).c_str()));
}

}  // namespace
}  // namespace clothlab
