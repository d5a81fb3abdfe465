#include "force_model.hpp"

#include <algorithm>

namespace clothlab {

void evaluate_forces(const force_model& forces, std::span<const double> position,
                     std::span<double> force) {
  forces.compute(position, force);
}

void compute_spring_forces(std::span<const spring_set> sets, std::span<const double> position,
                           std::span<double> force) {
  std::fill(force.begin(), force.end(), 0.0);
  for (const spring_set& set : sets)
    accumulate_spring_forces(set.springs, set.stiffness, position, force);
}

}  // namespace clothlab
