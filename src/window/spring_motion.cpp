#include "window/spring_motion.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace clothlab {
double damped_oscillator::position(double tau) const {
  const double gamma = damping / 2;
  if (omega_squared <= 0.0) {
    // No spring: x'' = forcing - mu x', a fall towards the terminal speed forcing / mu.
    if (damping <= 0.0)
      return x0 + v0 * tau + forcing * tau * tau / 2;
    const double terminal = forcing / damping;
    return x0 + terminal * tau + (v0 - terminal) * (1.0 - std::exp(-damping * tau)) / damping;
  }
  // y = x - x_eq solves y'' + mu y' + omega0^2 y = 0.
  const double equilibrium = forcing / omega_squared;
  const double y0 = x0 - equilibrium;
  const double discriminant = omega_squared - gamma * gamma;
  double y = 0.0;
  if (discriminant > 1e-12 * omega_squared) {  // under-damped: a decaying oscillation
    const double omega_d = std::sqrt(discriminant);
    y = std::exp(-gamma * tau) *
        (y0 * std::cos(omega_d * tau) + (v0 + gamma * y0) / omega_d * std::sin(omega_d * tau));
  } else if (discriminant < -1e-12 * omega_squared) {  // over-damped: two decaying exponentials
    const double s = std::sqrt(-discriminant);
    const double r1 = -gamma + s, r2 = -gamma - s;
    const double c1 = (v0 - r2 * y0) / (r1 - r2);
    y = c1 * std::exp(r1 * tau) + (y0 - c1) * std::exp(r2 * tau);
  } else {  // critically damped
    y = std::exp(-gamma * tau) * (y0 + (v0 + gamma * y0) * tau);
  }
  return equilibrium + y;
}

void spring_motion::clear() {
  times_.clear();
  simulated_.clear();
  exact_.clear();
  error_.clear();
  largest_error_ = 0.0;
}

// The model starts from the current state: x0 and v0 along u.
void spring_motion::restart(const single_spring& stage, double time) {
  clear();
  const particle_system& particles = stage.particles();
  const glm::dvec3 p0 = particles.get_position(0);
  const glm::dvec3 p1 = particles.get_position(1);
  const dynamics_parameters& d = stage.parameters.dynamics;
  dynamics_ = d;
  stiffness_ = stage.parameters.stiffness;
  start_time_ = time;
  model_.omega_squared = stiffness_ / d.mass;
  model_.damping = d.damping;
  model_.forcing = glm::dot(glm::dvec3(0.0, 0.0, -d.gravity), rest_direction_);
  model_.x0 = glm::dot(p1 - p0, rest_direction_) - rest_length_;
  model_.v0 = glm::dot(particles.get_velocity(1), rest_direction_);
}

void spring_motion::record(const single_spring& stage, double time, long step) {
  const particle_system& particles = stage.particles();
  if (particles.size() < 2 || stage.springs().empty())
    return;
  const glm::dvec3 p0 = particles.get_position(0);
  const glm::dvec3 p1 = particles.get_position(1);
  const dynamics_parameters& d = stage.parameters.dynamics;
  if (step == 0 || times_.empty() || time < times_.back()) {
    // A reset: the rest direction and length of the initial state.
    const double length = glm::length(p1 - p0);
    if (step == 0 && length > 0.0)
      rest_direction_ = (p1 - p0) / length;
    rest_length_ = stage.springs()[0].rest_length;
    restart(stage, time);
  } else if (d.mass != dynamics_.mass || d.damping != dynamics_.damping ||
             d.gravity != dynamics_.gravity || stage.parameters.stiffness != stiffness_) {
    restart(stage, time);  // another continuous model from here on
  }
  const double simulated = glm::dot(p1 - p0, rest_direction_) - rest_length_;
  const double exact_now = exact(time);
  if (std::isfinite(simulated))
    largest_error_ = std::max(largest_error_, std::abs(simulated - exact_now));
  // A sample per step, or per window_seconds / max_samples of simulated time for a small dt
  // (a thousandth less, so that rounding in the sum of the dt skips no step of dt = 0.01 s).
  constexpr double spacing = window_seconds / max_samples;
  if (!times_.empty() && time - last_sample_time_ < 0.999 * spacing)
    return;
  last_sample_time_ = time;
  std::size_t old = 0;  // the samples older than the window, dropped
  while (old < times_.size() && time - times_[old] > window_seconds)
    ++old;
  for (std::vector<float>* v : {&times_, &simulated_, &exact_, &error_})
    v->erase(v->begin(), v->begin() + static_cast<std::ptrdiff_t>(old));
  times_.push_back(static_cast<float>(time));
  simulated_.push_back(static_cast<float>(simulated));
  exact_.push_back(static_cast<float>(exact_now));
  error_.push_back(static_cast<float>(simulated - exact_now));
}

}  // namespace clothlab
