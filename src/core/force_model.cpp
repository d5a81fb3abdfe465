#include "core/force_model.hpp"

namespace clothlab {

void evaluate_forces(const force_model& forces, std::span<const double> position,
                     std::span<double> force) {
  forces.compute(position, force);
}

void add_mass_drag_force(const mass_drag_parameters& drag, std::span<const std::uint8_t> is_fixed,
                         std::span<const double> position, std::span<double> force) {
  if (!drag.enabled || drag.mass < 0 || static_cast<std::size_t>(drag.mass) >= is_fixed.size())
    return;
  const auto k = static_cast<std::size_t>(drag.mass);
  if (is_fixed[k])
    return;
  for (std::size_t c = 0; c < 3; ++c) {
    const double q = drag.target[static_cast<glm::length_t>(c)];
    force[3 * k + c] += drag.stiffness * (q - position[3 * k + c]);  // K_d (q - p_k)
  }
}

}  // namespace clothlab
