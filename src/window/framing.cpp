#include "window/framing.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "gl/render_geometry.hpp"  // chain_floor_height

namespace clothlab {

camera chain_view(const coupled_springs& chain) {
  const glm::vec3 top = chain.particles().get_position(0);
  const coupled_springs_parameters& p = chain.parameters;
  const float bottom =
      chain_floor_height(top.z, chain.springs(), p.dynamics.mass, p.dynamics.gravity, p.stiffness);
  return camera::framing(stage_kind::coupled, top.x, top.y, bottom, top.z + 0.2f);
}

bool fell_below_view(const camera& view, float aspect, std::span<const double> positions) {
  if (positions.size() < 3)
    return false;
  const glm::mat4 view_projection = view.projection(aspect) * view.view();
  for (std::size_t i = 0; i + 2 < positions.size(); i += 3) {
    const glm::vec4 clip = view_projection * glm::vec4(static_cast<float>(positions[i]),
                                                       static_cast<float>(positions[i + 1]),
                                                       static_cast<float>(positions[i + 2]), 1.0f);
    // Below the bottom edge: y / w < -1, in front of the eye.
    if (!(clip.w > 0.0f && clip.y < -clip.w))
      return false;
  }
  return true;
}

}  // namespace clothlab
