// The clothlab executable run as a subprocess, against shared/cli.md: help and version, every
// option, the CSV format (checked against a hand computation), bad usage (exit 2), divergence
// (exit 3), unwritable files (exit 1) and the OBJ. Each run happens in its own empty directory.
#include <fcntl.h>
#include <grp.h>
#include <gtest/gtest.h>
#include <poll.h>
#if defined(__APPLE__)
#include <util.h>  // forkpty (Linux: <pty.h>)
#else
#include <pty.h>
#endif
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "build_paths.hpp"

namespace {

// The off-screen context of clothlab itself, with no hand-over to clothlab-egl: OSMesa's where
// the build has it, else the build's only one (tests/cli/CMakeLists.txt says which it has).
#if defined(CLOTHLAB_TEST_HAS_OSMESA)
constexpr const char* own_context = "osmesa";
#elif defined(CLOTHLAB_TEST_HAS_EGL)
constexpr const char* own_context = "egl";
#else
constexpr const char* own_context = "auto";
#endif
// EGL's, where the build has it (beside OSMesa or alone), else the build's only context.
#if defined(CLOTHLAB_TEST_HAS_EGL)
constexpr const char* egl_context = "egl";
#else
constexpr const char* egl_context = own_context;
#endif

namespace fs = std::filesystem;
using arguments = std::vector<std::string>;

struct run_result {
  int exit_code = -1;  // 128 + signal when killed by a signal
  std::string out;
  std::string err;
};

std::string read_file(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string join(const arguments& args) {
  std::string line = "clothlab";
  for (const std::string& arg : args) {
    line += " " + arg;
  }
  return line;
}

// A fresh directory per test: clothlab runs in <root>/work (which must otherwise stay empty when
// it writes nothing); its standard output and error go to files beside it.
class cli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "clothlab-cli-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    root_ = pattern;
    fs::create_directory(work());
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }

  fs::path work() const { return root_ / "work"; }
  fs::path root() const { return root_; }

  long file_size_limit = 0;  // bytes: RLIMIT_FSIZE of the runs, 0 for none

  // without_display: DISPLAY and WAYLAND_DISPLAY removed from clothlab's environment.
  run_result run(const arguments& args, bool without_display = false) const {
    return finish(start(args, without_display));
  }

  // Starts clothlab without waiting for it; `name` tells its standard output and error files
  // apart from those of other runs at the same time.
  pid_t start(const arguments& args, bool without_display = false,
              const std::string& name = "") const {
    const fs::path out_path = root_ / ("stdout" + name + ".txt");
    const fs::path err_path = root_ / ("stderr" + name + ".txt");
    std::vector<char*> argv;
    std::string program = clothlab_test::executable_path;
    argv.push_back(program.data());
    std::vector<std::string> copies = args;
    for (std::string& arg : copies) {
      argv.push_back(arg.data());
    }
    argv.push_back(nullptr);

    const pid_t child = fork();
    if (child == 0) {
      const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (out < 0 || err < 0 || chdir(work().c_str()) != 0 || dup2(out, 1) < 0 ||
          dup2(err, 2) < 0) {
        _exit(126);
      }
      if (without_display) {
        unsetenv("DISPLAY");
        unsetenv("WAYLAND_DISPLAY");
      }
      if (file_size_limit > 0) {
        // A full disk, simulated: writes past the limit fail with EFBIG (SIGXFSZ ignored).
        signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{static_cast<rlim_t>(file_size_limit),
                           static_cast<rlim_t>(file_size_limit)};
        if (setrlimit(RLIMIT_FSIZE, &limit) != 0)
          _exit(126);
      }
      alarm(60);  // a run that hangs is killed (SIGALRM: exit code 128 + 14)
      execv(argv[0], argv.data());
      _exit(127);
    }
    return child;
  }

  // Waits for a run started by start().
  run_result finish(pid_t child, const std::string& name = "") const {
    const fs::path out_path = root_ / ("stdout" + name + ".txt");
    const fs::path err_path = root_ / ("stderr" + name + ".txt");
    run_result result;
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) != child) {
      return result;
    }
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = read_file(out_path);
    result.err = read_file(err_path);
    return result;
  }

 private:
  fs::path root_;
};

bool has_option(const arguments& args, const std::string& option) {
  return std::find(args.begin(), args.end(), option) != args.end();
}

// --headless, and small values for the options that the case does not set itself.
arguments headless_run(const arguments& extra) {
  arguments args = {"--headless"};
  if (!has_option(extra, "--steps")) {
    args.insert(args.end(), {"--steps", "2"});
  }
  // A small cloth (only the cloth has --N: the other stages refuse it).
  const auto stage = std::find(extra.begin(), extra.end(), "--stage");
  const bool cloth = stage == extra.end() || (stage + 1 != extra.end() && *(stage + 1) == "cloth");
  if (!has_option(extra, "--N") && cloth) {
    args.insert(args.end(), {"--N", "4"});
  }
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

std::size_t count_lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// One CSV line of cli.md: step,t,particle,x,y,z,vx,vy,vz.
struct csv_row {
  long step = 0;
  double t = 0;
  long particle = 0;
  double value[6] = {};  // x, y, z, vx, vy, vz
};

struct csv_file {
  std::string header;
  std::vector<csv_row> rows;
};

// Parses the file; fails the calling test (through ADD_FAILURE) on a malformed line.
csv_file read_csv(const fs::path& path) {
  csv_file csv;
  std::ifstream file(path);
  std::getline(file, csv.header);
  std::string line;
  while (std::getline(file, line)) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    std::string field;
    while (std::getline(stream, field, ',')) {
      fields.push_back(field);
    }
    if (fields.size() != 9) {
      ADD_FAILURE() << "CSV line without 9 fields: " << line;
      continue;
    }
    csv_row row;
    char* end = nullptr;
    row.step = std::strtol(fields[0].c_str(), &end, 10);
    EXPECT_EQ(*end, '\0') << line;
    row.t = std::strtod(fields[1].c_str(), &end);
    EXPECT_EQ(*end, '\0') << line;
    row.particle = std::strtol(fields[2].c_str(), &end, 10);
    EXPECT_EQ(*end, '\0') << line;
    for (std::size_t c = 0; c < 6; ++c) {
      row.value[c] = std::strtod(fields[3 + c].c_str(), &end);
      EXPECT_EQ(*end, '\0') << line;
    }
    csv.rows.push_back(row);
  }
  return csv;
}

// The steps present in the CSV, each with its particles listed exactly once in index order.
std::vector<long> written_steps(const csv_file& csv, long particle_count) {
  std::vector<long> steps;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const long expected_particle = static_cast<long>(i) % particle_count;
    EXPECT_EQ(csv.rows[i].particle, expected_particle) << "row " << i;
    if (expected_particle == 0) {
      steps.push_back(csv.rows[i].step);
    } else {
      EXPECT_EQ(csv.rows[i].step, steps.back()) << "row " << i;
    }
  }
  EXPECT_EQ(csv.rows.size() % static_cast<std::size_t>(particle_count), 0u);
  return steps;
}

constexpr const char* csv_header = "step,t,particle,x,y,z,vx,vy,vz";

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
        // Issue 9: the other paths and the off-screen contexts.
        // BEGIN TEACHER (the student copy has no parallel CPU path)
        arguments{"--backend", "cpu-parallel"},
        arguments{"--backend", "cpu-parallel", "--threads", "2", "--csv", "out.csv"},
        // END TEACHER
        arguments{"--gl", "auto", "--backend", "gpu"},
        arguments{"--gl", egl_context, "--backend", "gpu", "--png", "out.png", "--width", "32",
                  "--height", "32"},
        arguments{"--gl", own_context, "--png", "out.png", "--width", "32", "--height", "32"},
        // Issue 10: the drag, the sphere, tearing, self-collision.
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
        // Issue 11: the implicit scheme takes any dt, its damping a force (no mu dt <= 1).
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

