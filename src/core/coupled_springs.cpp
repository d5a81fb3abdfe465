#include "coupled_springs.hpp"

#include <algorithm>

#include "integrator.hpp"

namespace clothlab {

coupled_springs::coupled_springs(const coupled_springs_parameters& p) : parameters(p) {
  load_model();
}

void coupled_springs::load_model() {
  const int n = std::max(parameters.mass_count, 1);
  const glm::dvec3 p0 = {0.1, 0.0, 1.0};     // fixed top
  const glm::dvec3 link = {0.0, 0.0, -0.5};  // initial offset between neighbours
  particles_.resize(static_cast<std::size_t>(n) + 1);
  particles_.is_fixed[0] = 1;
  springs_.clear();
  for (int i = 0; i <= n; ++i) {
    particles_.set_position(i, p0 + double(i) * link);
    if (i > 0) {
      const auto a = static_cast<std::uint32_t>(i - 1);
      const auto b = static_cast<std::uint32_t>(i);
      springs_.push_back({a, b, glm::length(link)});
    }
  }
  particles_.set_velocity(static_cast<std::size_t>(n), {1.0, -1.0, 0.0});  // the last mass
}

void coupled_springs::compute_force() {
  const spring_set sets[] = {{springs_, parameters.stiffness}};
  evaluate_forces({sets, {}}, particles_.position, particles_.force);
}

void coupled_springs::apply_force() {
  const spring_set sets[] = {{springs_, parameters.stiffness}};
  integrator_.step(parameters.dynamics, {sets, {}}, particles_);
}

}  // namespace clothlab
