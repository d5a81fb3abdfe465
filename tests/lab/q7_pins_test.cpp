// Question 7: spring_mesh::load_model pins two corners of the cloth, s(0, 0) and s(N-1, 0):
// their is_fixed flag is set, so that apply_force never moves them.
#include <gtest/gtest.h>

#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::spring_mesh;

TEST(Q7Pins, TheTwoCornersOfTheFirstRowArePinned) {
  cloth_parameters p;
  p.grid_size = 6;
  spring_mesh cloth(p);
  const auto& fixed = cloth.particles().is_fixed;
  LAB_EXPECT_TRUE(fixed[spring_mesh::index(0, 0, 6)],
                  "Q7: the corner s(0, 0) (index 0) should be fixed: is_fixed[0] = 1 in "
                  "load_model");
  LAB_EXPECT_TRUE(fixed[spring_mesh::index(5, 0, 6)],
                  "Q7: the corner s(N-1, 0) (index N-1 = 5 for N = 6) should be fixed");
}

TEST(Q7Pins, NoOtherVertexIsPinned) {
  cloth_parameters p;
  p.grid_size = 6;
  spring_mesh cloth(p);
  int pinned = 0;
  for (std::uint8_t f : cloth.particles().is_fixed)
    pinned += f != 0;
  LAB_EXPECT_TRUE(pinned == 2,
                  "Q7: exactly two vertices, the corners s(0, 0) and s(N-1, 0), are pinned by "
                  "default")
      << "; " << pinned << " are";
}

// The pinned corners stay where they were, exactly, while the cloth hangs and swings for 200
// steps (their velocity stays 0).
TEST(Q7Pins, PinnedCornersStayExactlyInPlaceWhileTheClothHangs) {
  cloth_parameters p;
  p.grid_size = 5;
  spring_mesh cloth(p);
  const glm::dvec3 corner_a = cloth.particles().get_position(0);
  const glm::dvec3 corner_b = cloth.particles().get_position(4);
  for (int s = 0; s < 200; ++s)
    cloth.step();
  LAB_EXPECT_VEC(cloth.particles().get_position(0), corner_a, 0.0,
                 "Q7: the pinned corner s(0, 0) moved while the cloth hangs");
  LAB_EXPECT_VEC(cloth.particles().get_position(4), corner_b, 0.0,
                 "Q7: the pinned corner s(N-1, 0) moved while the cloth hangs");
}

TEST(Q7Pins, PinsNoneLeavesEveryVertexFree) {
  cloth_parameters p;
  p.grid_size = 4;
  p.pins = pin_mode::none;
  spring_mesh cloth(p);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    LAB_EXPECT_TRUE(!cloth.particles().is_fixed[k],
                    "Q7: with --pins none no vertex is fixed; vertex " + std::to_string(k) + " is");
}

}  // namespace
}  // namespace clothlab
