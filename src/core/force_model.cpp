#include "force_model.hpp"

#include <algorithm>

namespace clothlab {

void evaluate_forces(const force_model& forces, std::span<const double> position,
                     std::span<double> force) {
  std::fill(force.begin(), force.end(), 0.0);
  for (const spring_set& set : forces.spring_sets)
    accumulate_spring_forces(set.springs, set.stiffness, position, force);
  if (forces.add_other_forces)
    forces.add_other_forces(position, force);
}

}  // namespace clothlab
