#include "core/stability.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// One step of each scheme on the scalar mode x'' = -omega^2 x - mu x' (the same formulas as
// integrator.cpp and implicit_euler.cpp with F = -m omega^2 x and g = 0).
std::array<double, 2> scalar_step(integrator_kind integrator, double omega, double damping,
                                  double dt, double x, double v) {
  const double w2 = omega * omega;
  auto acceleration = [&](double position, double velocity) {
    return -w2 * position - damping * velocity;  // the damping force -mu m v, over m
  };
  switch (integrator) {
    case integrator_kind::semi_implicit: {
      const double v1 = (1 - damping * dt) * v - dt * w2 * x;
      return {x + dt * v1, v1};
    }
    case integrator_kind::explicit_euler:
      return {x + dt * v, (1 - damping * dt) * v - dt * w2 * x};
    case integrator_kind::velocity_verlet: {
      const double v_half = v + 0.5 * dt * acceleration(x, v);
      const double x1 = x + dt * v_half;
      return {x1, (v_half - 0.5 * dt * w2 * x1) / (1 + 0.5 * damping * dt)};
    }
    case integrator_kind::runge_kutta_4: {
      const double k1x = v, k1v = acceleration(x, v);
      const double k2x = v + 0.5 * dt * k1v, k2v = acceleration(x + 0.5 * dt * k1x, k2x);
      const double k3x = v + 0.5 * dt * k2v, k3v = acceleration(x + 0.5 * dt * k2x, k3x);
      const double k4x = v + dt * k3v, k4v = acceleration(x + dt * k3x, k4x);
      return {x + dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x),
              v + dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)};
    }
    case integrator_kind::implicit_euler: {
      // (1 + mu dt + dt^2 omega^2) dv = dt (a(x, v) - dt omega^2 v), J = -m omega^2.
      const double dv = dt * (acceleration(x, v) - dt * w2 * v) / (1 + damping * dt + dt * dt * w2);
      const double v1 = v + dv;
      return {x + dt * v1, v1};
    }
    case integrator_kind::xpbd: {
      // One substep of length dt (xpbd.hpp) on the spring of stiffness m omega^2 as a
      // constraint: the predicted x~ = x + dt (1 - mu dt) v, then C = x with alpha~ = 1 / (m
      // omega^2 dt^2) and w = 1/m: x' = x~ alpha~ / (w + alpha~) = x~ / (1 + (omega dt)^2), and
      // v' = (x' - x) / dt. A step of n substeps is this map with dt / n, n times.
      const double x_predicted = x + dt * (1 - damping * dt) * v;
      const double x1 = x_predicted / (1 + dt * dt * w2);
      return {x1, (x1 - x) / dt};
    }
  }
  return {NAN, NAN};
}

// The largest |eigenvalue| of a real 2 x 2 matrix, from lambda^2 - trace lambda + det = 0.
double spectral_radius(double trace, double det) {
  const double half_trace = trace / 2;
  const double discriminant = half_trace * half_trace - det;
  if (discriminant < 0)
    return std::sqrt(det);  // complex pair: |lambda|^2 = det
  const double root = std::sqrt(discriminant);
  return std::max(std::abs(half_trace + root), std::abs(half_trace - root));
}

// The first dt at which rho exceeds 1: a scan of omega dt (or mu dt) up to 20, then bisection.
double first_unstable_time_step(integrator_kind integrator, double omega, double damping) {
  const double rate = std::max(omega, damping);  // 1/s: the fastest time scale of the mode
  if (rate == 0.0)
    return infinity;
  constexpr double tolerance = 1e-12;
  constexpr int scan_points = 4000;
  constexpr double scan_end = 20.0;
  double stable = 0.0;
  for (int i = 1; i <= scan_points; ++i) {
    const double dt = scan_end * i / scan_points / rate;
    if (amplification_factor(integrator, omega, damping, dt) > 1 + tolerance) {
      double unstable = dt;
      for (int b = 0; b < 60; ++b) {
        const double middle = 0.5 * (stable + unstable);
        (amplification_factor(integrator, omega, damping, middle) > 1 + tolerance ? unstable
                                                                                  : stable) =
            middle;
      }
      return stable;
    }
    stable = dt;
  }
  return infinity;
}

std::string format_seconds(double seconds) {
  char text[32];
  if (std::isinf(seconds))
    return tr("none");
  std::snprintf(text, sizeof text, "%.3g ms", seconds * 1e3);
  return text;
}

}  // namespace

