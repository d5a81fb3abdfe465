// The view of stage 2 (src/window/framing.hpp) takes in the whole chain, however long: its top,
// its masses at rest and at their lowest swing are inside the view and between its near and far
// planes, and a mass is drawn at least a few pixels wide.
#include <gtest/gtest.h>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <vector>

#include "core/coupled_springs.hpp"
#include "gl/render_geometry.hpp"
#include "window/framing.hpp"

namespace clothlab {
namespace {

// The scene's part of the 1280 x 800 window, right of the panel.
constexpr float width = 870.0f, height = 800.0f;

// Expects the point inside the view (normalised device coordinates within the frame and the
// depth range).
void expect_in_view(const camera& view, const glm::dvec3& point, const char* what, int n) {
  const glm::mat4 view_projection = view.projection(width / height) * view.view();
  const glm::vec4 clip = view_projection * glm::vec4(glm::vec3(point), 1.0f);
  ASSERT_GT(clip.w, 0.0f) << what << ", n = " << n << ": behind the eye";
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  EXPECT_LE(std::abs(ndc.x), 0.98f) << what << ", n = " << n << " (x)";
  EXPECT_LE(std::abs(ndc.y), 0.98f) << what << ", n = " << n << " (y)";
  EXPECT_LT(std::abs(ndc.z), 1.0f) << what << ", n = " << n << ": beyond the near or far plane";
}

void expect_chain_framed(int n, double damping) {
  coupled_springs_parameters p;
  p.mass_count = n;
  p.dynamics.damping = damping;
  const coupled_springs chain(p);
  const camera view = chain_view(chain);
  const glm::dvec3 top = chain.particles().get_position(0);
  expect_in_view(view, top, "the fixed top p0", n);
  // Mass i at rest: every spring above it stretched by the weight it carries; at its lowest
  // swing (released at the rest lengths), twice that.
  const double stretch_per_mass = p.dynamics.mass * p.dynamics.gravity / p.stiffness;
  double rest = top.z, lowest = top.z;
  for (int i = 1; i <= n; ++i) {
    const double stretch = (n - i + 1) * stretch_per_mass;
    rest -= 0.5 + stretch;
    lowest -= 0.5 + 2 * stretch;
  }
  expect_in_view(view, {top.x, top.y, rest}, "the last mass at rest", n);
  expect_in_view(view, {top.x, top.y, lowest}, "the last mass at its lowest swing", n);
  // A mass is drawn (and picked) at least min_mass_pixels pixels in radius.
  const float metres_per_pixel = view.metres_per_pixel(height);
  EXPECT_GE(drawn_mass_radius(chain_mass_radius, metres_per_pixel) / metres_per_pixel,
            min_mass_pixels - 1e-4f)
      << "n = " << n;
}

TEST(ChainView, TakesInTheWholeChainHoweverLong) {
  expect_chain_framed(2, 0.2);   // the default: 2.5 m
  expect_chain_framed(10, 0.2);  // masses smaller than a pixel before
  expect_chain_framed(20, 2.0);  // at rest over 100 m long
  expect_chain_framed(50, 0.2);  // over a kilometre at its lowest swing
}

TEST(ChainView, TheDefaultChainsMassesKeepTheirSize) {
  const camera view = chain_view(coupled_springs(coupled_springs_parameters{}));
  EXPECT_EQ(drawn_mass_radius(chain_mass_radius, view.metres_per_pixel(height)), chain_mass_radius);
}

// A cloth that falls freely (the student's copy before questions 6 to 9) leaves the view from
// below; a cloth in view, or one the camera turned away from, has not fallen out of it.
TEST(FellBelowView, AFallingClothLeavesTheViewFromBelow) {
  const camera view = camera::default_for(stage_kind::cloth);
  std::vector<double> cloth;  // a flat 1 m cloth at z = 0, 11 x 11 points
  for (int kv = 0; kv <= 10; ++kv) {
    for (int ku = 0; ku <= 10; ++ku)
      cloth.insert(cloth.end(), {-0.5 + 0.1 * ku, -0.5 + 0.1 * kv, 0.0});
  }
  const float aspect = width / height;
  EXPECT_FALSE(fell_below_view(view, aspect, cloth));
  std::vector<double> fallen = cloth;
  for (std::size_t i = 2; i < fallen.size(); i += 3)
    fallen[i] -= 4.9;  // 1 s of free fall
  EXPECT_TRUE(fell_below_view(view, aspect, fallen));
  // Half-way out: still (partly) in view.
  std::vector<double> half = cloth;
  for (std::size_t i = 2; i < half.size() / 2; i += 3)
    half[i] -= 4.9;
  EXPECT_FALSE(fell_below_view(view, aspect, half));
  // The camera turned away (looking the other way): out of sight, but it did not fall.
  camera turned = view;
  turned.orbit(3.14159f, 0.0f);
  turned.target = view.target + 3.0f * (view.target - view.eye());
  EXPECT_FALSE(fell_below_view(turned, aspect, cloth));
  EXPECT_FALSE(fell_below_view(view, aspect, {}));
}

}  // namespace
}  // namespace clothlab
