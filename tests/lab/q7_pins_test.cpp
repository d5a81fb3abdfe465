// Question 7: two corners of the cloth are pinned (handout: "Fixez deux sommets des coins du
// tissu", any two of the four). An answer may mark them in load_model (particles_.is_fixed) or
// leave them out in apply_force, as the handout's section 4.3 suggests ("il suffit de ne jamais
// mettre a jour ses coordonnees"): load_model marks as fixed every vertex that apply_force never
// moves, so is_fixed names the pins either way. With --pins none, nothing is pinned.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::spring_mesh;

// "s(5, 0)"
std::string vertex(std::size_t k, int n) {
  return "s(" + std::to_string(k % std::size_t(n)) + ", " + std::to_string(k / std::size_t(n)) +
         ")";
}

bool is_corner(std::size_t k, int n) {
  const std::size_t ku = k % std::size_t(n), kv = k / std::size_t(n), last = std::size_t(n - 1);
  return (ku == 0 || ku == last) && (kv == 0 || kv == last);
}

std::vector<std::size_t> pinned_vertices(const spring_mesh& cloth) {
  std::vector<std::size_t> pinned;
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    if (cloth.particles().is_fixed[k])
      pinned.push_back(k);
  return pinned;
}

// At two grid sizes (an index written for one N only is not a corner at the other): exactly two
// vertices are pinned, and both are corners.
TEST(Q7Pins, TwoCornersArePinned) {
  for (const int n : {6, 3}) {
    cloth_parameters p;
    p.grid_size = n;
    const spring_mesh cloth(p);
    const std::vector<std::size_t> pinned = pinned_vertices(cloth);
    const std::string corners =
        format(tr("s(0, 0), s(N-1, 0), s(0, N-1) and s(N-1, N-1), indices 0, %d, %d and %d for "
                  "N = %d"),
               n - 1, n * (n - 1), n * n - 1, n);
    std::string names;
    for (std::size_t k : pinned)
      names += (names.empty() ? "" : ", ") + vertex(k, n);
    LAB_EXPECT_TRUE(!pinned.empty(),
                    format(tr("Q7: no vertex of the cloth is pinned (N = %d): fix two of its "
                              "corners, %s (mark them in particles_.is_fixed in load_model, or "
                              "never update them in apply_force)"),
                           n, corners.c_str()));
    if (pinned.empty())
      continue;
    std::size_t not_corner = pinned.size();
    for (std::size_t i = 0; i < pinned.size(); ++i)
      if (!is_corner(pinned[i], n) && not_corner == pinned.size())
        not_corner = i;
    LAB_EXPECT_TRUE(
        not_corner == pinned.size(),
        format(tr("Q7: the pinned vertex %s is not a corner of the N = %d cloth; its "
                  "corners are %s (k = ku + N kv)"),
               (not_corner < pinned.size() ? vertex(pinned[not_corner], n) : "").c_str(), n,
               corners.c_str()));
    LAB_EXPECT_TRUE(pinned.size() == 2,
                    format(tr("Q7: pin exactly two corners of the cloth; at N = %d, %zu vertices "
                              "are: %s"),
                           n, pinned.size(), names.c_str()));
  }
}

// The pinned corners stay where they were, exactly, with a zero velocity, while the cloth hangs
// and swings for 200 steps.
TEST(Q7Pins, PinnedCornersStayExactlyInPlaceWhileTheClothHangs) {
  cloth_parameters p;
  p.grid_size = 5;
  spring_mesh cloth(p);
  const std::vector<std::size_t> pinned = pinned_vertices(cloth);
  LAB_ASSERT_TRUE(!pinned.empty(), tr("Q7: no vertex of the cloth is pinned: fix two corners"));
  std::vector<glm::dvec3> start;
  for (std::size_t k : pinned)
    start.push_back(cloth.particles().get_position(k));
  for (int s = 0; s < 200; ++s)
    cloth.step();
  for (std::size_t i = 0; i < pinned.size(); ++i) {
    LAB_EXPECT_VEC(cloth.particles().get_position(pinned[i]), start[i], 0.0,
                   format(tr("Q7: the pinned corner %s moved while the cloth hangs (200 steps)"),
                          vertex(pinned[i], 5).c_str()));
    LAB_EXPECT_VEC(
        cloth.particles().get_velocity(pinned[i]), glm::dvec3(0.0), 0.0,
        format(tr("Q7: the pinned corner %s keeps a zero speed"), vertex(pinned[i], 5).c_str()));
  }
}

TEST(Q7Pins, PinsNoneLeavesEveryVertexFree) {
  cloth_parameters p;
  p.grid_size = 4;
  p.pins = pin_mode::none;
  spring_mesh cloth(p);
  for (std::size_t k = 0; k < cloth.particles().size(); ++k)
    LAB_EXPECT_TRUE(!cloth.particles().is_fixed[k],
                    format(tr("Q7: with --pins none (parameters.pins == pin_mode::none) no vertex "
                              "is pinned; %s is (marked in is_fixed, or never moved by "
                              "apply_force)"),
                           vertex(k, 4).c_str()));
}

}  // namespace
}  // namespace clothlab
