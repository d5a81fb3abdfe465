// Question 2: the single spring's motion against the continuous model. In 1D, with x the
// extension from the rest length L0 along the spring's rest direction u,
//   m x'' = -K x - mu m x' + m g_u      (g_u = g . u: the weight only moves the equilibrium)
// has an exact solution (a damped harmonic oscillator about x_eq = m g_u / K). This records,
// frame after frame, the simulated extension (p1 - p0) . u - L0 and that exact solution from
// the state where the comparison started (the reset, or the last change of K, mu, m or g0), so
// that the error of the integrator shows as dt grows.
// The 3D spring also swings sideways (its initial velocity is across the spring); the 1D model
// leaves that out. With the 1D start (scene::spring_one_dimensional_start) the initial velocity
// is along the spring and the motion is exactly 1D.
#pragma once

#include <glm/vec3.hpp>

#include <vector>

#include "core/single_spring.hpp"

namespace clothlab {

// x'' + mu x' + omega0^2 x = forcing, from x(0) = x0, x'(0) = v0.
struct damped_oscillator {
  double omega_squared = 0.0;         // K / m, 1/s^2
  double damping = 0.0;               // mu, 1/s
  double forcing = 0.0;               // g_u, m/s^2
  double x0 = 0.0;                    // m
  double v0 = 0.0;                    // m/s
  double position(double tau) const;  // x(tau), tau in s from the start
};

class spring_motion {
 public:
  // The plot covers the last window_seconds of simulated time, with at most max_samples
  // samples: one per step (dt = 0.01 s at the defaults), or one per window_seconds /
  // max_samples of simulated time for a smaller dt.
  static constexpr double window_seconds = 10.0;
  static constexpr std::size_t max_samples = 1000;

  // After each step (not each frame: a frame that stalls, a screenshot, takes many steps at
  // once, and the plot would join them by a straight chord); time is the stage's t, step its
  // step count (0 after a reset).
  void record(const single_spring& stage, double time, long step);

  // The samples since the comparison started (at most window_seconds of them), oldest first.
  const std::vector<float>& times() const { return times_; }             // t, s
  const std::vector<float>& simulated() const { return simulated_; }     // x, m
  const std::vector<float>& exact_at_samples() const { return exact_; }  // m
  const std::vector<float>& error() const { return error_; }             // simulated - exact, m
  double exact(double time) const { return model_.position(time - start_time_); }
  double start_time() const { return start_time_; }
  double largest_error() const { return largest_error_; }  // m, since the start, every step
  bool started() const { return !times_.empty(); }

 private:
  void restart(const single_spring& stage, double time);
  void clear();

  damped_oscillator model_;
  glm::dvec3 rest_direction_ = {0.0, 0.0, -1.0};  // u, unit: p1 - p0 at step 0
  double rest_length_ = 0.0;                      // L0, m
  dynamics_parameters dynamics_;                  // the parameters the model was built with
  double stiffness_ = 0.0;
  double start_time_ = 0.0;
  double last_sample_time_ = 0.0;  // s, of the newest sample (times_ holds floats)
  double largest_error_ = 0.0;
  std::vector<float> times_, simulated_, exact_, error_;
};

}  // namespace clothlab
