// Question 8: spring_mesh::compute_force, the forces of the structural, shear and bending springs
// of every vertex s(ku, kv) (handout figure 6), each with its own stiffness. Every test turns on
// one family at a time, moves vertices by hand, and compares with equation 2 evaluated for the
// pairs listed in its comment (spring_force, spring.hpp, is the handout's formula).
// Tolerances: the rounding of a spring force computed in single or double precision,
// float_rounding K |p| per spring (lab_check.hpp), whichever way its rest length is written
// (h sqrt 2 written out, or measured from the initial positions). Whether a spring exists is
// the answer's to decide (spring_intact, or a border test of its own): tearing, which needs
// spring_intact, is clothlab's addition and is not graded here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::spring_mesh;

// A flat N x N cloth of side S without wind, with the given stiffnesses (0 turns a family off).
// Without gravity too: the forces are the springs' alone, whether an answer adds m g in
// compute_force (as the handout's compute_force does) or g in apply_force.
spring_mesh cloth_with(int n, double side, double k_structural, double k_shear, double k_bending) {
  cloth_parameters p;
  p.dynamics.gravity = 0.0;
  p.grid_size = n;
  p.side_length = side;
  p.structural_stiffness = k_structural;
  p.shear_stiffness = k_shear;
  p.bending_stiffness = k_bending;
  p.wind_strength = 0.0;
  return spring_mesh(p);
}

glm::dvec3 force_on(const spring_mesh& cloth, int ku, int kv) {
  return cloth.particles().get_force(spring_mesh::index(ku, kv, cloth.grid_size()));
}
glm::dvec3 position_of(const spring_mesh& cloth, int ku, int kv) {
  return cloth.particles().get_position(spring_mesh::index(ku, kv, cloth.grid_size()));
}
void move(spring_mesh& cloth, int ku, int kv, const glm::dvec3& p) {
  cloth.particles().set_position(spring_mesh::index(ku, kv, cloth.grid_size()), p);
}

// What a force of the wrong sign says: the springs of `family` push where they should pull.
// (`family` and `vertex` already in the student's language.)
std::string reversed(const std::string& family, const std::string& vertex) {
  return format(tr("Q8, %s: %s feels its springs with the wrong sign (pushed where a stretched "
                   "spring pulls, and pulled where a compressed one pushes): equation 2, "
                   "spring_force(p_i, p_j, K, L0), is the force ON p_i; which of the two is the "
                   "vertex s(ku, kv)?"),
                family.c_str(), vertex.c_str());
}

// The rounding of the force of `springs` springs of stiffness K between positions of size
// `size` (lab_check.hpp).
double force_tolerance(int springs, double K, double size) {
  return springs * K * lab::rounding(size);
}

// 3 x 3, S = 2 (h = 1): s(ku, kv) = (-1 + ku, -1 + kv, 0). Structural only, K = 100. Pull s(2, 1)
// from (1, 0, 0) to (1.5, 0, 0):
//  - spring to s(1, 1) = (0, 0, 0): L = 1.5, F = 100 (1 - 1.5) (1.5, 0, 0) / 1.5 = (-50, 0, 0);
//  - springs to s(2, 0) and s(2, 2): d = (0.5, +-1, 0), L = sqrt 1.25, their y parts cancel:
//    F_x = 2 * 100 (1 - sqrt 1.25) / sqrt 1.25 * 0.5.
// And s(1, 1) feels the reaction of the first one, (50, 0, 0), its other springs being at rest.
TEST(Q8ComputeForce, StructuralSpringsPullAStretchedVertexBack) {
  spring_mesh cloth = cloth_with(3, 2.0, 100.0, 0.0, 0.0);
  move(cloth, 2, 1, {1.5, 0, 0});
  cloth.compute_force();
  const double side = 100.0 * (1 - std::sqrt(1.25)) / std::sqrt(1.25);
  LAB_EXPECT_FORCE(
      force_on(cloth, 2, 1), glm::dvec3(-50 + side, 0, 0), force_tolerance(3, 100.0, 1.5),
      tr("Q8, structural springs: s(2, 1), pulled 0.5 m away from s(1, 1), should "
         "be pulled back by its structural springs to s(1, 1), s(2, 0) and s(2, 2). "
         "Without them the cloth does not hold together"),
      reversed(tr("structural springs"), tr("s(2, 1), pulled 0.5 m away from s(1, 1),")));
  LAB_EXPECT_FORCE(force_on(cloth, 1, 1), glm::dvec3(50, 0, 0), force_tolerance(4, 100.0, 1.5),
                   tr("Q8, structural springs: s(1, 1) should feel the stretched spring to its "
                      "neighbour s(ku+1, kv) = s(2, 1): a spring pulls both of its ends"),
                   reversed(tr("structural springs"), "s(1, 1)"));
}

