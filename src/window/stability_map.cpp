#include "window/stability_map.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

namespace clothlab {

std::vector<double> stability_map::column_time_steps(double time_step, double time_step_limit) {
  const int half = columns / 2;
  double centre = time_step;
  double factor = std::sqrt(2.0);
  if (std::isfinite(time_step_limit) && time_step_limit > 0.0 && time_step > 0.0) {
    centre = time_step_limit;
    // The current dt farther than `half` columns of sqrt 2 from the limit: wider columns, the
    // current dt the first (or last) one.
    const double ratio = std::max(time_step_limit / time_step, time_step / time_step_limit);
    factor = std::max(factor, std::pow(ratio, 1.0 / half));
  }
  std::vector<double> time_steps;
  for (int i = 0; i < columns; ++i)
    time_steps.push_back(centre * std::pow(factor, i - half));
  return time_steps;
}

sweep_settings stability_map::settings_for(stage_kind stage, const single_spring_parameters& spring,
                                           const coupled_springs_parameters& coupled,
                                           const cloth_parameters& cloth, double time_step_limit) {
  sweep_settings settings;
  settings.stage = stage;
  settings.spring = spring;
  settings.coupled = coupled;
  settings.cloth = cloth;
  settings.axis = sweep_axis::stiffness;
  double time_step = 0.0;
  double stiffness = 0.0;
  switch (stage) {
    case stage_kind::spring:
      time_step = spring.dynamics.time_step;
      stiffness = spring.stiffness;
      break;
    case stage_kind::coupled:
      time_step = coupled.dynamics.time_step;
      stiffness = coupled.stiffness;
      break;
    case stage_kind::cloth:
      time_step = cloth.dynamics.time_step;
      stiffness = cloth.structural_stiffness;
      settings.simulated_time = 1.0;  // s: the cloth's cells are the costly ones
      break;
  }
  stiffness = std::max(stiffness, 1e-3);  // K = 0 would give a single row of zeros
  settings.time_steps = column_time_steps(time_step, time_step_limit);
  // Every cell runs at least min_steps_per_cell steps: a run of one or two steps of a large dt
  // ends before an unstable mode has grown enough to be seen (the right of the map stayed green).
  settings.simulated_time =
      std::max(settings.simulated_time, min_steps_per_cell * settings.time_steps.back());
  for (int j = 0; j < rows; ++j)
    settings.stiffnesses.push_back(stiffness * std::pow(10.0, (j - rows / 2) / 4.0));
  const unsigned cores = std::thread::hardware_concurrency();           // 0 when unknown
  settings.worker_count = cores > 1 ? static_cast<int>(cores - 1) : 1;  // a core for the window
  return settings;
}

void stability_map::start(stage_kind stage, const single_spring_parameters& spring,
                          const coupled_springs_parameters& coupled, const cloth_parameters& cloth,
                          double time_step_limit) {
  const sweep_settings settings = settings_for(stage, spring, coupled, cloth, time_step_limit);
  const double time_step = stage == stage_kind::spring    ? spring.dynamics.time_step
                           : stage == stage_kind::coupled ? coupled.dynamics.time_step
                                                          : cloth.dynamics.time_step;
  // The column nearest to the current dt (on a logarithmic scale).
  current_column_ = 0;
  for (int i = 1; i < columns; ++i) {
    if (std::abs(std::log(settings.time_steps[i] / time_step)) <
        std::abs(std::log(settings.time_steps[current_column_] / time_step)))
      current_column_ = i;
  }
  column_factor_ = settings.time_steps[1] / settings.time_steps[0];
  sweep_.start(settings);
  started_ = true;
  ended_said_ = false;
  stage_ = stage;
}

}  // namespace clothlab