double amplification_factor(integrator_kind integrator, double omega, double damping, double dt) {
  // The columns of A are the images of (1, 0) and (0, 1).
  const std::array<double, 2> first = scalar_step(integrator, omega, damping, dt, 1.0, 0.0);
  const std::array<double, 2> second = scalar_step(integrator, omega, damping, dt, 0.0, 1.0);
  const double trace = first[0] + second[1];
  const double det = first[0] * second[1] - second[0] * first[1];
  return spectral_radius(trace, det);
}

double time_step_limit(integrator_kind integrator, double omega, double damping) {
  const double w2 = omega * omega;
  switch (integrator) {
    case integrator_kind::semi_implicit:
      // (omega dt)^2 + 2 mu dt < 4: the positive root of w2 dt^2 + 2 mu dt - 4.
      if (omega == 0.0 && damping == 0.0)
        return infinity;
      return 4 / (damping + std::sqrt(damping * damping + 4 * w2));
    case integrator_kind::explicit_euler:
      // det < 1: omega^2 dt < mu; and 4 - 2 mu dt + (omega dt)^2 > 0 (binding when mu >= 2 omega).
      if (damping == 0.0)
        return omega == 0.0 ? infinity : 0.0;
      if (omega == 0.0)
        return 2 / damping;  // v <- (1 - mu dt) v: |1 - mu dt| <= 1
      if (damping >= 2 * omega)
        return (damping - std::sqrt(damping * damping - 4 * w2)) / w2;
      return damping / w2;
    case integrator_kind::velocity_verlet:
      if (damping == 0.0)
        return omega == 0.0 ? infinity : 2 / omega;
      return first_unstable_time_step(integrator, omega, damping);
    case integrator_kind::runge_kutta_4:
      if (damping == 0.0)
        return omega == 0.0 ? infinity : 2 * std::sqrt(2.0) / omega;
      return first_unstable_time_step(integrator, omega, damping);
    case integrator_kind::implicit_euler:
    case integrator_kind::xpbd:
      return infinity;
  }
  return 0.0;
}

double gershgorin_omega_max(const particle_system& particles,
                            std::span<const spring_set> spring_sets, double mass) {
  // row_bound[i] = sum of K_s over i's springs (the diagonal block's norm bound) + sum of K_s
  // over i's springs to moving particles (the off-diagonal blocks' norms).
  std::vector<double> row_bound(particles.size(), 0.0);
  for (const spring_set& set : spring_sets) {
    for (const spring& s : set.springs) {
      const bool a_moves = !particles.is_fixed[s.a];
      const bool b_moves = !particles.is_fixed[s.b];
      row_bound[s.a] += set.stiffness * (b_moves ? 2 : 1);
      row_bound[s.b] += set.stiffness * (a_moves ? 2 : 1);
    }
  }
  double largest = 0.0;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (!particles.is_fixed[k])
      largest = std::max(largest, row_bound[k]);
  }
  return std::sqrt(largest / mass);
}

