// The command line's options (docs/cli.md), clothlab run as a subprocess: help and version,
// every option accepted with a valid value, each reaching the physics it sets, whole numbers
// read in decimal, and the window's options without a display.
#include "cli_support.hpp"

namespace {

using namespace clothlab_cli_test;

TEST_F(cli, HelpPrintsTheOptionsAndExitsZero) {
  const run_result result = run({"--help"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("--headless"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("--csv"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("--stage"), std::string::npos) << result.out;
}

TEST_F(cli, VersionPrintsAndExitsZero) {
  const run_result result = run({"--version"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find('.'), std::string::npos) << result.out;
}

// Every option of cli.md is accepted with a valid value (one short headless run per option), and
// the files asked for are written.
class cli_accepts : public cli, public ::testing::WithParamInterface<arguments> {};

TEST_P(cli_accepts, ValidValue) {
  const arguments args = headless_run(GetParam());
  const run_result result = run(args);
  ASSERT_EQ(result.exit_code, 0) << join(args) << "\nstderr: " << result.err;
  for (const char* option : {"--csv", "--obj", "--png"}) {
    const auto at = std::find(args.begin(), args.end(), option);
    if (at != args.end()) {
      const fs::path written = work() / *(at + 1);
      ASSERT_TRUE(fs::exists(written)) << join(args) << ": " << written << " missing";
      EXPECT_GT(fs::file_size(written), 0u) << join(args);
      if (std::string(option) == "--png") {
        EXPECT_EQ(read_file(written).substr(0, 8), "\x89PNG\r\n\x1a\n") << join(args);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryOption, cli_accepts,
    ::testing::Values(
        arguments{"--stage", "spring"}, arguments{"--stage", "coupled"},
        arguments{"--stage", "cloth"}, arguments{"--backend", "cpu"}, arguments{"--backend", "gpu"},
        arguments{"--integrator", "semi-implicit"}, arguments{"--integrator", "explicit"},
        arguments{"--steps", "3"}, arguments{"--dt", "0.001"},
        arguments{"--stage", "spring", "--K", "30"}, arguments{"--stage", "coupled", "--K", "30"},
        arguments{"--K-struct", "4000"}, arguments{"--K-shear", "1500"},
        arguments{"--K-bend", "300"}, arguments{"--mu", "0.1"}, arguments{"--mass", "2"},
        arguments{"--gravity", "5"}, arguments{"--stage", "coupled", "--chain", "4"},
        arguments{"--N", "6"}, arguments{"--size", "2"}, arguments{"--pins", "corners"},
        arguments{"--pins", "none"}, arguments{"--wind-strength", "3"},
        arguments{"--wind-dir", "1,0,0.5"}, arguments{"--ground-z", "-0.5"},
        arguments{"--ground-z", "none"}, arguments{"--ground-friction", "1"},
        arguments{"--csv", "out.csv"}, arguments{"--csv", "out.csv", "--csv-every", "2"},
        arguments{"--obj", "out.obj"},
        arguments{"--png", "out.png", "--width", "64", "--height", "48"},
        arguments{"--backend", "gpu", "--png", "out.png", "--width", "32", "--height", "32"},
        arguments{"--integrator", "verlet"}, arguments{"--integrator", "rk4"},
        arguments{"--integrator", "implicit"}, arguments{"--energy-csv", "energy.csv"},
        arguments{"--scaling", "resolution-independent"},
        arguments{"--scaling", "resolution-independent", "--reference-N", "10"},
        arguments{"--scaling", "per-particle"}, arguments{"--stage", "spring", "--start", "1d"},
        arguments{"--stage", "spring", "--start", "3d"},
        // The other paths and the off-screen contexts.
        // BEGIN TEACHER (the student copy has no parallel CPU path)
        arguments{"--backend", "cpu-parallel"},
        arguments{"--backend", "cpu-parallel", "--threads", "2", "--csv", "out.csv"},
        // END TEACHER
        arguments{"--gl", "auto", "--backend", "gpu"},
        arguments{"--gl", egl_context, "--backend", "gpu", "--png", "out.png", "--width", "32",
                  "--height", "32"},
        arguments{"--gl", own_context, "--png", "out.png", "--width", "32", "--height", "32"},
        // The drag, the sphere, tearing, self-collision.
        arguments{"--drag", "3,3:0.2,0.2,0.3"},
        arguments{"--drag", "3,3:0,0,0", "--drag-stiffness", "500"},
        // The mouse's drag spring on stages 1 and 2 (in the window; headless there is no mouse).
        arguments{"--stage", "spring", "--drag-stiffness", "500"},
        arguments{"--stage", "coupled", "--drag-stiffness", "500"},
        arguments{"--sphere", "0,0,-0.5,0.3", "--obj", "out.obj"},
        arguments{"--sphere", "0,0,-0.5,0.3", "--sphere-friction", "2", "--backend", "gpu"},
        arguments{"--tear-strain", "0.5", "--obj", "out.obj"},
        arguments{"--self-collision", "0.02"},
        // BEGIN TEACHER
        arguments{"--tear-strain", "0.5", "--self-collision", "0.02", "--backend", "cpu-parallel"},
        // END TEACHER
        // The implicit scheme takes any dt, its damping a force (no mu dt <= 1).
        arguments{"--stage", "spring", "--integrator", "implicit", "--dt", "2", "--mu", "0",
                  "--steps", "2000"},
        arguments{"--stage", "spring", "--integrator", "implicit", "--dt", "0.6", "--mu", "5"}),
    [](const ::testing::TestParamInfo<arguments>& param_info) {
      // "--wind-dir 1,0,0.5" -> "wind_dir_1_0_0_5"
      std::string name;
      for (const std::string& arg : param_info.param) {
        for (const char c : arg) {
          const bool alphanumeric = std::isalnum(static_cast<unsigned char>(c)) != 0;
          if (alphanumeric) {
            name += c;
          } else if (!name.empty() && name.back() != '_') {
            name += '_';
          }
        }
        if (!name.empty() && name.back() != '_') {
          name += '_';
        }
      }
      name.pop_back();
      return name;
    });

// Whole numbers are decimal, as typed: a leading zero is not octal ("--steps 010" runs ten steps
// of a chain of ten masses, "--csv-every 03" writes every third), and a base prefix is refused.
TEST_F(cli, WholeNumbersAreDecimalWhateverTheirLeadingZeros) {
  const run_result result = run({"--headless", "--stage", "coupled", "--chain", "010", "--steps",
                                 "010", "--csv-every", "03", "--csv", "c.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(written_steps(read_csv(work() / "c.csv"), 11), (std::vector<long>{0, 3, 6, 9, 10}));
  const run_result hexadecimal = run({"--headless", "--stage", "coupled", "--steps", "0x10"});
  EXPECT_EQ(hexadecimal.exit_code, 2) << hexadecimal.err;
  EXPECT_NE(hexadecimal.err.find("--steps"), std::string::npos) << hexadecimal.err;
  EXPECT_NE(hexadecimal.err.find("0x10"), std::string::npos) << hexadecimal.err;
}

// The options reach the physics: each run below is checked against its first step(s) by hand.

// Single spring, --integrator explicit: p1 = (0.1, 0, 0.5) + 0.01 (1, -1, 0) = (0.11, -0.01, 0.5)
// (the old velocity), v1 as in the semi-implicit case, (0.998, -0.998, -0.098).
TEST_F(cli, IntegratorOptionSelectsTheScheme) {
  const run_result result = run({"--headless", "--stage", "spring", "--integrator", "explicit",
                                 "--steps", "1", "--csv", "s.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "s.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  const double expected[6] = {0.11, -0.01, 0.5, 0.998, -0.998, -0.098};
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_NEAR(csv.rows[3].value[c], expected[c], 1e-15) << "field " << c;
  }
}

// Single spring, --dt 0.02 --mu 0.5 --gravity 5, first step (spring at rest length):
//   v1 = (1, -1, 0)(1 - 0.5 * 0.02) + 0.02 (0, 0, -5) = (0.99, -0.99, -0.1)
//   p1 = (0.1, 0, 0.5) + 0.02 v1 = (0.1198, -0.0198, 0.498), at t = 0.02.
TEST_F(cli, TimeStepDampingAndGravityOptionsReachTheSpring) {
  const run_result result = run({"--headless", "--stage", "spring", "--dt", "0.02", "--mu", "0.5",
                                 "--gravity", "5", "--steps", "1", "--csv", "s.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "s.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  EXPECT_EQ(csv.rows[3].t, 0.02);
  const double expected[6] = {0.1198, -0.0198, 0.498, 0.99, -0.99, -0.1};
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_NEAR(csv.rows[3].value[c], expected[c], 1e-15) << "field " << c;
  }
}

// Single spring, --K 50 --mass 0.5, second step (defaults dt = 0.01, mu = 0.2, g0 = 9.8). After
// the first step p1 = (0.10998, -0.00998, 0.49902), v1 = (0.998, -0.998, -0.098) (see above);
// then with d = p1 - p0 the spring force is F = K (0.5 - |d|) d / |d| (handout equation 2) and
//   v2 = v1 (1 - mu dt) + dt (F / m + g),   p2 = p1 + dt v2.
TEST_F(cli, StiffnessAndMassOptionsReachTheSpring) {
  const run_result result = run({"--headless", "--stage", "spring", "--K", "50", "--mass", "0.5",
                                 "--steps", "2", "--csv", "s.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "s.csv");
  ASSERT_EQ(csv.rows.size(), 6u);
  const double p1[3] = {0.10998, -0.00998, 0.49902};
  const double v1[3] = {0.998, -0.998, -0.098};
  const double d[3] = {p1[0] - 0.1, p1[1], p1[2] - 1.0};
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double g[3] = {0.0, 0.0, -9.8};
  for (std::size_t c = 0; c < 3; ++c) {
    const double force = 50.0 * (0.5 - length) / length * d[c];
    const double v2 = v1[c] * (1.0 - 0.2 * 0.01) + 0.01 * (force / 0.5 + g[c]);
    EXPECT_NEAR(csv.rows[5].value[3 + c], v2, 1e-14) << "v, c = " << c;
    EXPECT_NEAR(csv.rows[5].value[c], p1[c] + 0.01 * v2, 1e-14) << "p, c = " << c;
  }
}

// --chain 3: particle 0 (fixed) then 3 masses at p0 + i (0, 0, -0.5), the last one moving.
TEST_F(cli, ChainOptionSetsTheNumberOfMasses) {
  const run_result result =
      run({"--headless", "--stage", "coupled", "--chain", "3", "--steps", "1", "--csv", "c.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "c.csv");
  ASSERT_EQ(written_steps(csv, 4), (std::vector<long>{0, 1}));
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(csv.rows[i].value[0], 0.1) << i;
    EXPECT_EQ(csv.rows[i].value[2], 1.0 - 0.5 * static_cast<double>(i)) << i;
    EXPECT_EQ(csv.rows[i].value[3], i == 3 ? 1.0 : 0.0) << i;
  }
}

// --N 3 --size 2 --pins none --gravity 4 --dt 0.001: step 0 at p = (-1 + ku, -1 + kv, 0) (h = 1);
// at step 1 every particle (the corners too) has v = (0, 0, -4 * 0.001) = (0, 0, -0.004), within
// the float rounding of an answer to question 6 that computes in single precision.
TEST_F(cli, GridSizePinsAndGravityOptionsReachTheCloth) {
  const run_result result =
      run({"--headless", "--stage", "cloth", "--N", "3", "--size", "2", "--pins", "none",
           "--gravity", "4", "--dt", "0.001", "--steps", "1", "--csv", "cloth.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "cloth.csv");
  ASSERT_EQ(written_steps(csv, 9), (std::vector<long>{0, 1}));
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_DOUBLE_EQ(csv.rows[k].value[0], -1.0 + static_cast<double>(k % 3)) << k;
    EXPECT_DOUBLE_EQ(csv.rows[k].value[1], -1.0 + static_cast<double>(k / 3)) << k;
    EXPECT_NEAR(csv.rows[9 + k].value[5], -0.004, 0.004 * 1e-6) << k;
  }
}

// --wind-strength 3 --wind-dir 0,3,4 on the flat cloth (n = (0, 0, 1), u_w = (0, 0.6, 0.8)),
// without gravity, damping or pins, dt = 0.01: F = 3 * 0.8 * (0, 0, 1) = (0, 0, 2.4) N on each
// unit mass, so at step 1 v = (0, 0, 0.024) everywhere, within the float rounding (1e-6) of
// answers to questions 6 and 13 that compute in single precision.
TEST_F(SolutionCli, WindOptionsReachTheCloth) {
  const run_result result =
      run({"--headless", "--stage",    "cloth", "--N",     "3",    "--pins", "none",
           "--gravity",  "0",          "--mu",  "0",       "--dt", "0.01",   "--wind-strength",
           "3",          "--wind-dir", "0,3,4", "--steps", "1",    "--csv",  "cloth.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "cloth.csv");
  ASSERT_EQ(written_steps(csv, 9), (std::vector<long>{0, 1}));
  for (std::size_t k = 9; k < 18; ++k) {
    EXPECT_NEAR(csv.rows[k].value[3], 0.0, 0.024 * 1e-6) << k;
    EXPECT_NEAR(csv.rows[k].value[4], 0.0, 0.024 * 1e-6) << k;
    EXPECT_NEAR(csv.rows[k].value[5], 0.024, 0.024 * 1e-6) << k;
  }
}

// --ground-z -1e-5 just under the cloth, --pins none, dt = 0.002: after the integrator a free
// particle is at z = -9.8 * 0.002^2 = -3.92e-5 < -1e-5, so the contact puts it back at z = -1e-5
// with v_z = max(-0.0196, 0) = 0.
TEST_F(SolutionCli, GroundHeightOptionReachesTheCloth) {
  const run_result result =
      run({"--headless", "--stage", "cloth", "--N", "3", "--pins", "none", "--ground-z", "-1e-5",
           "--ground-friction", "5", "--steps", "1", "--csv", "cloth.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "cloth.csv");
  ASSERT_EQ(written_steps(csv, 9), (std::vector<long>{0, 1}));
  for (std::size_t k = 9; k < 18; ++k) {
    EXPECT_EQ(csv.rows[k].value[2], -1e-5) << k;
    EXPECT_EQ(csv.rows[k].value[5], 0.0) << k;
  }
}

// Without the ground a free cloth falls through z = -1 in 0.6 s; with the default ground it
// stops on it.
TEST_F(SolutionCli, GroundZNoneRemovesTheGround) {
  const auto fall = [](const std::string& csv, const arguments& extra) {
    arguments args = {"--headless", "--stage", "cloth", "--N", "4",           "--pins", "none",
                      "--steps",    "300",     "--csv", csv,   "--csv-every", "300"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  ASSERT_EQ(run(fall("without.csv", {"--ground-z", "none"})).exit_code, 0);
  ASSERT_EQ(run(fall("with.csv", {})).exit_code, 0);
  const csv_file fallen = read_csv(work() / "without.csv");
  const csv_file landed = read_csv(work() / "with.csv");
  ASSERT_EQ(fallen.rows.size(), 32u);
  ASSERT_EQ(landed.rows.size(), 32u);
  for (std::size_t k = 16; k < 32; ++k) {
    EXPECT_LT(fallen.rows[k].value[2], -1.0) << k;
    EXPECT_GE(landed.rows[k].value[2], -1.0) << k;
  }
}

// Without --headless clothlab opens the window; with no display to open it on, that is "any
// other failure": exit 1 with a message.
TEST_F(cli, WindowWithoutADisplayExitsOne) {
  const run_result result = run({"--stage", "spring"}, true);
  EXPECT_EQ(result.exit_code, 1) << result.err;
  EXPECT_FALSE(result.err.empty());
}

// Question 2 on the command line: with --start 1d the mass moves on the spring's line (its
// velocity only ever along z) and its period, measured between the highest points (vz from +
// to -), is the harmonic oscillator's 2 pi / sqrt(K / m) (semi-implicit Euler's frequency is
// (2 / dt) asin(omega dt / 2): 8e-5 off at dt = 0.01 s). The handout's start gives 1.12 s.
TEST_F(cli, Start1dSpringHasTheHarmonicOscillatorsPeriod) {
  const run_result result = run({"--headless", "--stage", "spring", "--start", "1d", "--mu", "0",
                                 "--steps", "1000", "--csv", "spring.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::vector<double> highest;  // times of the highest points
  const csv_row* previous = nullptr;
  for (const csv_row& row : read_csv(work() / "spring.csv").rows) {
    if (row.particle != 1)
      continue;
    EXPECT_EQ(row.value[0], 0.1) << "x moved at t = " << row.t;
    EXPECT_EQ(row.value[4], 0.0) << "vy at t = " << row.t;
    if (previous != nullptr && previous->value[5] > 0 && row.value[5] <= 0) {
      const double f = previous->value[5] / (previous->value[5] - row.value[5]);
      highest.push_back(previous->t + f * (row.t - previous->t));
    }
    previous = &row;
  }
  ASSERT_GE(highest.size(), 5u);
  const double period = (highest.back() - highest.front()) / double(highest.size() - 1);
  const double predicted = 2.0 * M_PI / std::sqrt(20.0 / 1.0);
  EXPECT_NEAR(period, predicted, 2e-4 * predicted) << "measured " << period;
}

// BEGIN TEACHER (the student copy has no compute path)

// The compute-shader path runs and writes its outputs (not in the student copy, whose step
// shader would hold question 12's answer: label cli-solution).
TEST_F(SolutionCli, GpuComputeRunsAndWritesItsOutputs) {
  const arguments args = headless_run({"--backend", "gpu-compute", "--csv", "out.csv", "--png",
                                       "out.png", "--width", "32", "--height", "32"});
  const run_result result = run(args);
  ASSERT_EQ(result.exit_code, 0) << join(args) << "\nstderr: " << result.err;
  EXPECT_GT(fs::file_size(work() / "out.csv"), 0u);
  EXPECT_EQ(read_file(work() / "out.png").substr(0, 8), "\x89PNG\r\n\x1a\n");
}

// END TEACHER

// A self-collision distance above the shortest rest length h is clamped to h, with a warning.
TEST_F(cli, SelfCollisionAboveTheRestLengthIsClampedWithAWarning) {
  const run_result result =
      run({"--headless", "--N", "4", "--steps", "2", "--self-collision", "1000"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << result.err;
  EXPECT_NE(result.err.find("--self-collision 1000: clamped"), std::string::npos) << result.err;
  const run_result below =
      run({"--headless", "--N", "4", "--steps", "2", "--self-collision", "0.1"});
  EXPECT_EQ(below.exit_code, 0) << below.err;
  EXPECT_TRUE(below.err.empty()) << below.err;
}

}  // namespace