// Single spring with the defaults (dt = 0.01, mu = 0.2, g0 = 9.8, K = 20, m = 1), one step.
// Step 0 is the initial state of model.md; at step 1 the spring is still at rest length, so
//   v1 = (1, -1, 0)(1 - 0.2 * 0.01) + 0.01 (0, 0, -9.8) = (0.998, -0.998, -0.098)
//   p1 = (0.1, 0, 0.5) + 0.01 v1 = (0.10998, -0.00998, 0.49902)
TEST_F(cli, SingleSpringCsvHoldsTheInitialStateAndTheHandComputedFirstStep) {
  const run_result result =
      run({"--headless", "--stage", "spring", "--steps", "1", "--csv", "spring.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string text = read_file(work() / "spring.csv");
  EXPECT_EQ(count_lines(text), 5u) << text;
  const csv_file csv = read_csv(work() / "spring.csv");
  EXPECT_EQ(csv.header, csv_header);
  ASSERT_EQ(csv.rows.size(), 4u);
  const double expected[4][6] = {{0.1, 0.0, 1.0, 0.0, 0.0, 0.0},
                                 {0.1, 0.0, 0.5, 1.0, -1.0, 0.0},
                                 {0.1, 0.0, 1.0, 0.0, 0.0, 0.0},
                                 {0.10998, -0.00998, 0.49902, 0.998, -0.998, -0.098}};
  for (std::size_t r = 0; r < 4; ++r) {
    EXPECT_EQ(csv.rows[r].step, r < 2 ? 0 : 1);
    EXPECT_EQ(csv.rows[r].t, r < 2 ? 0.0 : 0.01);
    EXPECT_EQ(csv.rows[r].particle, static_cast<long>(r % 2));
    for (std::size_t c = 0; c < 6; ++c) {
      EXPECT_NEAR(csv.rows[r].value[c], expected[r][c], 1e-15) << "row " << r << ", field " << c;
    }
  }
}

// --csv-every 3 over 10 steps writes steps 0, 3, 6, 9 and the last one, 10; t = step * dt.
TEST_F(cli, CsvEveryWritesEveryKthStepPlusTheFirstAndTheLast) {
  const run_result result = run({"--headless", "--stage", "coupled", "--chain", "2", "--dt",
                                 "0.005", "--steps", "10", "--csv-every", "3", "--csv", "c.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "c.csv");
  EXPECT_EQ(csv.header, csv_header);
  EXPECT_EQ(written_steps(csv, 3), (std::vector<long>{0, 3, 6, 9, 10}));
  for (const csv_row& row : csv.rows) {
    EXPECT_DOUBLE_EQ(row.t, static_cast<double>(row.step) * 0.005) << "step " << row.step;
  }
}

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

// When the last step is itself a multiple of K it is written once.
TEST_F(cli, CsvEveryWritesALastStepThatIsAMultipleOfKOnce) {
  const run_result result = run(
      {"--headless", "--stage", "spring", "--steps", "9", "--csv-every", "3", "--csv", "s.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(written_steps(read_csv(work() / "s.csv"), 2), (std::vector<long>{0, 3, 6, 9}));
}

// The tests that follow the cloth's motion need the lab's solution (questions 6 to 9, 13): in
// the student copy they fail until every question is answered (label cli-solution).
using SolutionCli = cli;

// Cloth N = 3, S = 1 (h = 0.5), pinned corners 0 and 2. Step 0: p(ku, kv) = (-0.5 + 0.5 ku,
// -0.5 + 0.5 kv, 0) at rest. Step 1 (dt = 0.002, springs at rest length, so gravity alone):
// free particles have v = (0, 0, -9.8 * 0.002) = (0, 0, -0.0196), pinned ones stay at rest.
TEST_F(SolutionCli, ClothCsvListsEveryParticleInIndexOrder) {
  const run_result result =
      run({"--headless", "--stage", "cloth", "--N", "3", "--steps", "1", "--csv", "cloth.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "cloth.csv");
  EXPECT_EQ(csv.header, csv_header);
  ASSERT_EQ(written_steps(csv, 9), (std::vector<long>{0, 1}));
  for (std::size_t k = 0; k < 9; ++k) {
    const csv_row& initial = csv.rows[k];
    EXPECT_DOUBLE_EQ(initial.value[0], -0.5 + 0.5 * static_cast<double>(k % 3)) << k;
    EXPECT_DOUBLE_EQ(initial.value[1], -0.5 + 0.5 * static_cast<double>(k / 3)) << k;
    EXPECT_EQ(initial.value[2], 0.0) << k;
    const csv_row& first = csv.rows[9 + k];
    const bool pinned = k == 0 || k == 2;
    EXPECT_EQ(first.value[3], 0.0) << k;
    EXPECT_EQ(first.value[4], 0.0) << k;
    EXPECT_NEAR(first.value[5], pinned ? 0.0 : -0.0196, 1e-15) << k;
  }
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
// at step 1 every particle (the corners too) has v = (0, 0, -4 * 0.001) = (0, 0, -0.004).
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
    EXPECT_NEAR(csv.rows[9 + k].value[5], -0.004, 1e-15) << k;
  }
}

// --wind-strength 3 --wind-dir 0,3,4 on the flat cloth (n = (0, 0, 1), u_w = (0, 0.6, 0.8)),
// without gravity, damping or pins, dt = 0.01: F = 3 * 0.8 * (0, 0, 1) = (0, 0, 2.4) N on each
// unit mass, so at step 1 v = (0, 0, 0.024) everywhere.
TEST_F(SolutionCli, WindOptionsReachTheCloth) {
  const run_result result =
      run({"--headless", "--stage",    "cloth", "--N",     "3",    "--pins", "none",
           "--gravity",  "0",          "--mu",  "0",       "--dt", "0.01",   "--wind-strength",
           "3",          "--wind-dir", "0,3,4", "--steps", "1",    "--csv",  "cloth.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "cloth.csv");
  ASSERT_EQ(written_steps(csv, 9), (std::vector<long>{0, 1}));
  for (std::size_t k = 9; k < 18; ++k) {
    EXPECT_NEAR(csv.rows[k].value[3], 0.0, 1e-12) << k;
    EXPECT_NEAR(csv.rows[k].value[4], 0.0, 1e-12) << k;
    EXPECT_NEAR(csv.rows[k].value[5], 0.024, 1e-12) << k;
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

// Bad usage: exit 2, exactly one line on stderr naming the option, nothing written.
struct bad_usage {
  std::string label;
  arguments args;
  std::string option;  // what the error line must name
};

void PrintTo(const bad_usage& c, std::ostream* os) {
  *os << c.label;
}

class cli_refuses : public cli, public ::testing::WithParamInterface<bad_usage> {};

TEST_P(cli_refuses, BadUsage) {
  arguments args = {"--headless", "--csv", "out.csv", "--obj", "out.obj"};
  const arguments with_defaults = headless_run(GetParam().args);
  args.insert(args.end(), with_defaults.begin() + 1, with_defaults.end());
  const run_result result = run(args);
  EXPECT_EQ(result.exit_code, 2) << join(args) << "\nstderr: " << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << join(args) << "\nstderr: " << result.err;
  EXPECT_FALSE(result.err.empty() || result.err.back() != '\n') << result.err;
  EXPECT_NE(result.err.find(GetParam().option), std::string::npos)
      << join(args) << "\nstderr does not name " << GetParam().option << ": " << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
  EXPECT_TRUE(fs::is_empty(work())) << join(args) << " wrote a file";
}

INSTANTIATE_TEST_SUITE_P(
    EveryKindOfBadInput, cli_refuses,
    ::testing::Values(
        bad_usage{"UnknownOption", {"--frobnicate", "3"}, "--frobnicate"},
        bad_usage{"MissingValue", {"--dt"}, "--dt"},
        bad_usage{"MalformedNumber", {"--dt", "abc"}, "--dt"},
        bad_usage{"TrailingGarbage", {"--dt", "0.01x"}, "--dt"},
        bad_usage{"NonIntegerGridSize", {"--N", "2.5"}, "--N"},
        bad_usage{"ZeroTimeStep", {"--dt", "0"}, "--dt"},
        bad_usage{"NegativeTimeStep", {"--dt", "-1"}, "--dt"},
        bad_usage{"GridOfOne", {"--N", "1"}, "--N"},
        bad_usage{"NegativeSteps", {"--steps", "-5"}, "--steps"},
        bad_usage{"ZeroMass", {"--mass", "0"}, "--mass"},
        bad_usage{"NegativeMass", {"--mass", "-1"}, "--mass"},
        bad_usage{"ZeroCsvEvery", {"--csv-every", "0"}, "--csv-every"},
        bad_usage{"EmptyChain", {"--stage", "coupled", "--chain", "0"}, "--chain"},
        bad_usage{"ZeroWindDirection", {"--wind-dir", "0,0,0"}, "--wind-dir"},
        bad_usage{"TwoComponentWindDirection", {"--wind-dir", "1,2"}, "--wind-dir"},
        bad_usage{"UnknownStage", {"--stage", "foo"}, "--stage"},
        bad_usage{"StageNumberOutOfRange", {"--stage", "3"}, "--stage"},
        bad_usage{"PinsNumberOutOfRange", {"--pins", "2"}, "--pins"},
        bad_usage{"UnknownIntegrator", {"--integrator", "foo"}, "--integrator"},
        bad_usage{"UnknownPins", {"--pins", "foo"}, "--pins"},
        bad_usage{"UnknownBackend", {"--backend", "foo"}, "--backend"},
        bad_usage{"MalformedGroundZ", {"--ground-z", "abc"}, "--ground-z"},
        bad_usage{"NaNTimeStep", {"--dt", "nan"}, "--dt"},
        bad_usage{"InfiniteTimeStep", {"--dt", "inf"}, "--dt"},
        bad_usage{"NaNStiffness", {"--K", "nan"}, "--K"},
        bad_usage{"InfiniteStructuralStiffness", {"--K-struct", "inf"}, "--K-struct"},
        bad_usage{"InfiniteDamping", {"--mu", "inf"}, "--mu"},
        bad_usage{"NaNGravity", {"--gravity", "nan"}, "--gravity"},
        bad_usage{"MinusInfiniteMass", {"--mass", "-inf"}, "--mass"},
        bad_usage{"InfiniteSize", {"--size", "inf"}, "--size"},
        bad_usage{"NaNWindStrength", {"--wind-strength", "nan"}, "--wind-strength"},
        bad_usage{"NaNWindDirection", {"--wind-dir", "nan,0,1"}, "--wind-dir"},
        bad_usage{"NaNGroundZ", {"--ground-z", "nan"}, "--ground-z"},
        bad_usage{"NaNGroundFriction", {"--ground-friction", "nan"}, "--ground-friction"},
        bad_usage{
            "CpuOnlyIntegratorOnGpu", {"--backend", "gpu", "--integrator", "rk4"}, "--integrator"},
        bad_usage{"UnknownScaling", {"--scaling", "foo"}, "--scaling"},
        bad_usage{"ReferenceGridOfOne", {"--reference-N", "1"}, "--reference-N"},
        bad_usage{"DampingFactorNegative", {"--mu", "1000"}, "--mu"},
        bad_usage{"SweepDtWithoutSweep", {"--sweep-dt", "0.1,0.2"}, "--sweep-dt"},
        bad_usage{
            "MalformedSweepList", {"--sweep", "m.csv", "--sweep-dt", "0.1,abc"}, "--sweep-dt"},
        bad_usage{
            "SweepRangeWithoutCount", {"--sweep", "m.csv", "--sweep-dt", "0.1:0.2"}, "--sweep-dt"},
        bad_usage{"SweepNOnTheSingleSpring",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-N", "2,3"},
                  "--sweep-N"},
        bad_usage{"ZeroSweepTime", {"--sweep", "m.csv", "--sweep-time", "0"}, "--sweep-time"},
        // Issue 12: the bounds of docs/limits.md, each message naming the option.
        bad_usage{"HugeMassD1", {"--stage", "cloth", "--mass", "1e308"}, "--mass 1e+308"},
        bad_usage{"HugeTimeStepD2", {"--dt", "1e308"}, "--dt 1e+308"},
        bad_usage{"TimeStepAboveTenSeconds", {"--dt", "15"}, "--dt 15"},
        bad_usage{"SubnormalTimeStepD9", {"--dt", "1e-320"}, "between 1e-09 and 10 s"},
        bad_usage{"TimeStepOverflowingADouble", {"--dt", "1e999"}, "--dt"},
        bad_usage{"HugeSizeD3", {"--size", "1.7976931348623157e308"}, "--size"},
        bad_usage{"LargeSizeD4", {"--size", "1e300"}, "between 0.001 and 1000 m"},
        bad_usage{"SubnormalSizeD4", {"--size", "1e-320"}, "--size"},
        bad_usage{"HugeStiffness", {"--K-struct", "2e9"}, "--K-struct 2e+09"},
        bad_usage{"HugeSpringStiffness", {"--stage", "spring", "--K", "1e10"}, "--K 1e+10"},
        bad_usage{"HugeGravity", {"--gravity", "1e4"}, "--gravity 10000"},
        bad_usage{"HugeWindStrength", {"--wind-strength", "-1e7"}, "--wind-strength"},
        bad_usage{"HugeWindDirection", {"--wind-dir", "1e300,0,0"}, "--wind-dir"},
        bad_usage{"SubnormalWindDirectionD9", {"--wind-dir", "1e-320,0,0"}, "at least 1e-06"},
        bad_usage{"GroundFarAway", {"--ground-z", "-1e4"}, "--ground-z -10000"},
        bad_usage{"TooManySteps", {"--steps", "2000000000"}, "--steps"},
        bad_usage{"HugeSizeInTheMiddleOfASweepD5",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-K", "1e-300:1e300:3"},
                  "--sweep-K 1e+300"},
        bad_usage{"SweepListValueOutOfRangeD5",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-dt", "0.01,50,0.02"},
                  "--sweep-dt 50"},
        bad_usage{"TinySweepTimeStepD6",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-dt", "1e-300"},
                  "--sweep-dt 1e-300"},
        bad_usage{"BackendOfNoKind", {"--backend", "quantum"}, "--backend"},
        // Issue 11: an option the chosen stage has no use for is refused, naming its stage.
        bad_usage{"GridSizeOnTheSpring", {"--stage", "spring", "--N", "50"}, "--N"},
        bad_usage{"WindOnTheSpring",
                  {"--stage", "spring", "--wind-strength", "5"},
                  "--wind-strength: the cloth's option"},
        bad_usage{"SpringStiffnessOnTheCloth", {"--K", "50"}, "--K: the spring stages'"},
        bad_usage{"ChainOnTheCloth", {"--chain", "5"}, "--chain: the chain's option"},
        bad_usage{"GroundFrictionOnTheSpring",
                  {"--stage", "spring", "--ground-friction", "2"},
                  "--ground-friction"},
        bad_usage{"UnknownContext", {"--gl", "vulkan"}, "--gl"},
        bad_usage{"ThreadsWithoutParallel", {"--threads", "2"}, "--threads"},
        bad_usage{"StartOnTheCloth", {"--start", "1d"}, "--start"},
        bad_usage{"StartUnknown", {"--stage", "spring", "--start", "2d"}, "--start"},
        // BEGIN TEACHER
        bad_usage{"TooManyThreads",
                  {"--backend", "cpu-parallel", "--threads", "100000"},
                  "--threads 100000"},
        // END TEACHER
        // COPY| bad_usage{"ParallelPathInTheTeachersCopy",
        // COPY|           {"--backend", "cpu-parallel"},
        // COPY|           "--backend cpu-parallel: the parallel CPU path (--backend cpu-parallel) is in the teacher's copy"},
        bad_usage{"ParallelSpring",
                  {"--stage", "spring", "--backend", "cpu-parallel"},
                  "--backend cpu-parallel"},
        bad_usage{"ComputeWithRk4",
                  {"--backend", "gpu-compute", "--integrator", "rk4"},
                  "--integrator rk4"},
        bad_usage{"DragOutsideTheGrid", {"--drag", "9,0:0,0,0"}, "outside the 4 x 4 grid"},
        bad_usage{"DragAPinnedCorner", {"--drag", "3,0:0,0,0"}, "is pinned"},
        bad_usage{"DragWithoutTarget", {"--drag", "1,1"}, "--drag 1,1"},
        bad_usage{"DragFarAway", {"--drag", "1,1:0,0,1e5"}, "--drag"},
        // The particle (KU, KV) is the cloth's: the masses of stages 1 and 2 take the mouse only.
        bad_usage{"DragOnTheChain",
                  {"--stage", "coupled", "--drag", "1,1:0,0,0"},
                  "--drag: the cloth's; use it with --stage cloth"},
        bad_usage{"DragOnTheSpring",
                  {"--stage", "spring", "--drag", "0,1:0,0,0"},
                  "--drag: the cloth's; use it with --stage cloth"},
        bad_usage{"DragStiffnessOutOfRangeOnTheChain",
                  {"--stage", "coupled", "--drag-stiffness", "-5"},
                  "--drag-stiffness -5"},
        bad_usage{"SphereWithoutRadius", {"--sphere", "0,0,0"}, "--sphere"},
        bad_usage{"SphereOfNoRadius", {"--sphere", "0,0,0,0"}, "--sphere 0"},
        bad_usage{"SphereFrictionTooHigh",
                  {"--sphere", "0,0,0,1", "--sphere-friction", "1e4"},
                  "--sphere-friction"},
        bad_usage{"NegativeTearStrain", {"--tear-strain", "-0.1"}, "--tear-strain"},
        bad_usage{"SelfCollisionOnTheGpu",
                  {"--self-collision", "0.01", "--backend", "gpu"},
                  "--self-collision"},
        bad_usage{"SphereOnTheSpring", {"--stage", "spring", "--sphere", "0,0,0,1"}, "--sphere"}),
    [](const ::testing::TestParamInfo<bad_usage>& param_info) { return param_info.param.label; });

// K = 1e6 and dt = 0.1 (w dt = 100, far above 2): the spring explodes. Exit 3, one stderr line
// naming the step s at which the state stopped being finite, and the CSV holds steps 0 .. s-1,
// all finite.
TEST_F(cli, DivergenceExitsThreeAndKeepsEveryFiniteStep) {
  const arguments args = {"--headless", "--stage", "spring", "--K",   "1e6",         "--dt",
                          "0.1",        "--steps", "1000",   "--csv", "diverged.csv"};
  const run_result result = run(args);
  EXPECT_EQ(result.exit_code, 3) << "stderr: " << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << result.err;
  const csv_file csv = read_csv(work() / "diverged.csv");
  EXPECT_EQ(csv.header, csv_header);
  const std::vector<long> steps = written_steps(csv, 2);
  ASSERT_GE(steps.size(), 2u);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(steps[i], static_cast<long>(i));
  }
  ASSERT_LT(steps.back(), 999) << "the run must have stopped early";
  for (const csv_row& row : csv.rows) {
    for (const double value : row.value) {
      ASSERT_TRUE(std::isfinite(value)) << "step " << row.step;
    }
  }
  const std::string diverged_step = std::to_string(steps.back() + 1);
  EXPECT_NE(result.err.find("step"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(diverged_step), std::string::npos)
      << "expected the step " << diverged_step << " in: " << result.err;
}

// Without --headless clothlab opens the window; with no display to open it on, that is "any
// other failure": exit 1 with a message.
TEST_F(cli, WindowWithoutADisplayExitsOne) {
  const run_result result = run({"--stage", "spring"}, true);
  EXPECT_EQ(result.exit_code, 1) << result.err;
  EXPECT_FALSE(result.err.empty());
}

TEST_F(cli, UnwritableCsvExitsOne) {
  const run_result result =
      run({"--headless", "--stage", "spring", "--steps", "2", "--csv", "/nonexistent-dir/x.csv"});
  EXPECT_EQ(result.exit_code, 1) << result.err;
  EXPECT_FALSE(result.err.empty());
}

TEST_F(cli, UnwritableObjExitsOne) {
  const run_result result =
      run({"--headless", "--N", "3", "--steps", "2", "--obj", "/nonexistent-dir/x.obj"});
  EXPECT_EQ(result.exit_code, 1) << result.err;
  EXPECT_FALSE(result.err.empty());
}

// N = 5: 25 positions, 25 normals, 25 texture coordinates, 2 * 4^2 = 32 triangles.
TEST_F(cli, ObjHoldsTheClothsVerticesAndTriangles) {
  const run_result result =
      run({"--headless", "--stage", "cloth", "--N", "5", "--steps", "10", "--obj", "cloth.obj"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::ifstream obj(work() / "cloth.obj");
  std::string line;
  int positions = 0;
  int normals = 0;
  int texture_coordinates = 0;
  int triangles = 0;
  while (std::getline(obj, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    positions += tag == "v";
    normals += tag == "vn";
    texture_coordinates += tag == "vt";
    if (tag == "f") {
      ++triangles;
      std::string corner;
      int corners = 0;
      while (fields >> corner) {
        const long vertex = std::strtol(corner.c_str(), nullptr, 10);
        EXPECT_TRUE(vertex >= 1 && vertex <= 25) << line;
        ++corners;
      }
      EXPECT_EQ(corners, 3) << line;
    }
  }
  EXPECT_EQ(positions, 25);
  EXPECT_EQ(normals, 25);
  EXPECT_EQ(texture_coordinates, 25);
  EXPECT_EQ(triangles, 32);
}

// Tearing on both CPU paths (issue 10): a corner of the 8 x 8 cloth pulled hard tears springs,
// and the OBJ drops the triangles that lost one (2 * 7^2 = 98 when none has); cpu-parallel hands
// its torn springs back, so both write the same faces.
TEST_F(SolutionCli, TornTrianglesLeaveTheObjOnBothCpuPaths) {
  std::vector<int> faces;
  // BEGIN TEACHER
  const std::vector<const char*> backends = {"cpu", "cpu-parallel"};
  // END TEACHER
  // COPY| const std::vector<const char*> backends = {"cpu"};  // the copy has no cpu-parallel
  for (const char* backend : backends) {
    const run_result result = run({"--headless", "--N", "8", "--steps", "300", "--tear-strain",
                                   "0.15", "--drag", "7,7:1.5,1.5,0.5", "--drag-stiffness", "20000",
                                   "--backend", backend, "--obj", "torn.obj"});
    ASSERT_EQ(result.exit_code, 0) << backend << ": " << result.err;
    std::ifstream obj(work() / "torn.obj");
    int count = 0;
    for (std::string line; std::getline(obj, line);)
      count += line.rfind("f ", 0) == 0;
    faces.push_back(count);
  }
  EXPECT_LT(faces[0], 98) << "the cloth must tear";
  // BEGIN TEACHER
  EXPECT_EQ(faces[1], faces[0]) << "cpu-parallel's OBJ against cpu's";
  // END TEACHER
}

}  // namespace

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

// Energies at step 0 of the single spring, by hand (m = 1, g0 = 9.8): kinetic m |v|^2 / 2 with
// v = (1, -1, 0) is 1; gravity m g0 z of p1 at z = 0.5 is 4.9 (p0 is fixed and counts nothing);
// the spring is at its rest length, 0; total 5.9. Columns as documented.
TEST_F(cli, EnergyCsvStartsWithTheHandComputedEnergies) {
  const run_result result = run({"--headless", "--stage", "spring", "--steps", "4", "--csv-every",
                                 "2", "--energy-csv", "energy.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::istringstream text(read_file(work() / "energy.csv"));
  std::string line;
  std::getline(text, line);
  EXPECT_EQ(line, "step,t,kinetic,gravity,spring,total");
  std::getline(text, line);
  double step = 0, t = 0, kinetic = 0, gravity = 0, spring = 0, total = 0;
  ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &step, &t, &kinetic, &gravity,
                        &spring, &total),
            6)
      << line;
  EXPECT_EQ(step, 0);
  EXPECT_DOUBLE_EQ(kinetic, 1.0);
  EXPECT_DOUBLE_EQ(gravity, 4.9);
  EXPECT_DOUBLE_EQ(spring, 0.0);
  EXPECT_DOUBLE_EQ(total, 5.9);
  int rows = 1;
  while (std::getline(text, line))
    ++rows;
  EXPECT_EQ(rows, 3) << "steps 0, 2 and 4";
}

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

// The shared options set the chosen stage only (issue 11): mu = 300 is fine for the cloth
// (dt = 0.002, mu dt = 0.6), in the window too, whose spring stages keep their own default mu;
// on the spring (dt = 0.01) it would make the damping factor 1 - 300 * 0.01 = -2: refused.
TEST_F(cli, DampingIsCheckedForTheChosenStageOnly) {
  const run_result window = run({"--stage", "cloth", "--mu", "300"}, true);  // no display: exit 1
  EXPECT_EQ(window.exit_code, 1) << window.err;
  EXPECT_EQ(window.err.find("--mu"), std::string::npos) << window.err;
  const run_result headless =
      run({"--headless", "--stage", "cloth", "--N", "4", "--steps", "2", "--mu", "300"});
  EXPECT_EQ(headless.exit_code, 0) << headless.err;
  const run_result spring = run({"--headless", "--stage", "spring", "--steps", "2", "--mu", "300"});
  EXPECT_EQ(spring.exit_code, 2) << spring.err;
  EXPECT_NE(spring.err.find("--mu 300"), std::string::npos) << spring.err;
  EXPECT_NE(spring.err.find("spring"), std::string::npos) << spring.err;
}

// A subnormal value is read as the number it is and then refused by the option's range, naming
// the bound, whatever the option (D9): no option calls it "not a finite number".
TEST_F(cli, SubnormalValuesAreRefusedByTheirRangeAlike) {
  for (const arguments& args : {arguments{"--dt", "1e-320"}, arguments{"--size", "1e-320"},
                                arguments{"--mass", "1e-320"}}) {
    const run_result result = run(headless_run(args));
    EXPECT_EQ(result.exit_code, 2) << join(args);
    EXPECT_NE(result.err.find("must be between"), std::string::npos) << result.err;
  }
  const run_result ground = run(headless_run({"--ground-z", "1e-320"}));
  EXPECT_EQ(ground.exit_code, 0) << "1e-320 is inside --ground-z's range: " << ground.err;
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

// D7: a device that takes no data. Each output reports the failure (exit 1, naming the file)
// instead of exit 0.
TEST_F(cli, EveryOutputToAFullDeviceExitsOne) {
  const std::vector<arguments> cases = {
      {"--N", "3", "--steps", "1", "--csv", "/dev/full"},
      {"--N", "3", "--steps", "1", "--energy-csv", "/dev/full"},
      {"--N", "3", "--steps", "1", "--obj", "/dev/full"},
      {"--N", "3", "--steps", "1", "--png", "/dev/full", "--width", "32", "--height", "32"},
      {"--stage", "spring", "--sweep", "/dev/full", "--sweep-dt", "0.01", "--sweep-K", "1"}};
  for (arguments args : cases) {
    args.insert(args.begin(), "--headless");
    const run_result result = run(args);
    EXPECT_EQ(result.exit_code, 1) << join(args) << "\n" << result.err;
    EXPECT_NE(result.err.find("/dev/full"), std::string::npos) << result.err;
  }
}

// D8: a disk that fills up during the run (a file-size limit): exit 1 naming the file, no
// partial file, and a file of the same name from before left as it was.
TEST_F(cli, FailedWriteLeavesNoPartialFileAndTheOldOneIntact) {
  const struct {
    const char* option;
    const char* name;
    arguments more;
  } cases[] = {
      {"--csv", "states.csv", {"--N", "10", "--steps", "200"}},
      {"--energy-csv", "energy.csv", {"--N", "10", "--steps", "20000"}},
      {"--obj", "cloth.obj", {"--N", "60", "--steps", "2"}},
      {"--png", "cloth.png", {"--N", "10", "--steps", "2", "--width", "400", "--height", "300"}}};
  file_size_limit = 4096;
  for (const auto& c : cases) {
    std::ofstream(work() / c.name) << "old\n";
    arguments args = {"--headless", c.option, c.name};
    args.insert(args.end(), c.more.begin(), c.more.end());
    const run_result result = run(args);
    EXPECT_EQ(result.exit_code, 1) << join(args) << "\n" << result.err;
    EXPECT_NE(result.err.find(std::string(c.option) + " " + c.name), std::string::npos)
        << result.err;
    EXPECT_EQ(read_file(work() / c.name), "old\n") << c.name;
    for (const fs::directory_entry& entry : fs::directory_iterator(work()))
      EXPECT_NE(entry.path().filename().string().front(), '.') << "left " << entry.path();
    fs::remove(work() / c.name);
  }
}

// The files of a headless run appear whole or not at all: while it runs they are hidden
// temporary files, renamed into place at the end.
TEST_F(cli, FilesAppearOnlyWhenWhole) {
  const pid_t child = start({"--headless", "--N", "30", "--steps", "1000000000", "--csv", "s.csv"});
  bool temporary_seen = false;
  for (int i = 0; i < 500 && !temporary_seen; ++i) {
    for (const fs::directory_entry& entry : fs::directory_iterator(work()))
      temporary_seen = temporary_seen || entry.path().filename().string().rfind(".s.csv.", 0) == 0;
    usleep(10000);
  }
  EXPECT_TRUE(temporary_seen);
  EXPECT_FALSE(fs::exists(work() / "s.csv")) << "the CSV appeared before the run ended";
  kill(child, SIGTERM);
  const run_result result = finish(child);
  EXPECT_EQ(result.exit_code, 143) << result.err;
  EXPECT_TRUE(fs::exists(work() / "s.csv"));
}

// D10: SIGINT, SIGTERM and SIGHUP during a run end it after a whole step: exit 128 + signal,
// one line naming the signal, and a CSV of whole lines and whole steps.
class cli_signals : public cli, public ::testing::WithParamInterface<int> {};

TEST_P(cli_signals, StopTheRunWithWholeLines) {
  const int signal_number = GetParam();
  const long particles = 30 * 30;
  const pid_t child = start({"--headless", "--N", "30", "--steps", "1000000000", "--csv", "s.csv"});
  // Wait until the run has written something (its temporary file holds more than 200 kB).
  bool written = false;
  for (int i = 0; i < 1000 && !written; ++i) {
    for (const fs::directory_entry& entry : fs::directory_iterator(work()))
      written = written || (entry.is_regular_file() && entry.file_size() > 200000);
    usleep(10000);
  }
  ASSERT_TRUE(written);
  kill(child, signal_number);
  const run_result result = finish(child);
  EXPECT_EQ(result.exit_code, 128 + signal_number) << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << result.err;
  EXPECT_NE(result.err.find("interrupted"), std::string::npos) << result.err;
  const std::string text = read_file(work() / "s.csv");
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "the last line is cut";
  const csv_file csv = read_csv(work() / "s.csv");
  EXPECT_EQ(csv.header, csv_header);
  const std::vector<long> steps = written_steps(csv, particles);
  ASSERT_GE(steps.size(), 2u);
  EXPECT_NE(result.err.find("after step " + std::to_string(steps.back())), std::string::npos)
      << result.err;
  for (const fs::directory_entry& entry : fs::directory_iterator(work()))
    EXPECT_NE(entry.path().filename().string().front(), '.') << "left " << entry.path();
}

INSTANTIATE_TEST_SUITE_P(InterruptSignals, cli_signals, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& param_info) {
                           return std::string(param_info.param == SIGINT    ? "SIGINT"
                                              : param_info.param == SIGTERM ? "SIGTERM"
                                                                            : "SIGHUP");
                         });

// D11: two runs writing the same CSV at once. Each writes its own temporary file and renames it
// into place: the CSV is the whole output of one of them, not a mixture.
TEST_F(cli, TwoRunsWritingOneFileLeaveOneWholeOutput) {
  const arguments a = {"--headless", "--stage", "spring", "--K", "10", "--steps", "20000"};
  const arguments b = {"--headless", "--stage", "spring", "--K", "30", "--steps", "20000"};
  auto with_csv = [](arguments args, const char* name) {
    args.insert(args.end(), {"--csv", name});
    return args;
  };
  ASSERT_EQ(run(with_csv(a, "a.csv")).exit_code, 0);
  ASSERT_EQ(run(with_csv(b, "b.csv")).exit_code, 0);
  const std::string alone_a = read_file(work() / "a.csv");
  const std::string alone_b = read_file(work() / "b.csv");
  ASSERT_NE(alone_a, alone_b);
  for (int attempt = 0; attempt < 3; ++attempt) {
    const pid_t first = start(with_csv(a, "same.csv"), false, "a");
    const pid_t second = start(with_csv(b, "same.csv"), false, "b");
    EXPECT_EQ(finish(first, "a").exit_code, 0);
    EXPECT_EQ(finish(second, "b").exit_code, 0);
    const std::string together = read_file(work() / "same.csv");
    EXPECT_TRUE(together == alone_a || together == alone_b)
        << "a mixture of " << together.size() << " bytes";
  }
}

// Progress: on a terminal a line at most every second; nothing when standard error is a file
// (every other test).
TEST_F(cli, ProgressIsShownOnATerminalOnly) {
  int terminal = -1;
  const pid_t child = forkpty(&terminal, nullptr, nullptr, nullptr);
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::string program = clothlab_test::executable_path;
    if (chdir(work().c_str()) != 0)
      _exit(126);
    // The single spring (the code of no lab question): damped, it never diverges.
    execl(program.c_str(), program.c_str(), "--headless", "--stage", "spring", "--steps",
          "1000000000", static_cast<char*>(nullptr));
    _exit(127);
  }
  std::string seen;
  const auto start_time = std::chrono::steady_clock::now();
  bool interrupted = false;
  for (;;) {
    pollfd ready{terminal, POLLIN, 0};
    if (poll(&ready, 1, 100) > 0) {
      char buffer[512];
      const ssize_t n = read(terminal, buffer, sizeof buffer);
      if (n <= 0)
        break;  // the run ended and closed the terminal
      seen.append(buffer, static_cast<std::size_t>(n));
    }
    if (!interrupted && std::chrono::steady_clock::now() - start_time > std::chrono::seconds(3)) {
      kill(child, SIGINT);
      interrupted = true;
    }
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << status << "\n" << seen;
  EXPECT_NE(seen.find("\rclothlab: step "), std::string::npos) << seen;
  EXPECT_NE(seen.find(" of 1000000000 ("), std::string::npos) << seen;
  EXPECT_LE(std::count(seen.begin(), seen.end(), '\r'), 12) << "more than one line a second";

  const run_result plain = run({"--headless", "--N", "30", "--steps", "3000"});
  EXPECT_EQ(plain.exit_code, 0);
  EXPECT_TRUE(plain.err.empty()) << plain.err;
}

// BEGIN TEACHER (the student copy has no compute path)
namespace {

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

}  // namespace
// END TEACHER

// Issue 22: the edges of every input.
namespace {

bool temporary_file_left(const fs::path& folder) {
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().filename().string().front() == '.')
      return true;
  }
  return false;
}

// An empty value is an error naming the option, whatever the option: CLI11 used to read ''
// as 0 (--steps '' ran 0 steps, --N '' was "--N 0") and an empty path as no file at all.
TEST_F(cli, EmptyValuesAreRefusedNamingTheOption) {
  const std::vector<arguments> cases = {{"--steps", ""},
                                        {"--N", ""},
                                        {"--dt", ""},
                                        {"--csv", ""},
                                        {"--energy-csv", ""},
                                        {"--obj", ""},
                                        {"--png", ""},
                                        {"--sweep", ""},
                                        {"--stage", ""},
                                        {"--wind-dir", ""},
                                        {"--ground-z", ""},
                                        {"--drag", ""},
                                        {"--sphere", ""},
                                        {"--self-collision", ""},
                                        {"--csv-every", ""},
                                        {"--width", ""},
                                        {"--integrator", ""},
                                        {"--sweep", "m.csv", "--sweep-N", ""},
                                        {"--sweep", "m.csv", "--sweep-dt", ""}};
  for (arguments args : cases) {
    args.insert(args.begin(), "--headless");
    const run_result result = run(args);
    const std::string option = args[args.size() - 2];
    EXPECT_EQ(result.exit_code, 2) << join(args) << "\n" << result.err;
    EXPECT_EQ(count_lines(result.err), 1u) << join(args) << "\n" << result.err;
    EXPECT_TRUE(result.err.find(option + " ''") != std::string::npos ||
                result.err.find(option + ":") != std::string::npos)
        << join(args) << "\n"
        << result.err;
    EXPECT_TRUE(fs::is_empty(work())) << join(args) << " wrote a file";
  }
}

// A value with a newline (or another control character) is quoted escaped: the message stays
// one line.
TEST_F(cli, ValuesWithANewlineStayOnOneLine) {
  const std::vector<arguments> cases = {{"--dt", "1\n2"},
                                        {"--stage", "cloth\nspring"},
                                        {"--wind-dir", "1,0,\n0"},
                                        {"--sweep", "m.csv", "--sweep-dt", "0.01,\n0.02"},
                                        {"--csv", "no-such-folder/a\nb.csv"},
                                        {"--frobnicate\n", "1"}};
  for (arguments args : cases) {
    args.insert(args.begin(), "--headless");
    const run_result result = run(args);
    EXPECT_NE(result.exit_code, 0) << join(args);
    EXPECT_EQ(count_lines(result.err), 1u) << join(args) << "\n" << result.err;
    EXPECT_TRUE(fs::is_empty(work())) << join(args) << " wrote a file";
  }
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

// A process started by the tests below, with what they need that cli::start() does not do.
struct spawn_settings {
  std::vector<std::string> argv;         // argv[0]: the program
  fs::path folder;                       // its working folder; stdout and stderr go beside it
  bool block_sigint = false;             // start it with SIGINT blocked
  uid_t user = 0;                        // 0: as the test; else setuid to it (the test is root)
  std::vector<std::string> environment;  // NAME=VALUE added

  spawn_settings(std::vector<std::string> command, fs::path in)
      : argv(std::move(command)), folder(std::move(in)) {}
};

// Starts the process; returns its pid once it has replaced the forked copy of the test (a
// close-on-exec pipe closes), so that a signal sent after it reaches clothlab, not the copy.
pid_t spawn(const spawn_settings& how) {
  std::vector<std::string> copies = how.argv;
  std::vector<char*> argv;
  for (std::string& arg : copies)
    argv.push_back(arg.data());
  argv.push_back(nullptr);
  int exec_done[2];
  if (pipe(exec_done) != 0)  // (close-on-exec both ends: pipe2 is Linux's alone)
    return -1;
  for (const int end : exec_done)
    fcntl(end, F_SETFD, FD_CLOEXEC);
  const pid_t child = fork();
  if (child == 0) {
    const fs::path out = how.folder.parent_path() / "stdout.txt";
    const fs::path err = how.folder.parent_path() / "stderr.txt";
    const int out_fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    const int err_fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (out_fd < 0 || err_fd < 0 || dup2(out_fd, 1) < 0 || dup2(err_fd, 2) < 0 ||
        chdir(how.folder.c_str()) != 0)
      _exit(126);
    for (const std::string& variable : how.environment)
      putenv(const_cast<char*>(variable.c_str()));
    if (how.block_sigint) {
      sigset_t set;
      sigemptyset(&set);
      sigaddset(&set, SIGINT);
      sigprocmask(SIG_BLOCK, &set, nullptr);
    }
    // A failure here says why on the child's standard error (the test prints it).
    const auto fail = [](const char* what, int status) {
      const std::string line = std::string("spawn: ") + what + ": " + std::strerror(errno) + "\n";
      (void)!write(2, line.data(), line.size());
      _exit(status);
    };
    if (how.user != 0 && (setgroups(0, nullptr) != 0 || setgid(how.user) != 0))
      fail("cannot take the group of the user", 126);
    if (how.user != 0 && setuid(how.user) != 0)
      fail("cannot become the user", 126);
    // A bound against a hang, far above a run's time on a loaded machine (the test waits for
    // the process's end, not for a time).
    alarm(240);
    execv(argv[0], argv.data());
    fail(argv[0], 127);
  }
  close(exec_done[1]);
  char byte;
  while (read(exec_done[0], &byte, 1) < 0 && errno == EINTR) {
  }
  close(exec_done[0]);
  return child;
}

struct ended {
  bool exited = false;  // false: killed by a signal
  int code = -1;        // the exit status, or the signal
  std::string err;
};

ended wait_for(pid_t child, const fs::path& folder) {
  int status = 0;
  ended result;
  if (child < 0 || waitpid(child, &status, 0) != child)
    return result;
  result.exited = WIFEXITED(status);
  result.code = result.exited ? WEXITSTATUS(status) : WTERMSIG(status);
  result.err = read_file(folder.parent_path() / "stderr.txt");
  return result;
}

arguments clothlab_command(const arguments& args) {
  arguments argv = {clothlab_test::executable_path};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

// SIGINT at any moment, from the first microsecond to past the end of the run: the run either
// ends whole (exit 0, every file there) or reports the signal in one line with exit 130, the
// OBJ not written and the CSV of whole lines; never a death by the signal, never a temporary
// file left. Before issue 22, a signal in the first 5-200 ms killed clothlab silently, and one
// near the end left the OBJ written with exit 130. The process starts with SIGINT blocked, so
// that a signal sent during the dynamic loader's start (about a millisecond, before any code of
// clothlab can run: docs/limits.md) waits for clothlab's handler, which unblocks it.
TEST_F(cli, SignalAtAnyMomentIsReportedOrTooLate) {
  const arguments run = {"--headless", "--N",   "20",    "--steps", "2000", "--csv-every",
                         "50",         "--csv", "s.csv", "--obj",   "s.obj"};
  // Microseconds after the start: the first ones, then random moments up to past the end (the
  // run itself takes about 0.1 s of CPU), from a seed that a failure names.
  const unsigned seed = std::random_device{}();
  std::mt19937 random(seed);
  std::vector<long> delays = {0, 1000};
  for (int i = 0; i < 7; ++i)
    delays.push_back(std::uniform_int_distribution<long>(0, 300000)(random));
  // A signal sent before any code of clothlab runs (held back until then) is reported.
  {
    spawn_settings how{clothlab_command(run), work()};
    how.block_sigint = true;
    const pid_t child = spawn(how);
    kill(child, SIGINT);
    const ended result = wait_for(child, work());
    EXPECT_TRUE(result.exited && result.code == 130) << result.code << ": " << result.err;
    EXPECT_EQ(count_lines(result.err), 1u) << result.err;
    EXPECT_TRUE(fs::is_empty(work()));
  }
  for (std::size_t trial = 0; trial < delays.size(); ++trial) {
    fs::remove_all(work());
    fs::create_directory(work());
    spawn_settings how{clothlab_command(run), work()};
    how.block_sigint = true;
    const pid_t child = spawn(how);
    usleep(static_cast<useconds_t>(delays[trial]));
    kill(child, SIGINT);
    const ended result = wait_for(child, work());
    const std::string what = "SIGINT " + std::to_string(delays[trial]) +
                             " us after the start (seed " + std::to_string(seed) + ")";
    ASSERT_TRUE(result.exited) << what << ": killed by signal " << result.code;
    EXPECT_FALSE(temporary_file_left(work())) << what;
    if (result.code == 0) {
      EXPECT_TRUE(result.err.empty()) << what << ": " << result.err;
      EXPECT_TRUE(fs::exists(work() / "s.csv") && fs::exists(work() / "s.obj")) << what;
      continue;
    }
    EXPECT_EQ(result.code, 130) << what << ": " << result.err;
    EXPECT_EQ(count_lines(result.err), 1u) << what << ": " << result.err;
    EXPECT_NE(result.err.find("interrupted by SIGINT"), std::string::npos) << what << result.err;
    EXPECT_FALSE(fs::exists(work() / "s.obj")) << what << ": the OBJ of an interrupted run";
    if (fs::exists(work() / "s.csv")) {
      const std::string text = read_file(work() / "s.csv");
      EXPECT_TRUE(!text.empty() && text.back() == '\n') << what;
    }
  }
}

// timeout(1) sends SIGTERM to clothlab, then to its whole process group: clothlab twice. The
// second signal used to end clothlab at once, without a message, with its temporary file left
// and a sweep's finished cells lost. Now it changes nothing: one line, exit 143, no temporary
// file, and the sweep's CSV with the cells done.
TEST_F(cli, TimeoutsTwoSignalsLeaveWholeFiles) {
  const std::vector<arguments> runs = {
      {"--headless", "--stage", "spring", "--sweep", "s.csv", "--sweep-dt", "1e-4:1e-3:8",
       "--sweep-K", "1:100:8", "--sweep-time", "1000"},
      {"--headless", "--N", "20", "--steps", "1000000000", "--csv-every", "100", "--csv", "s.csv"}};
  // Under timeout itself (SIGTERM sent to timeout, which passes it on as on expiry), then the
  // same two signals sent by hand 20 ms apart (two signals sent back to back to a process that
  // is not running merge into one). Each once the run has begun: its CSV's temporary file is
  // there (on a loaded machine a fixed 0.3 s could end before the program had started).
  const auto run_has_begun = [this] {
    for (int i = 0; i < 6000; ++i) {
      for (const auto& entry : fs::directory_iterator(work()))
        if (entry.path().filename().string().starts_with(".s.csv."))
          return true;
      usleep(10000);
    }
    return false;
  };
  for (const arguments& run : runs) {
    for (const bool by_timeout : {true, false}) {
      fs::remove_all(work());
      fs::create_directory(work());
      ended result;
      if (by_timeout) {
        arguments argv = {"/usr/bin/timeout", "--preserve-status", "1000"};
        const arguments command = clothlab_command(run);
        argv.insert(argv.end(), command.begin(), command.end());
        const pid_t timeout = spawn({argv, work()});
        EXPECT_TRUE(run_has_begun()) << join(run) << ": no CSV begun within 60 s";
        kill(timeout, SIGTERM);
        result = wait_for(timeout, work());
      } else {
        const pid_t child = spawn({clothlab_command(run), work()});
        EXPECT_TRUE(run_has_begun()) << join(run) << ": no CSV begun within 60 s";
        kill(child, SIGTERM);
        usleep(20000);
        kill(child, SIGTERM);
        result = wait_for(child, work());
      }
      const std::string what = join(run) + (by_timeout ? " under timeout" : " signalled twice");
      EXPECT_TRUE(result.exited && result.code == 143)
          << what << ": " << result.exited << " " << result.code << "\n"
          << result.err;
      EXPECT_EQ(count_lines(result.err), 1u) << what << ": " << result.err;
      EXPECT_NE(result.err.find("interrupted by SIGTERM"), std::string::npos) << result.err;
      EXPECT_FALSE(temporary_file_left(work())) << what;
      const std::string text = read_file(work() / "s.csv");
      EXPECT_TRUE(!text.empty() && text.back() == '\n') << what;
    }
  }
}

// A signal while the rows of a large step are being written (a million lines, a second and a
// half at N = 1024): the step's lines are taken back out, so that the CSV holds whole steps.
TEST_F(cli, SignalWhileALargeStepIsWrittenKeepsWholeSteps) {
  const spawn_settings how{
      clothlab_command({"--headless", "--N", "1024", "--steps", "3", "--csv", "c.csv"}), work()};
  const pid_t child = spawn(how);
  bool writing = false;  // the temporary CSV holds more than the header
  for (int i = 0; i < 3000 && !writing; ++i) {
    for (const fs::directory_entry& entry : fs::directory_iterator(work()))
      writing = writing || (entry.is_regular_file() && entry.file_size() > 4'000'000);
    usleep(2000);
  }
  kill(child, SIGTERM);
  const ended result = wait_for(child, work());
  ASSERT_TRUE(result.exited) << result.code;
  EXPECT_EQ(result.code, 143) << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << result.err;
  EXPECT_NE(result.err.find("while step 0 of 3 was being written"), std::string::npos)
      << result.err;
  EXPECT_FALSE(temporary_file_left(work()));
  const std::string text = read_file(work() / "c.csv");
  const std::size_t lines = count_lines(text);
  EXPECT_EQ((lines - 1) % (1024 * 1024), 0u) << lines << " lines: a step cut short";
}

// A signal after the last step, while the OBJ is being written: the OBJ is not written (it was,
// with exit 143, before issue 22), as docs/limits.md says of an interrupted run.
TEST_F(cli, SignalWhileTheObjIsWrittenLeavesNoObj) {
  const spawn_settings how{
      clothlab_command({"--headless", "--N", "512", "--steps", "0", "--csv-every", "10", "--csv",
                        "c.csv", "--obj", "c.obj"}),
      work()};
  const pid_t child = spawn(how);
  bool writing = false;  // the OBJ's temporary file has begun to fill
  for (int i = 0; i < 20000 && !writing; ++i) {
    for (const fs::directory_entry& entry : fs::directory_iterator(work())) {
      const std::string name = entry.path().filename().string();
      writing = writing || (name.rfind(".c.obj.", 0) == 0 && entry.file_size() > 0);
    }
    usleep(500);
  }
  ASSERT_TRUE(writing);
  kill(child, SIGTERM);
  const ended result = wait_for(child, work());
  ASSERT_TRUE(result.exited) << result.code;
  EXPECT_EQ(result.code, 143) << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << result.err;
  EXPECT_FALSE(fs::exists(work() / "c.obj"));
  EXPECT_TRUE(fs::exists(work() / "c.csv"));
  EXPECT_FALSE(temporary_file_left(work()));
}

// /dev/full: every output says why it failed, the energy CSV and the sweep included.
TEST_F(cli, FullDeviceMessagesSayWhy) {
  const std::vector<arguments> cases = {
      {"--N", "3", "--steps", "1", "--csv", "/dev/full"},
      {"--N", "3", "--steps", "1", "--energy-csv", "/dev/full"},
      {"--N", "3", "--steps", "1", "--obj", "/dev/full"},
      {"--stage", "spring", "--sweep", "/dev/full", "--sweep-dt", "0.01", "--sweep-K", "1"}};
  for (arguments args : cases) {
    args.insert(args.begin(), "--headless");
    const run_result result = run(args);
    EXPECT_EQ(result.exit_code, 1) << join(args) << "\n" << result.err;
    EXPECT_NE(result.err.find("No space left on device"), std::string::npos) << join(args) << "\n"
                                                                             << result.err;
  }
}

// A GLSL error is reported at its file and line, in the shader the loader compiles and in the
// file it includes (gpu_cloth_common.glsl, whose lines the compiler numbers in their own
// source string): "shaders/gpu_cloth_common.glsl:89(12): error: ...", exit 1.
TEST_F(cli, ShaderErrorsNameTheFileAndLineThatHoldThem) {
  const fs::path source =
      fs::path(clothlab_test::render_reference_directory).parent_path().parent_path().parent_path();
  for (const char* broken : {"gpu_cloth_common.glsl", "gpu_step.frag"}) {
    const fs::path data = root() / "data";
    fs::remove_all(data);
    fs::create_directories(data);
    fs::copy(source / "shaders", data / "shaders");
    fs::copy(source / "assets", data / "assets");
    const std::string text = read_file(data / "shaders" / broken);
    const long line = std::count(text.begin(), text.end(), '\n') + 1;
    std::ofstream(data / "shaders" / broken, std::ios::app)
        << "float broken_line() { return undeclared_name; }\n";
    spawn_settings how{clothlab_command({"--headless", "--gl", own_context, "--backend", "gpu",
                                         "--N", "4", "--steps", "1"}),
                       work()};
    how.environment = {"CLOTHLAB_DATA_DIR=" + data.string()};
    const ended result = wait_for(spawn(how), work());
    EXPECT_TRUE(result.exited && result.code == 1) << broken << ": " << result.err;
    const std::string place = std::string("shaders/") + broken + ":" + std::to_string(line);
    const std::string other_form = std::string("shaders/") + broken + "(" + std::to_string(line);
    EXPECT_TRUE(result.err.find(place) != std::string::npos ||
                result.err.find(other_form) != std::string::npos)
        << "expected " << place << " in: " << result.err;
    EXPECT_NE(result.err.find("undeclared_name"), std::string::npos) << result.err;
  }
}

// A data file missing (CLOTHLAB_DATA_DIR pointing at a copy without it) fails before step 1,
// naming the file, with the files of a previous run left as they were (a missing GPU shader
// used to replace an existing CSV with a header-only one; a missing drawing shader or texture
// was found only after the whole simulation).
TEST_F(cli, MissingDataFileFailsBeforeAnyOutput) {
  const fs::path source =
      fs::path(clothlab_test::render_reference_directory).parent_path().parent_path().parent_path();
  const struct {
    const char* missing;
    arguments args;
  } cases[] = {{"shaders/gpu_step.frag", {"--backend", "gpu", "--steps", "2000", "--csv", "s.csv"}},
               {"shaders/draw_lit.frag", {"--steps", "2000", "--csv", "s.csv", "--png", "p.png"}},
               {"assets/cloth.png", {"--steps", "2000", "--csv", "s.csv", "--png", "p.png"}}};
  for (const auto& c : cases) {
    const fs::path data = root() / "data";
    fs::remove_all(data);
    fs::create_directories(data);
    fs::copy(source / "shaders", data / "shaders");
    fs::copy(source / "assets", data / "assets");
    fs::remove(data / c.missing);
    std::ofstream(work() / "s.csv") << "old\n";
    arguments args = {"--headless", "--N", "10", "--gl", own_context};
    args.insert(args.end(), c.args.begin(), c.args.end());
    spawn_settings how{clothlab_command(args), work()};
    how.environment = {"CLOTHLAB_DATA_DIR=" + data.string()};
    const ended result = wait_for(spawn(how), work());
    EXPECT_TRUE(result.exited && result.code == 1) << c.missing << ": " << result.err;
    EXPECT_EQ(count_lines(result.err), 1u) << result.err;
    EXPECT_NE(result.err.find(fs::path(c.missing).filename().string()), std::string::npos)
        << result.err;
    EXPECT_EQ(read_file(work() / "s.csv"), "old\n") << c.missing;
    EXPECT_FALSE(fs::exists(work() / "p.png")) << c.missing;
    EXPECT_FALSE(temporary_file_left(work())) << c.missing;
  }
}

// A folder where nobody can reach: the first of the temporary folder, /tmp and /var/tmp whose
// every parent lets others through (a private TMPDIR, 0700, does not: nobody could not even
// start the program there). Empty when none does.
fs::path folder_others_can_reach() {
  for (const fs::path& candidate :
       {fs::temp_directory_path(), fs::path("/tmp"), fs::path("/var/tmp")}) {
    std::error_code ec;
    bool reachable = fs::is_directory(candidate, ec);
    for (fs::path p = candidate; reachable && !p.empty(); p = p.parent_path()) {
      reachable = (fs::status(p, ec).permissions() & fs::perms::others_exec) != fs::perms::none;
      if (p == p.root_path())
        break;
    }
    if (reachable)
      return candidate;
  }
  return {};
}

// A folder that takes no new file: an existing writable output is written in place, whatever
// the output (the CSV was, the OBJ and the PNG were refused with "Permission denied"). Run as
// an unprivileged user (root writes into any folder), nobody, on a copy of the program and of
// its data files in a folder nobody can reach (the build tree may lie in a home or a folder
// made by mkdtemp, 0700; so may the temporary folder).
TEST_F(cli, ReadOnlyFolderWritesEveryExistingWritableOutput) {
  if (geteuid() != 0)
    GTEST_SKIP() << "needs root, to run clothlab as nobody in a folder it cannot write";
  const fs::path base = folder_others_can_reach();
  if (base.empty())
    GTEST_SKIP() << "no temporary folder that others can reach (TMPDIR, /tmp, /var/tmp)";
  std::string pattern = (base / "clothlab-cli-nobody-XXXXXX").string();
  ASSERT_NE(mkdtemp(pattern.data()), nullptr) << std::strerror(errno);
  const fs::path tree = pattern;
  struct removed_at_the_end {
    fs::path path;
    ~removed_at_the_end() {
      std::error_code ignored;
      fs::permissions(path / "run" / "work", fs::perms(0755), ignored);
      fs::remove_all(path, ignored);
    }
  } cleanup{tree};
  const fs::path source =
      fs::path(clothlab_test::render_reference_directory).parent_path().parent_path().parent_path();
  const fs::path program = tree / "bin" / "clothlab";
  const fs::path data = tree / "data";
  const fs::path folder = tree / "run" / "work";  // stdout.txt and stderr.txt go to run/
  fs::create_directories(program.parent_path());
  fs::create_directories(folder);
  fs::create_directories(data);
  fs::copy_file(clothlab_test::executable_path, program);
  fs::copy(source / "shaders", data / "shaders", fs::copy_options::recursive);
  fs::copy(source / "assets", data / "assets", fs::copy_options::recursive);
  fs::permissions(tree, fs::perms(0755), fs::perm_options::add);
  for (const fs::path& path : fs::recursive_directory_iterator(tree))
    fs::permissions(path, fs::perms(0755), fs::perm_options::add);
  fs::permissions(folder.parent_path(), fs::perms(0777));
  // First, that nobody can run the program here at all (a user namespace without the user
  // nobody, or a file system mounted noexec, cannot): else the test has nothing to say.
  spawn_settings probe{{program.string(), "--version"}, folder};
  probe.user = 65534;  // nobody
  const ended probed = wait_for(spawn(probe), folder);
  if (!probed.exited || probed.code != 0)
    GTEST_SKIP() << "nobody cannot run " << program << " here: " << probed.err;
  for (const char* name : {"s.csv", "e.csv", "c.obj", "c.png"}) {
    std::ofstream(folder / name) << "old\n";
    fs::permissions(folder / name, fs::perms(0666));
  }
  fs::permissions(folder, fs::perms(0555));
  spawn_settings how{{program.string(), "--headless", "--gl",  own_context, "--N",          "4",
                      "--steps",        "2",          "--csv", "s.csv",     "--energy-csv", "e.csv",
                      "--obj",          "c.obj",      "--png", "c.png",     "--width",      "16",
                      "--height",       "16"},
                     folder};
  // (TMPDIR, where the PNG's writer writes first, one that nobody can use)
  how.environment = {"CLOTHLAB_DATA_DIR=" + data.string(), "TMPDIR=" + base.string()};
  how.user = 65534;
  const ended result = wait_for(spawn(how), folder);
  fs::permissions(folder, fs::perms(0755));
  EXPECT_TRUE(result.exited && result.code == 0)
      << (result.exited ? "exit " : "signal ") << result.code << ": " << result.err;
  for (const char* name : {"s.csv", "e.csv", "c.obj", "c.png"})
    EXPECT_NE(read_file(folder / name), "old\n") << name;
  EXPECT_EQ(read_file(folder / "c.png").substr(0, 8), "\x89PNG\r\n\x1a\n");
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