stability_estimate estimate_stability(const particle_system& particles,
                                      std::span<const spring_set> spring_sets,
                                      const dynamics_parameters& dynamics) {
  stability_estimate estimate;
  estimate.omega_max = gershgorin_omega_max(particles, spring_sets, dynamics.mass);
  estimate.time_step_limit =
      time_step_limit(dynamics.integrator, estimate.omega_max, dynamics.damping);
  const double dt = dynamics.time_step;
  estimate.ratio = std::isinf(estimate.time_step_limit) ? 0.0
                   : estimate.time_step_limit == 0.0    ? infinity
                                                        : dt / estimate.time_step_limit;
  const std::string name(integrator_name(dynamics.integrator));
  if (dynamics.integrator == integrator_kind::xpbd) {
    // What XPBD pays instead of a limit: over a substep h, (omega h)^2 = w / alpha~ compares the
    // constraint's correction with its compliance; above 1, a few sweeps leave the springs
    // softer than K (docs/stability.md).
    const double h = dt / std::max(dynamics.xpbd.substeps, 1);
    const double stiffness_ratio = std::pow(estimate.omega_max * h, 2);
    estimate.explanation =
        format(tr("%s: no step-size limit (omega_max <= %.4g rad/s); substep h = %s, "
                  "(omega h)^2 = %.3g%s"),
               tr(name.c_str()), estimate.omega_max, format_seconds(h).c_str(), stiffness_ratio,
               stiffness_ratio > 1 ? tr(": softer than K unless more substeps or iterations")
                                   : tr(": the springs reach K"));
  } else if (std::isinf(estimate.time_step_limit)) {
    estimate.explanation =
        format(tr("%s: no step-size limit (omega_max <= %.4g rad/s, dt omega = %.3g)"),
               tr(name.c_str()), estimate.omega_max, dt * estimate.omega_max);
  } else if (estimate.time_step_limit == 0.0) {
    estimate.explanation =
        format(tr("%s without damping grows by sqrt(1 + (dt omega)^2) per step at any dt "
                  "(omega_max <= %.4g rad/s): add damping mu > omega^2 dt"),
               tr(name.c_str()), estimate.omega_max);
  } else {
    estimate.explanation =
        format(tr("%s: stable while dt < %s (omega_max <= %.4g rad/s); dt = %s is %.3g x the "
                  "limit%s"),
               tr(name.c_str()), format_seconds(estimate.time_step_limit).c_str(),
               estimate.omega_max, format_seconds(dt).c_str(), estimate.ratio,
               estimate.ratio >= 1 ? tr(": expect divergence, lower dt or K") : "");
  }
  return estimate;
}

stability_estimate estimate_stability(const single_spring& stage) {
  const spring_set sets[] = {{stage.springs(), stage.parameters.stiffness}};
  return estimate_stability(stage.particles(), sets, stage.parameters.dynamics);
}

stability_estimate estimate_stability(const coupled_springs& stage) {
  const spring_set sets[] = {{stage.springs(), stage.parameters.stiffness}};
  return estimate_stability(stage.particles(), sets, stage.parameters.dynamics);
}

stability_estimate estimate_stability(const spring_mesh& stage) {
  const std::array<spring_set, 3> sets = stage.spring_sets();
  return estimate_stability(stage.particles(), sets, stage.effective_parameters().dynamics);
}

divergence_status divergence_check(const particle_system& particles, double speed_bound) {
  divergence_status status;
  const double bound_squared = speed_bound * speed_bound;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const glm::dvec3 p = particles.get_position(k);
    const glm::dvec3 v = particles.get_velocity(k);
    const double speed_squared = glm::dot(v, v);
    char line[256];
    if (!std::isfinite(p.x + p.y + p.z) || !std::isfinite(speed_squared)) {
      std::snprintf(line, sizeof line, tr("particle %zu has a non-finite position or velocity"), k);
    } else if (speed_squared > bound_squared) {
      std::snprintf(line, sizeof line,
                    tr("speed %.3g m/s of particle %zu exceeds the bound %.3g m/s"),
                    std::sqrt(speed_squared), k, speed_bound);
    } else {
      continue;
    }
    status.diverged = true;
    status.reason = line;
    return status;
  }
  return status;
}

double divergence_speed_bound(double gravity, double fall_height, double initial_speed) {
  const double fall_speed = std::sqrt(2 * std::abs(gravity) * std::max(fall_height, 0.0));
  return 1e3 * std::max({1.0, initial_speed, fall_speed});
}

divergence_status divergence_check(const single_spring& stage) {
  constexpr double initial_speed = 1.4142135623730951;  // |(1, -1, 0)| of load_model
  constexpr double fall_height = 1.0;                   // p0 is at z = 1
  return divergence_check(
      stage.particles(),
      divergence_speed_bound(stage.parameters.dynamics.gravity, fall_height, initial_speed));
}

divergence_status divergence_check(const coupled_springs& stage) {
  constexpr double initial_speed = 1.4142135623730951;  // |(1, -1, 0)| of the last mass
  const double fall_height = 0.5 * (stage.parameters.mass_count + 1);
  return divergence_check(
      stage.particles(),
      divergence_speed_bound(stage.parameters.dynamics.gravity, fall_height, initial_speed));
}

double divergence_speed_bound(const spring_mesh& stage) {
  const double fall_height = stage.parameters.side_length + 1.0;  // the cloth starts at rest
  return divergence_speed_bound(stage.parameters.dynamics.gravity, fall_height, 0.0);
}

divergence_status divergence_check(const spring_mesh& stage) {
  return divergence_check(stage.particles(), divergence_speed_bound(stage));
}

}  // namespace clothlab