// Shear only, K = 100, 3 x 3, S = 2: move the centre s(1, 1) to c = (0.3, 0.2, 0.4). It is joined
// to the four corners by diagonals of rest length sqrt 2; the corner s(0, 0) only to the centre.
TEST(Q8ComputeForce, ShearSpringsHoldTheDiagonals) {
  spring_mesh cloth = cloth_with(3, 2.0, 0.0, 100.0, 0.0);
  const glm::dvec3 c = {0.3, 0.2, 0.4};
  move(cloth, 1, 1, c);
  cloth.compute_force();
  const double L0 = std::sqrt(2.0);
  glm::dvec3 expected(0.0);
  for (const glm::dvec3 corner :
       {glm::dvec3(-1, -1, 0), glm::dvec3(1, -1, 0), glm::dvec3(1, 1, 0), glm::dvec3(-1, 1, 0)})
    expected += spring_force(c, corner, 100.0, L0);
  LAB_EXPECT_FORCE(force_on(cloth, 1, 1), expected, force_tolerance(4, 100.0, 1.5),
                   tr("Q8, shear springs: the centre s(1, 1), moved off its place, should be held "
                      "by its four diagonal springs to s(ku+-1, kv+-1) (rest length h sqrt 2). "
                      "Without them the cloth collapses along its diagonals"),
                   reversed(tr("shear springs"), tr("the centre s(1, 1), moved off its place,")));
  LAB_EXPECT_FORCE(force_on(cloth, 0, 0), spring_force(glm::dvec3(-1, -1, 0), c, 100.0, L0),
                   force_tolerance(1, 100.0, 1.5),
                   tr("Q8, shear springs: the corner s(0, 0) should feel its one diagonal spring, "
                      "to s(1, 1)"),
                   reversed(tr("shear springs"), tr("the corner s(0, 0)")));
}

// Bending only, K_bend = 7, 3 x 3, S = 2: lift s(2, 0) = (1, -1, 0) to (1, -1, 1). Its bending
// springs go two vertices away, to s(0, 0) = (-1, -1, 0) and s(2, 2) = (1, 1, 0): d = (2, 0, 1)
// and (0, -2, 1), both of length sqrt 5 and rest length 2:
//   F = 7 (2 - sqrt 5) / sqrt 5 (2, -2, 2).
TEST(Q8ComputeForce, BendingSpringsSkipOneVertex) {
  spring_mesh cloth = cloth_with(3, 2.0, 0.0, 0.0, 7.0);
  move(cloth, 2, 0, {1, -1, 1});
  cloth.compute_force();
  const double scale = 7.0 * (2 - std::sqrt(5.0)) / std::sqrt(5.0);
  LAB_EXPECT_FORCE(force_on(cloth, 2, 0), scale * glm::dvec3(2, -2, 2),
                   force_tolerance(2, 7.0, 1.5),
                   tr("Q8, bending springs: s(2, 0), lifted out of the plane, should be pulled "
                      "back by its bending springs to s(ku-2, kv) and s(ku, kv+2) (rest length "
                      "2h). Without them the cloth folds with no resistance, like paper"),
                   reversed(tr("bending springs"), tr("s(2, 0), lifted out of the plane,")));
  LAB_EXPECT_FORCE(force_on(cloth, 0, 0), spring_force({-1, -1, 0}, {1, -1, 1}, 7.0, 2.0),
                   force_tolerance(2, 7.0, 1.5),
                   tr("Q8, bending springs: s(0, 0) should feel the bending spring to "
                      "s(ku+2, kv)"),
                   reversed(tr("bending springs"), "s(0, 0)"));
}

