// The mouse's geometry (src/window/picking.hpp) against hand computations on a flat cloth.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "core/coupled_springs.hpp"
#include "window/picking.hpp"

namespace clothlab {
namespace {

// The 3 x 3 cloth of side 1 m lies flat at z = 0: particle (ku, kv) at (-0.5 + 0.5 ku,
// -0.5 + 0.5 kv, 0), index ku + 3 kv.
spring_mesh flat_cloth() {
  cloth_parameters p;
  p.grid_size = 3;
  p.side_length = 1.0;
  spring_mesh cloth(p);
  cloth.load_model();
  return cloth;
}

pick_ray straight_down(double x, double y) {
  return {{x, y, 5.0}, {0.0, 0.0, -1.0}};
}

TEST(Picking, APressOnTheClothGrabsTheVertexNearestToWhereTheRayHitsIt) {
  const spring_mesh cloth = flat_cloth();
  // (0.1, 0.2) is in the cell of (0, 0), nearest to the centre particle (1, 1) = 4.
  EXPECT_EQ(pick_particle(cloth, straight_down(0.1, 0.2), 0.0), std::optional<std::size_t>(4));
  // (0.45, -0.4): nearest to the corner (2, 0) = 2.
  EXPECT_EQ(pick_particle(cloth, straight_down(0.45, -0.4), 0.0), std::optional<std::size_t>(2));
}

TEST(Picking, APressOffTheClothGrabsOnlyWithinTheAngle) {
  const spring_mesh cloth = flat_cloth();
  // (0.7, 0): 0.2 m beside particle (2, 1) = 5, seen from 5 m: atan(0.2 / 5) = 0.04 rad.
  EXPECT_EQ(pick_particle(cloth, straight_down(0.7, 0.0), 0.03), std::nullopt);
  EXPECT_EQ(pick_particle(cloth, straight_down(0.7, 0.0), 0.05), std::optional<std::size_t>(5));
}

TEST(Picking, ARayAwayFromTheClothGrabsNothing) {
  const spring_mesh cloth = flat_cloth();
  const pick_ray up = {{0.0, 0.0, 1.0}, {0.0, 0.0, 1.0}};  // the cloth is behind it
  EXPECT_EQ(pick_particle(cloth, up, 0.1), std::nullopt);
}

// The chain of two in its initial state: p0 = (0.1, 0, 1) (fixed), p1 = (0.1, 0, 0.5),
// p2 = (0.1, 0, 0). Masses drawn with radius 0.085 m, p0 with 0.045 m.
particle_system chain_of_two() {
  return coupled_springs{}.particles();
}
constexpr double mass_radius = 0.085, fixed_radius = 0.045;

TEST(PickingMasses, ARayThroughAMassSphereGrabsIt) {
  const particle_system chain = chain_of_two();
  // Along +y, 0.058 m from p1's centre (0.05 across, 0.03 up): inside its sphere.
  const pick_ray ray = {{0.15, -5.0, 0.53}, {0.0, 1.0, 0.0}};
  EXPECT_EQ(pick_mass(chain, ray, mass_radius, fixed_radius, 0.0), std::optional<std::size_t>(1));
}

TEST(PickingMasses, TheFirstSphereAlongTheRayWinsAndTheFixedPointIsSmaller) {
  const particle_system chain = chain_of_two();
  // Straight down through the chain's axis: p0's sphere comes first (the caller refuses it).
  EXPECT_EQ(pick_mass(chain, straight_down(0.1, 0.0), mass_radius, fixed_radius, 0.0),
            std::optional<std::size_t>(0));
  // 0.06 m beside the axis: outside p0's sphere (0.045), inside p1's (0.085), above p2's.
  EXPECT_EQ(pick_mass(chain, straight_down(0.16, 0.0), mass_radius, fixed_radius, 0.0),
            std::optional<std::size_t>(1));
}

TEST(PickingMasses, APressBesideTheMassesGrabsOnlyWithinTheAngle) {
  const particle_system chain = chain_of_two();
  // Along +y, 0.2 m beside p1 seen from 5 m: atan(0.2 / 5) = 0.04 rad (p0 and p2: 0.107 rad).
  const pick_ray ray = {{0.3, -5.0, 0.5}, {0.0, 1.0, 0.0}};
  EXPECT_EQ(pick_mass(chain, ray, mass_radius, fixed_radius, 0.03), std::nullopt);
  EXPECT_EQ(pick_mass(chain, ray, mass_radius, fixed_radius, 0.05), std::optional<std::size_t>(1));
  const pick_ray away = {{0.1, -5.0, 0.5}, {0.0, -1.0, 0.0}};  // the chain is behind it
  EXPECT_EQ(pick_mass(chain, away, mass_radius, fixed_radius, 0.1), std::nullopt);
}

TEST(Picking, TheTargetIsWhereTheRayMeetsTheCameraFacingPlane) {
  // From (0, 0, 5) along (0.6, 0, -0.8), the plane z = 1 is reached at t = 4 / 0.8 = 5.
  const pick_ray ray = {{0.0, 0.0, 5.0}, {0.6, 0.0, -0.8}};
  const glm::dvec3 q = point_on_plane(ray, {7.0, 3.0, 1.0}, {0.0, 0.0, 1.0});
  EXPECT_NEAR(q.x, 3.0, 1e-12);
  EXPECT_NEAR(q.y, 0.0, 1e-12);
  EXPECT_NEAR(q.z, 1.0, 1e-12);
}

TEST(Picking, TheRayThroughTheViewsCentreRunsFromTheEyeThroughTheTarget) {
  const camera view = camera::default_for(stage_kind::cloth);
  const pick_ray ray = ray_through(view, 1.5f, 0.0, 0.0);
  const glm::dvec3 along = viewing_direction(view);
  EXPECT_NEAR(glm::dot(ray.direction, along), 1.0, 1e-6);
  // The target lies on the ray: its distance from the ray is (almost) zero.
  const glm::dvec3 to_target = glm::dvec3(view.target) - ray.origin;
  EXPECT_NEAR(glm::length(to_target - glm::dot(to_target, ray.direction) * ray.direction), 0.0,
              1e-5);
}

}  // namespace
}  // namespace clothlab
