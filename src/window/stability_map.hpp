// Question 4's stability map: the current stage run over a grid of time steps dt and
// stiffnesses K around the current values, on background threads (sweep.hpp), each cell
// stable or diverged, beside the theoretical step-size limit of stability.hpp.
#pragma once

#include <vector>

#include "parameters.hpp"
#include "sweep.hpp"

namespace clothlab {

class stability_map {
 public:
  // dt from dt/8 to 8 dt (factors of sqrt 2), K from K/10 to 10 K: the centre cell is the
  // current (dt, K). The cloth's K is K_struct, K_shear and K_bend scaled together.
  static constexpr int columns = 13;
  static constexpr int rows = 9;

  // Starts the runs for `stage` with the given parameters (a running map is cancelled first).
  void start(stage_kind stage, const single_spring_parameters& spring,
             const coupled_springs_parameters& coupled, const cloth_parameters& cloth);
  void cancel() { sweep_.cancel(); }
  bool running() const { return sweep_.running(); }
  double fraction_done() const { return sweep_.fraction_done(); }
  bool started() const { return started_; }
  stage_kind stage() const { return stage_; }
  // The cells so far, row by row from the smallest K, each row from the smallest dt.
  std::vector<sweep_cell> cells() const { return sweep_.snapshot(); }

 private:
  background_sweep sweep_;
  bool started_ = false;
  stage_kind stage_ = stage_kind::spring;
};

}  // namespace clothlab
