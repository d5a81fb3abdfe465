#include "framing.hpp"

#include "render_geometry.hpp"  // chain_floor_height

namespace clothlab {

camera chain_view(const coupled_springs& chain) {
  const glm::vec3 top = chain.particles().get_position(0);
  const coupled_springs_parameters& p = chain.parameters;
  const float bottom =
      chain_floor_height(top.z, chain.springs(), p.dynamics.mass, p.dynamics.gravity, p.stiffness);
  return camera::framing(stage_kind::coupled, top.x, top.y, bottom, top.z + 0.2f);
}

}  // namespace clothlab
