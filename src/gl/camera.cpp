#include "gl/camera.hpp"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace clothlab {
namespace {

constexpr float max_pitch = 1.5f;     // rad: never straight above or below (lookAt needs it)
constexpr float min_distance = 0.2f;  // m
constexpr float max_distance = 50.0f;
// The near and far planes: 0.05 m and 200 m around the lab's scenes (a few metres away); for a
// view from farther than 50 m (a long soft chain, framed whole: 50 masses at K = 20 N/m hang
// over a kilometre), a thousandth and four times the distance.
constexpr float near_plane = 0.05f;  // m
constexpr float far_plane = 200.0f;  // m
const glm::vec3 up = {0.0f, 0.0f, 1.0f};

}  // namespace

camera camera::default_for(stage_kind stage) {
  camera view;
  switch (stage) {
    case stage_kind::spring:
      // p0 = (0.1, 0, 1); the mass swings around z = 0 (its rest position is 0.99 m below p0).
      view.target = {0.1f, 0.0f, 0.1f};
      view.distance = 2.9f;
      view.yaw = 0.9f;
      view.pitch = 0.22f;
      break;
    case stage_kind::coupled:
      // The default chain of two masses hangs from z = 1 to about z = -1.5 at rest; released at
      // the springs' rest lengths, its lower mass first bounces down to about z = -3.
      view.target = {0.1f, 0.0f, -0.95f};
      view.distance = 5.6f;
      view.yaw = 0.9f;
      view.pitch = 0.2f;
      break;
    case stage_kind::cloth:
      // The 1 m cloth, pinned at (+-0.5, -0.5, 0), swings down towards the ground z = -1.
      view.target = {0.0f, -0.35f, -0.45f};
      view.distance = 2.8f;
      view.yaw = 0.8f;
      view.pitch = 0.32f;
      break;
  }
  return view;
}

camera camera::framing(stage_kind stage, float x, float y, float bottom, float top) {
  camera view = default_for(stage);
  const float extent = std::max(top - bottom, 0.0f);
  // Seen from the side, an extent e fills the view's height at distance (e / 2) / tan(fov / 2).
  const float needed = extent / 2.0f / 0.75f / std::tan(view.field_of_view / 2.0f);
  if (needed > view.distance) {
    view.distance = needed;
    view.target = {x, y, (top + bottom) / 2.0f};
  }
  return view;
}

glm::vec3 camera::eye() const {
  const glm::vec3 direction = {std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                               std::sin(pitch)};
  return target + distance * direction;
}

glm::mat4 camera::view() const {
  return glm::lookAt(eye(), target, up);
}

glm::mat4 camera::projection(float aspect) const {
  return glm::perspective(field_of_view, aspect > 0.0f ? aspect : 1.0f,
                          std::max(near_plane, 0.001f * distance),
                          std::max(far_plane, 4.0f * distance));
}

float camera::metres_per_pixel(float height) const {
  return 2.0f * distance * std::tan(field_of_view / 2.0f) / std::max(height, 1.0f);
}

void camera::orbit(float delta_yaw, float delta_pitch) {
  yaw += delta_yaw;
  pitch = std::clamp(pitch + delta_pitch, -max_pitch, max_pitch);
}

void camera::zoom(float factor) {
  if (!(factor > 0.0f))
    return;
  // (a framed view may be farther than max_distance: the wheel does not push it farther)
  distance = std::clamp(distance * factor, min_distance, std::max(max_distance, distance));
}

void camera::pan(float dx, float dy) {
  const glm::vec3 forward = glm::normalize(target - eye());
  const glm::vec3 right = glm::normalize(glm::cross(forward, up));
  const glm::vec3 screen_up = glm::cross(right, forward);
  target += distance * (dx * right + dy * screen_up);
}

}  // namespace clothlab
