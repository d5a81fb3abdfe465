// Question 4's stability map (src/window/stability_map.hpp): at the defaults of every stage its
// range shows stable and diverged runs, the current dt among its columns.
#include <gtest/gtest.h>

#include <cmath>

#include "core/coupled_springs.hpp"
#include "core/single_spring.hpp"
#include "core/stability.hpp"
#include "core/sweep.hpp"
#include "window/stability_map.hpp"

namespace clothlab {
namespace {

TEST(StabilityMap, ColumnsAreCentredOnTheLimitAndTakeInTheCurrentTimeStep) {
  // Stage 1's defaults: dt = 0.01 s, the limit 2 / sqrt(K / m) = 0.447 s.
  const std::vector<double> far = stability_map::column_time_steps(0.01, 0.447);
  ASSERT_EQ(far.size(), static_cast<std::size_t>(stability_map::columns));
  EXPECT_NEAR(far[stability_map::columns / 2], 0.447, 1e-12);
  EXPECT_NEAR(far.front(), 0.01, 1e-12);  // wider columns, the current dt the first
  // Near the limit: sqrt 2 apart.
  const std::vector<double> near = stability_map::column_time_steps(0.3, 0.447);
  EXPECT_NEAR(near[1] / near[0], std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(near[stability_map::columns / 2], 0.447, 1e-12);
  // No limit (implicit Euler): centred on the current dt, as before.
  const std::vector<double> none = stability_map::column_time_steps(0.01, INFINITY);
  EXPECT_NEAR(none[stability_map::columns / 2], 0.01, 1e-12);
}

// The map as the window starts it, run to the end: how many cells diverged and stayed stable.
std::pair<int, int> diverged_and_stable(stage_kind stage, double time_step_limit) {
  const sweep_settings settings = stability_map::settings_for(stage, {}, {}, {}, time_step_limit);
  int diverged = 0, stable = 0;
  for (const sweep_cell& cell : run_sweep(settings)) {
    EXPECT_TRUE(cell.computed);
    (cell.diverged ? diverged : stable) += 1;
  }
  return {diverged, stable};
}

TEST(StabilityMap, TheDefaultSpringShowsRedAndGreen) {
  single_spring spring{single_spring_parameters{}};
  spring.load_model();
  const auto [diverged, stable] =
      diverged_and_stable(stage_kind::spring, estimate_stability(spring).time_step_limit);
  EXPECT_GE(diverged, 20) << "the map at stage 1's defaults is (nearly) all green";
  EXPECT_GE(stable, 20);
}

// The chain's springs are question 5's answer: in the student copy, without them, every run is
// a free fall (label window-solution).
TEST(SolutionStabilityMap, TheDefaultChainShowsRedAndGreen) {
  coupled_springs chain{coupled_springs_parameters{}};
  chain.load_model();
  const auto [diverged, stable] =
      diverged_and_stable(stage_kind::coupled, estimate_stability(chain).time_step_limit);
  EXPECT_GE(diverged, 20) << "the map at stage 2's defaults is (nearly) all green";
  EXPECT_GE(stable, 20);
}

}  // namespace
}  // namespace clothlab
