// The stability explorer: the map of diverged cells matches the predicted limit on the single
// spring, the CSV has the contract's columns, and the background run can be polled and stopped.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "core/sweep.hpp"

namespace clothlab {
namespace {

// Semi-implicit Euler, no damping: dt < 2 / sqrt(K/m) = 0.447 s for K = 20, 0.224 s for K = 80.
// No dt of the grid is within 10% of a limit.
sweep_settings spring_map() {
  sweep_settings s;
  s.stage = stage_kind::spring;
  s.spring.dynamics.damping = 0.0;
  s.spring.dynamics.integrator = integrator_kind::semi_implicit;
  s.axis = sweep_axis::stiffness;
  s.time_steps = {0.1, 0.2, 0.3, 0.4, 0.5};
  s.stiffnesses = {20.0, 80.0};
  s.simulated_time = 40.0;
  return s;
}

TEST(Sweep, DivergedCellsAreThoseBeyondThePredictedLimit) {
  const std::vector<sweep_cell> cells = run_sweep(spring_map());
  ASSERT_EQ(cells.size(), 10u);
  for (const sweep_cell& cell : cells) {
    const double limit = 2 / std::sqrt(cell.stiffness);
    EXPECT_TRUE(cell.computed);
    EXPECT_DOUBLE_EQ(cell.time_step_limit, limit);
    EXPECT_EQ(cell.diverged, cell.time_step > limit)
        << "dt = " << cell.time_step << ", K = " << cell.stiffness << ", step " << cell.step;
    if (!cell.diverged) {  // it ran at least the simulated time: ceil(T / dt) steps
      EXPECT_EQ(cell.step, static_cast<long>(std::ceil(40.0 / cell.time_step - 1e-9)));
    }
  }
  // Row by row: K = 20 first, along the time steps.
  EXPECT_EQ(cells[0].stiffness, 20.0);
  EXPECT_EQ(cells[4].time_step, 0.5);
  EXPECT_EQ(cells[5].stiffness, 80.0);
}

TEST(Sweep, CsvHasTheContractColumns) {
  sweep_settings s = spring_map();
  s.time_steps = {0.1, 0.5};
  s.stiffnesses = {20.0};
  std::ostringstream out;
  write_sweep_csv(out, run_sweep(s));
  std::istringstream lines(out.str());
  std::string header, first, second, extra;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(header, "dt,K,N,integrator,diverged,step");
  EXPECT_EQ(first, "0.10000000000000001,20,1,semi-implicit,0,400");
  EXPECT_EQ(second.rfind("0.5,20,1,semi-implicit,1,", 0), 0u) << second;
  EXPECT_FALSE(std::getline(lines, extra));
}

TEST(Sweep, GridSizeAxisRunsTheClothAtEachN) {
  sweep_settings s;
  s.stage = stage_kind::cloth;
  s.cloth.dynamics.integrator = integrator_kind::velocity_verlet;
  s.axis = sweep_axis::grid_size;
  s.time_steps = {0.002};
  s.grid_sizes = {5, 8};
  s.simulated_time = 0.1;
  const std::vector<sweep_cell> cells = run_sweep(s);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].grid_size, 5);
  EXPECT_EQ(cells[1].grid_size, 8);
  EXPECT_EQ(cells[1].stiffness, s.cloth.structural_stiffness);
  EXPECT_FALSE(cells[1].diverged);
  EXPECT_EQ(cells[1].step, 50);
}

TEST(Sweep, RefusesBadSettings) {
  sweep_settings s = spring_map();
  s.axis = sweep_axis::grid_size;
  s.grid_sizes = {4};
  EXPECT_THROW(make_sweep_cells(s), std::invalid_argument);  // the spring has no N
  s = spring_map();
  s.time_steps = {0.1, -0.1};
  EXPECT_THROW(make_sweep_cells(s), std::invalid_argument);
}

TEST(Sweep, CancelledBeforeStartingComputesNothing) {
  sweep_progress progress;
  progress.cancel = true;
  for (const sweep_cell& cell : run_sweep(spring_map(), &progress))
    EXPECT_FALSE(cell.computed);
  EXPECT_EQ(progress.cells_done, 0);
  EXPECT_EQ(progress.cells_total, 10);
}

TEST(Sweep, RunsInTheBackgroundAndReportsProgress) {
  background_sweep sweep;
  sweep.start(spring_map());
  while (sweep.running())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_DOUBLE_EQ(sweep.fraction_done(), 1.0);
  const std::vector<sweep_cell> cells = sweep.snapshot();
  ASSERT_EQ(cells.size(), 10u);
  for (const sweep_cell& cell : cells)
    EXPECT_TRUE(cell.computed);
  // Restarting and cancelling leaves a consistent, partly computed map and no thread behind.
  sweep_settings long_map = spring_map();
  long_map.simulated_time = 1e5;
  sweep.start(long_map);
  sweep.cancel();
  EXPECT_FALSE(sweep.running());
  EXPECT_EQ(sweep.snapshot().size(), 10u);
}

}  // namespace
}  // namespace clothlab
