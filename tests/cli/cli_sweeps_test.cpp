// The stability map (--sweep, docs/cli.md): the single spring around its theoretical limit,
// the lists of values and their ranges, and the work a sweep may ask for.
#include "cli_support.hpp"

namespace {

using namespace clothlab_cli_test;

// The stability map of the undamped single spring with K = 400, m = 1: omega = 20 rad/s, so
// semi-implicit Euler is stable for dt < 2 / omega = 0.1 s. At 0.9x the limit the cell is
// stable, at 1.1x it diverges.
TEST_F(cli, SweepMapsTheSingleSpringAroundItsTheoreticalLimit) {
  const run_result result =
      run({"--headless", "--stage", "spring", "--mu", "0", "--sweep", "map.csv", "--sweep-dt",
           "0.09,0.11", "--sweep-K", "400", "--sweep-time", "20"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::istringstream text(read_file(work() / "map.csv"));
  std::string line;
  std::getline(text, line);
  EXPECT_EQ(line, "dt,K,N,integrator,diverged,step");
  std::vector<std::string> rows;
  while (std::getline(text, line))
    rows.push_back(line);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].find("0.089999999999999997,400,1,semi-implicit,0,"), 0u) << rows[0];
  EXPECT_EQ(rows[1].find("0.11,400,1,semi-implicit,1,"), 0u) << rows[1];
}

// D6: sweeps that would run without end are refused with the number of steps and the limit,
// and nothing is written.
TEST_F(cli, SweepAskingForTooManyStepsIsRefusedWithTheCount) {
  const run_result per_cell =
      run({"--headless", "--stage", "spring", "--sweep", "m.csv", "--sweep-dt", "1e-9"});
  EXPECT_EQ(per_cell.exit_code, 2) << per_cell.err;
  EXPECT_EQ(count_lines(per_cell.err), 1u) << per_cell.err;
  EXPECT_NE(per_cell.err.find("--sweep-dt"), std::string::npos) << per_cell.err;
  EXPECT_NE(per_cell.err.find("2e+09 steps"), std::string::npos) << per_cell.err;
  EXPECT_NE(per_cell.err.find("10000000"), std::string::npos) << per_cell.err;
  // 200 x 200 cells of 1e6 steps each: 4e10 steps in all.
  const run_result total = run({"--headless", "--stage", "spring", "--sweep", "m.csv", "--sweep-dt",
                                "1e-6:2e-6:200", "--sweep-K", "1:2:200", "--sweep-time", "1"});
  EXPECT_EQ(total.exit_code, 2) << total.err;
  EXPECT_NE(total.err.find("limit 1e+09"), std::string::npos) << total.err;
  EXPECT_TRUE(fs::is_empty(work()));
}

// --sweep-N 1 on the cloth (a grid of one particle) was an uncaught exception (exit 134) that
// left the sweep's temporary file; the chain's n = 1 stays accepted.
TEST_F(cli, SweepOfAOneParticleClothIsRefused) {
  for (const char* list : {"1", "1,4", "1:4:3"}) {
    const arguments args = {"--headless", "--sweep", "s.csv", "--sweep-N", list};
    const run_result result = run(args);
    EXPECT_EQ(result.exit_code, 2) << join(args) << "\n" << result.err;
    EXPECT_EQ(count_lines(result.err), 1u) << result.err;
    EXPECT_NE(result.err.find("--sweep-N 1"), std::string::npos) << result.err;
    EXPECT_TRUE(fs::is_empty(work())) << join(args) << " wrote a file";
  }
  const run_result chain = run({"--headless", "--stage", "coupled", "--sweep", "s.csv", "--sweep-N",
                                "1,2", "--sweep-dt", "0.01", "--sweep-time", "0.1"});
  EXPECT_EQ(chain.exit_code, 0) << chain.err;
}

// A range whose ends are tiny or far apart is read like its single values: 1e-320:1:3 used to
// be "--sweep-K inf" (to / from overflowed) while 1:1e-320:3 was accepted.
TEST_F(cli, SweepRangesWithSubnormalEndsAreReadAlike) {
  for (const char* range : {"1e-320:1:3", "1:1e-320:3", "0x1p-1074:1:2"}) {
    const arguments args = {"--headless", "--stage",      "spring", "--sweep",
                            "s.csv",      "--sweep-K",    range,    "--sweep-dt",
                            "0.01",       "--sweep-time", "0.05"};
    const run_result result = run(args);
    EXPECT_EQ(result.exit_code, 0) << join(args) << "\n" << result.err;
    const std::string text = read_file(work() / "s.csv");
    EXPECT_EQ(text.find("inf"), std::string::npos) << text;
    EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  }
}

// A sweep's cells are counted with their set-up (building a cloth of N^2 particles and
// estimating its limit costs about 7 of its steps): 200 cells of N = 1024 that run one step
// each used to be accepted and take 4.5 minutes.
TEST_F(cli, SweepSetUpCountsInItsWork) {
  const run_result result = run(
      {"--headless", "--sweep", "s.csv", "--sweep-N", "1024:1024:200", "--sweep-time", "0.001"});
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << result.err;
  EXPECT_NE(result.err.find("set-up"), std::string::npos) << result.err;
  EXPECT_TRUE(fs::is_empty(work()));
}

}  // namespace
