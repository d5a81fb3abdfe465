// The renderer's CPU-side geometry and the orbit camera, checked against hand computations
// (no GL context needed).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <vector>

#include "core/coupled_springs.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"
#include "gl/camera.hpp"
#include "gl/render_geometry.hpp"

namespace clothlab {
namespace {

glm::vec3 point(const std::vector<float>& xyz, std::size_t i) {
  return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
}

TEST(SphereMesh, VerticesAreOnTheUnitSphereAndTrianglesFaceOutwards) {
  const sphere_mesh sphere = make_unit_sphere(8, 6);
  EXPECT_EQ(sphere.vertices.size(), 3u * 9 * 7);
  EXPECT_EQ(sphere.indices.size(), 3u * 2 * 8 * 6);
  for (std::size_t i = 0; i < sphere.vertices.size() / 3; ++i) {
    EXPECT_NEAR(glm::length(point(sphere.vertices, i)), 1.0f, 1e-6f);
  }
  for (std::size_t t = 0; t < sphere.indices.size(); t += 3) {
    const glm::vec3 a = point(sphere.vertices, sphere.indices[t]);
    const glm::vec3 b = point(sphere.vertices, sphere.indices[t + 1]);
    const glm::vec3 c = point(sphere.vertices, sphere.indices[t + 2]);
    const glm::vec3 face_normal = glm::cross(b - a, c - a);
    if (glm::length(face_normal) < 1e-7f)
      continue;  // degenerate at the poles
    // Counter-clockwise from outside: the face normal points away from the centre.
    EXPECT_GT(glm::dot(face_normal, a + b + c), 0.0f) << "triangle " << t / 3;
  }
}

TEST(Coil, RunsFromOneEndToTheOtherWithinItsRadius) {
  const glm::vec3 a = {0.1f, 0.0f, 1.0f};
  const glm::vec3 b = {0.4f, -0.2f, 0.2f};
  const coil_shape coil;
  std::vector<float> points;
  append_coil(a, b, coil, points);
  ASSERT_EQ(points.size(), 3u * static_cast<std::size_t>(coil.vertex_count()));
  EXPECT_EQ(point(points, 0), a);
  EXPECT_EQ(point(points, points.size() / 3 - 1), b);
  const glm::vec3 axis = glm::normalize(b - a);
  for (std::size_t i = 0; i < points.size() / 3; ++i) {
    const glm::vec3 p = point(points, i) - a;
    const float distance_from_axis = glm::length(p - glm::dot(p, axis) * axis);
    EXPECT_LE(distance_from_axis, coil.radius + 1e-5f);
  }
}

TEST(ClothIndices, CountsAndWindingOfA3x3Grid) {
  cloth_parameters parameters;
  parameters.grid_size = 3;
  const spring_mesh cloth(parameters);
  const cloth_indices result = make_cloth_indices(cloth);
  // 2 x 2 cells, 2 triangles each.
  EXPECT_EQ(result.triangles.count, 3u * 8);
  // 6 edges along u, 6 along v, 4 diagonals; each a pair of indices.
  EXPECT_EQ(result.edges.count, 2u * 16);
  EXPECT_EQ(result.springs[0].count, 2u * 12);  // structural
  EXPECT_EQ(result.springs[1].count, 2u * 8);   // shear
  EXPECT_EQ(result.springs[2].count, 2u * 6);   // bending
  EXPECT_EQ(result.indices.size(), result.springs[2].first + result.springs[2].count);
  // Every triangle of the flat cloth is counter-clockwise seen from +z, where its normal points.
  const auto& p = cloth.particles();
  for (std::uint32_t t = 0; t < result.triangles.count; t += 3) {
    const glm::dvec3 a = p.get_position(result.indices[t]);
    const glm::dvec3 b = p.get_position(result.indices[t + 1]);
    const glm::dvec3 c = p.get_position(result.indices[t + 2]);
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0);
  }
}

TEST(GridCoordinates, CornersOfTheTextureAndTexelsFollowKuAndKv) {
  const auto uv = make_grid_texture_coordinates(3);
  const auto texels = make_grid_texels(3);
  ASSERT_EQ(uv.size(), 18u);
  ASSERT_EQ(texels.size(), 18u);
  // Particle k = ku + 3 kv = 5 is (ku, kv) = (2, 1): (u, v) = (1, 0.5).
  EXPECT_FLOAT_EQ(uv[2 * 5], 1.0f);
  EXPECT_FLOAT_EQ(uv[2 * 5 + 1], 0.5f);
  EXPECT_EQ(texels[2 * 5], 2);
  EXPECT_EQ(texels[2 * 5 + 1], 1);
}

TEST(ChainFloor, SingleSpringByHand) {
  // L0 = 0.5, static stretch m g / K = 9.8 / 20 = 0.49: floor at 1 - (0.5 + 2 * 0.49 + 0.3).
  const single_spring stage;
  EXPECT_NEAR(chain_floor_height(1.0f, stage.springs(), 1.0, 9.8, 20.0), -0.78f, 1e-5f);
}

TEST(ChainFloor, TwoMassesByHand) {
  // The top spring carries two masses, the lower one: stretch (2 + 1) 9.8 / 20 = 1.47.
  const coupled_springs stage;
  EXPECT_NEAR(chain_floor_height(1.0f, stage.springs(), 1.0, 9.8, 20.0),
              1.0f - (1.0f + 2.0f * 1.47f + 0.3f), 1e-5f);
}

TEST(Camera, EyeIsAtDistanceFromTargetAndLooksAtIt) {
  camera view;
  view.target = {1.0f, 2.0f, 3.0f};
  view.distance = 4.0f;
  view.yaw = 0.0f;
  view.pitch = 0.0f;
  EXPECT_NEAR(glm::length(view.eye() - glm::vec3(5.0f, 2.0f, 3.0f)), 0.0f, 1e-6f);
  // The target is straight ahead: on the view's -z axis at the camera's distance.
  const glm::vec4 target_in_view = view.view() * glm::vec4(view.target, 1.0f);
  EXPECT_NEAR(target_in_view.x, 0.0f, 1e-5f);
  EXPECT_NEAR(target_in_view.y, 0.0f, 1e-5f);
  EXPECT_NEAR(target_in_view.z, -4.0f, 1e-5f);
  // z is up: a point above the target is above the screen's centre.
  const glm::vec4 above = view.view() * glm::vec4(view.target + glm::vec3(0, 0, 1), 1.0f);
  EXPECT_GT(above.y, 0.5f);
}

TEST(Camera, PitchAndDistanceAreClamped) {
  camera view;
  view.orbit(0.2f, 10.0f);
  EXPECT_FLOAT_EQ(view.pitch, 1.5f);
  view.orbit(0.0f, -20.0f);
  EXPECT_FLOAT_EQ(view.pitch, -1.5f);
  view.zoom(1000.0f);
  EXPECT_FLOAT_EQ(view.distance, 50.0f);
  view.zoom(1e-6f);
  EXPECT_FLOAT_EQ(view.distance, 0.2f);
}

TEST(Camera, PanMovesTheTargetSidewaysInTheScreen) {
  camera view;
  view.yaw = 0.0f;
  view.pitch = 0.0f;
  view.distance = 2.0f;
  const glm::vec3 before = view.target;
  view.pan(0.5f, 0.0f);
  // Looking along -x with z up, the screen's right is forward x up = +y; 0.5 distance = 1 m.
  const glm::vec3 moved = view.target - before;
  EXPECT_NEAR(moved.y, 1.0f, 1e-5f);
  EXPECT_NEAR(moved.x, 0.0f, 1e-5f);
  EXPECT_NEAR(moved.z, 0.0f, 1e-5f);
}

// Every position the stage takes in its first seconds lands inside the 4:3 default view.
template <typename Stage>
void expect_framed(Stage& stage, stage_kind kind, int steps, float margin) {
  const camera view = camera::default_for(kind);
  const glm::mat4 view_projection = view.projection(4.0f / 3.0f) * view.view();
  for (int s = 0; s <= steps; ++s) {
    const auto& p = stage.particles();
    for (std::size_t k = 0; k < p.size(); ++k) {
      const glm::vec4 clip = view_projection * glm::vec4(glm::vec3(p.get_position(k)), 1.0f);
      ASSERT_GT(clip.w, 0.0f);
      EXPECT_LT(std::abs(clip.x / clip.w), 1.0f - margin) << "step " << s << " particle " << k;
      EXPECT_LT(std::abs(clip.y / clip.w), 1.0f - margin) << "step " << s << " particle " << k;
      if (::testing::Test::HasFailure())
        return;  // the first particle out of the view says it (the rest would only repeat it)
    }
    stage.step();
  }
}

TEST(DefaultCamera, FramesTheSingleSpring) {
  single_spring stage;
  expect_framed(stage, stage_kind::spring, 500, 0.05f);
}

TEST(SolutionDefaultCamera, FramesTheDefaultChain) {
  coupled_springs stage;
  expect_framed(stage, stage_kind::coupled, 500, 0.05f);
}

// The cloth hanging from s(0, 0) and s(N-1, 0), the corners of the documents' pictures, whichever
// two question 7 pins: the test pins these itself (apply_force never moves a fixed vertex).
TEST(SolutionDefaultCamera, FramesTheFallingCloth) {
  cloth_parameters parameters;
  parameters.pins = pin_mode::none;
  spring_mesh cloth(parameters);
  const int n = cloth.grid_size();
  cloth.particles().is_fixed[spring_mesh::index(0, 0, n)] = 1;
  cloth.particles().is_fixed[spring_mesh::index(n - 1, 0, n)] = 1;
  expect_framed(cloth, stage_kind::cloth, 1500, 0.02f);
}

}  // namespace
}  // namespace clothlab
