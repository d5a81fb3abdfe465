// Question 4's stability map: the current stage run over a grid of time steps dt and
// stiffnesses K, on background threads (sweep.hpp), each cell stable or diverged, beside the
// theoretical step-size limit of stability.hpp.
#pragma once

#include <vector>

#include "core/parameters.hpp"
#include "core/sweep.hpp"

namespace clothlab {

class stability_map {
 public:
  // K from K/10 to 10 K (factors of 10^1/4) around the current K; dt across, centred on the
  // theoretical step-size limit of the current (dt, K) so that the map shows both sides of it
  // (at stage 1's defaults dt = 0.01 s is 45 times below the limit: a map around dt would be all
  // green). The cloth's K is K_struct, K_shear and K_bend scaled together.
  static constexpr int columns = 13;
  static constexpr int rows = 9;
  // The fewest steps a cell runs (its simulated time is longer for a large dt): enough for an
  // unstable mode to grow past the divergence check's bounds.
  static constexpr double min_steps_per_cell = 40.0;

  // The dt of the columns: geometric, centred on time_step_limit, sqrt 2 apart, or farther
  // apart so that the current time_step is the first or last column. Without a finite,
  // positive limit (implicit Euler; explicit Euler undamped, never stable), centred on the
  // current dt.
  static std::vector<double> column_time_steps(double time_step, double time_step_limit);
  // The settings of the map for `stage` with the given parameters; time_step_limit: the
  // stage's limit now (estimate_stability).
  static sweep_settings settings_for(stage_kind stage, const single_spring_parameters& spring,
                                     const coupled_springs_parameters& coupled,
                                     const cloth_parameters& cloth, double time_step_limit);

  // Starts the runs for `stage` (a running map is cancelled first).
  void start(stage_kind stage, const single_spring_parameters& spring,
             const coupled_springs_parameters& coupled, const cloth_parameters& cloth,
             double time_step_limit);
  void cancel() { sweep_.cancel(); }
  // Once a frame: in the browser (no threads) computes the next cells for about `seconds`.
  void advance(double seconds) { sweep_.advance(seconds); }
  bool running() const { return sweep_.running(); }
  double fraction_done() const { return sweep_.fraction_done(); }
  bool started() const { return started_; }
  // True once after the map of the last start() ended (done or stopped), so that its result is
  // said once.
  bool just_ended() {
    if (!started_ || ended_said_ || sweep_.running())
      return false;
    ended_said_ = true;
    return true;
  }
  stage_kind stage() const { return stage_; }
  // The cells so far, row by row from the smallest K, each row from the smallest dt.
  std::vector<sweep_cell> cells() const { return sweep_.snapshot(); }
  // The cell of the current (dt, K) when the map started: the middle row, the nearest column.
  int current_column() const { return current_column_; }
  double column_factor() const { return column_factor_; }  // dt ratio between two columns

 private:
  background_sweep sweep_;
  bool started_ = false;
  bool ended_said_ = false;
  stage_kind stage_ = stage_kind::spring;
  int current_column_ = columns / 2;
  double column_factor_ = 1.4142135623730951;
};

}  // namespace clothlab