// A 2 x 2 cloth, S = 1 (h = 1), all three families with different stiffnesses: lift s(1, 1) by
// 0.5. Its structural springs to s(0, 1) and s(1, 0) (rest 1) and its shear spring to s(0, 0)
// (rest sqrt 2) must each use their own family's stiffness.
TEST(Q8ComputeForce, EachFamilyUsesItsOwnStiffness) {
  spring_mesh cloth = cloth_with(2, 1.0, 300.0, 70.0, 11.0);
  const glm::dvec3 p = position_of(cloth, 1, 1) + glm::dvec3(0, 0, 0.5);
  move(cloth, 1, 1, p);
  cloth.compute_force();
  const glm::dvec3 structural = spring_force(p, position_of(cloth, 0, 1), 300.0, 1.0) +
                                spring_force(p, position_of(cloth, 1, 0), 300.0, 1.0);
  const glm::dvec3 shear = spring_force(p, position_of(cloth, 0, 0), 70.0, std::sqrt(2.0));
  const double tolerance = force_tolerance(3, 300.0, 1.0);
  const std::string family = lab::reversed_part(
      force_on(cloth, 1, 1), structural + shear,
      {{tr("structural springs"), structural}, {tr("shear springs"), shear}}, tolerance);
  LAB_EXPECT_FORCE(force_on(cloth, 1, 1), structural + shear, tolerance,
                   family.empty() ? tr("Q8: with K_struct = 300 and K_shear = 70, s(1, 1) lifted "
                                       "by 0.5 m should feel two structural springs with "
                                       "K_struct and one shear spring with K_shear")
                                  : reversed(family, tr("s(1, 1), lifted by 0.5 m,")),
                   reversed(tr("every family"), tr("s(1, 1), lifted by 0.5 m,")));
}

// A corner has only the neighbours inside the grid: on a 4 x 4 cloth (S = 3, h = 1) with every
// vertex moved, s(0, 0) feels structural s(1, 0), s(0, 1); shear s(1, 1); bending s(2, 0), s(0, 2).
TEST(Q8ComputeForce, ACornerFeelsOnlyTheSpringsInsideTheGrid) {
  spring_mesh cloth = cloth_with(4, 3.0, 40.0, 30.0, 20.0);
  for (int kv = 0; kv < 4; ++kv)
    for (int ku = 0; ku < 4; ++ku)
      move(cloth, ku, kv,
           position_of(cloth, ku, kv) +
               0.1 * glm::dvec3(std::sin(ku + 2.0 * kv), std::cos(3.0 * ku - kv), ku * kv % 3));
  cloth.compute_force();
  const glm::dvec3 p = position_of(cloth, 0, 0);
  const glm::dvec3 structural = spring_force(p, position_of(cloth, 1, 0), 40.0, 1.0) +
                                spring_force(p, position_of(cloth, 0, 1), 40.0, 1.0);
  const glm::dvec3 shear = spring_force(p, position_of(cloth, 1, 1), 30.0, std::sqrt(2.0));
  const glm::dvec3 bending = spring_force(p, position_of(cloth, 2, 0), 20.0, 2.0) +
                             spring_force(p, position_of(cloth, 0, 2), 20.0, 2.0);
  const glm::dvec3 expected = structural + shear + bending;
  const double tolerance = force_tolerance(5, 40.0, 2.5);
  const std::string family = lab::reversed_part(force_on(cloth, 0, 0), expected,
                                                {{tr("structural springs"), structural},
                                                 {tr("shear springs"), shear},
                                                 {tr("bending springs"), bending}},
                                                tolerance);
  LAB_EXPECT_FORCE(force_on(cloth, 0, 0), expected, tolerance,
                   family.empty()
                       ? tr("Q8: the corner s(0, 0) has five springs: structural to s(1, 0) and "
                            "s(0, 1), shear to s(1, 1), bending to s(2, 0) and s(0, 2); "
                            "neighbours outside the grid (ku < 0, kv < 0) have none")
                       : reversed(family, tr("the corner s(0, 0)")),
                   reversed(tr("every family"), tr("the corner s(0, 0)")));
}

