#include "stability_map.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

namespace clothlab {

void stability_map::start(stage_kind stage, const single_spring_parameters& spring,
                          const coupled_springs_parameters& coupled,
                          const cloth_parameters& cloth) {
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
  for (int i = 0; i < columns; ++i)
    settings.time_steps.push_back(time_step * std::pow(2.0, (i - columns / 2) / 2.0));
  for (int j = 0; j < rows; ++j)
    settings.stiffnesses.push_back(stiffness * std::pow(10.0, (j - rows / 2) / 4.0));
  const unsigned cores = std::thread::hardware_concurrency();           // 0 when unknown
  settings.worker_count = cores > 1 ? static_cast<int>(cores - 1) : 1;  // a core for the window
  sweep_.start(settings);
  started_ = true;
  stage_ = stage;
}

}  // namespace clothlab
