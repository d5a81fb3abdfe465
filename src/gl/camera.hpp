// An orbit camera: it looks at a target from a distance, turned by yaw (around z, which is up)
// and pitch (above the horizontal). No GL here: matrices only.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/parameters.hpp"  // stage_kind

namespace clothlab {

struct camera {
  glm::vec3 target = {0.0f, 0.0f, -0.3f};  // m, the point looked at
  float distance = 3.0f;                   // m, from target to eye
  float yaw = -0.6f;                       // rad, around z
  float pitch = 0.35f;                     // rad, above the horizontal (clamped to +-1.5)
  float field_of_view = 0.8f;              // rad, vertical

  static camera default_for(stage_kind stage);  // the fixed view of --png and the reset-view key
  // default_for(stage), moved back (never closer, however far) and re-centred so that the
  // vertical extent from bottom to top (z, m) at (x, y) fills at most 75 % of the view's height.
  static camera framing(stage_kind stage, float x, float y, float bottom, float top);

  glm::vec3 eye() const;
  glm::mat4 view() const;
  // aspect = width / height. The near and far planes follow the distance, so that a long chain
  // framed from a kilometre away is inside them.
  glm::mat4 projection(float aspect) const;
  // The side of a pixel at the target's distance, m, in a view `height` pixels high.
  float metres_per_pixel(float height) const;

  void orbit(float delta_yaw, float delta_pitch);  // left mouse drag
  void zoom(float factor);  // wheel: distance *= factor, kept in [0.2, 50] (or the framed distance)
  void pan(float dx, float dy);  // right mouse drag, in units of distance
};

}  // namespace clothlab