// Spring forces come in opposite pairs along the line of their two vertices: on any shape their
// sum and their total torque are zero. A deformed 5 x 5 cloth, every family on.
TEST(Q8ComputeForce, SpringForcesSumToZeroAndExertNoTorque) {
  spring_mesh cloth = cloth_with(5, 1.0, 500.0, 200.0, 50.0);
  for (int kv = 0; kv < 5; ++kv)
    for (int ku = 0; ku < 5; ++ku)
      move(cloth, ku, kv,
           position_of(cloth, ku, kv) +
               0.05 * glm::dvec3(std::cos(ku * kv), std::sin(ku + 3.0 * kv), ku - kv));
  cloth.compute_force();
  glm::dvec3 sum(0.0), torque(0.0), largest(0.0);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    const glm::dvec3 f = cloth.particles().get_force(k);
    sum += f;
    torque += glm::cross(cloth.particles().get_position(k), f);
    largest = glm::max(largest, glm::abs(f));
  }
  LAB_EXPECT_TRUE(largest.x + largest.y + largest.z > 1.0,
                  tr("Q8: a deformed cloth with stiff springs should feel spring forces"));
  // Tolerance: the rounding of every spring force at both of its ends (80 structural ends of
  // K = 500, 64 shear ends of K = 200, 60 bending ends of K = 50; positions of size 1).
  const double tolerance = lab::rounding(80 * 500.0 + 64 * 200.0 + 60 * 50.0);
  LAB_EXPECT_VEC(sum, glm::dvec3(0.0), tolerance,
                 tr("Q8: the spring forces should sum to zero (each spring pulls its two ends "
                    "with opposite forces): is some spring counted on one end only, or twice?"));
  LAB_EXPECT_VEC(torque, glm::dvec3(0.0), tolerance,
                 tr("Q8: the spring forces should exert no total torque (each pair lies along its "
                    "spring)"));
}

// At rest, every spring at its rest length (h, h sqrt 2 or 2h): no force anywhere, corners,
// borders and inner vertices alike (a wrong rest length shows here). 5 x 5, every family on.
TEST(Q8ComputeForce, AClothAtRestFeelsNoSpringForce) {
  spring_mesh cloth = cloth_with(5, 1.0, 500.0, 200.0, 50.0);
  cloth.compute_force();
  // Tolerance: the rounding of 12 springs of K = 500 at most, positions of size 1 (a rest
  // length written out, h sqrt 2, differs from the measured one by that rounding only).
  LAB_EXPECT_EVERY_VEC(k, 5 * 5, force_on(cloth, int(k % 5), int(k / 5)), glm::dvec3(0.0),
                       force_tolerance(12, 500.0, 1.0),
                       format(tr("Q8: on the flat cloth at rest every spring has its rest length "
                                 "(h for a structural spring, h sqrt 2 for a shear one, 2h for a "
                                 "bending one): s(%d, %d) should feel no spring force"),
                              int(k % 5), int(k / 5)));
}

}  // namespace
}  // namespace clothlab
