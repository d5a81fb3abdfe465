#include "window/run_statistics.hpp"

#include <algorithm>
#include <cstdio>

#include "core/i18n.hpp"

namespace clothlab {

void rate_meter::restart() {
  steps_in_window_ = 0;
  frames_in_window_ = 0;
  stepping_seconds_in_window_ = 0.0;
  stepping_rate_ = 0.0;
  window_start_ = clock::now();
}

void rate_meter::add_frame(int steps, double stepping_seconds) {
  steps_in_window_ += steps;
  frames_in_window_ += 1;
  stepping_seconds_in_window_ += stepping_seconds;
  const double seconds = seconds_since(window_start_);
  if (seconds >= 0.5) {
    steps_per_second_ = static_cast<double>(steps_in_window_) / seconds;
    frames_per_second_ = static_cast<double>(frames_in_window_) / seconds;
    stepping_rate_ = stepping_seconds_in_window_ > 0.0
                         ? static_cast<double>(steps_in_window_) / stepping_seconds_in_window_
                         : 0.0;
    steps_in_window_ = 0;
    frames_in_window_ = 0;
    stepping_seconds_in_window_ = 0.0;
    window_start_ = clock::now();
  }
}

void energy_record::clear() {
  for (std::vector<float>& history : values_)
    history.clear();
  times_.clear();
}

void energy_record::record(const energy_breakdown& energy, double time) {
  latest_ = energy;
  const double values[4] = {energy.kinetic, energy.gravity, energy.spring, energy.total};
  for (std::size_t i = 0; i < values_.size(); ++i) {
    std::vector<float>& history = values_[i];
    if (history.size() == frames_kept)
      history.erase(history.begin());
    history.push_back(static_cast<float>(values[i]));
  }
  if (times_.size() == frames_kept)
    times_.erase(times_.begin());
  times_.push_back(static_cast<float>(time));
}

std::size_t intact_spring_count(const spring_mesh& cloth) {
  std::size_t springs = 0;
  for (const spring_family family : all_spring_families)
    springs += cloth.springs(family).size();
  return springs;
}

void tear_report::check(const spring_mesh& cloth, long step, double time) {
  // The springs of the whole N x N cloth (model.md): structural 2 N (N - 1), shear
  // 2 (N - 1)^2, bending 2 N (N - 2).
  const auto n = static_cast<std::size_t>(std::max(cloth.grid_size(), 2));
  const std::size_t whole = 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n - 2);
  const std::size_t springs = intact_spring_count(cloth);
  if (springs >= whole) {
    reported_ = false;
    return;
  }
  if (reported_)
    return;
  reported_ = true;
  std::printf(
      tr("clothlab-window: %s\n"),
      format(tr("the cloth began to tear by step %ld (t = %.3f s): %zu of %zu springs left"), step,
             time, springs, whole)
          .c_str());
  std::fflush(stdout);
}

}  // namespace clothlab
