// The files a run writes (docs/cli.md): the CSV of states against a hand computation, the OBJ,
// the energy CSV, and what happens when a file cannot be written (exit 1, no partial file, a
// full device, a read-only folder), the progress line on a terminal, missing and broken data
// files.
#include "cli_support.hpp"

namespace {

using namespace clothlab_cli_test;

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

// When the last step is itself a multiple of K it is written once.
TEST_F(cli, CsvEveryWritesALastStepThatIsAMultipleOfKOnce) {
  const run_result result = run(
      {"--headless", "--stage", "spring", "--steps", "9", "--csv-every", "3", "--csv", "s.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(written_steps(read_csv(work() / "s.csv"), 2), (std::vector<long>{0, 3, 6, 9}));
}

// Cloth N = 3, S = 1 (h = 0.5), two pinned corners (question 7: any two; the teacher's are 0 and
// 2). Step 0: p(ku, kv) = (-0.5 + 0.5 ku, -0.5 + 0.5 kv, 0) at rest. Step 1 (dt = 0.002, springs
// at rest length, so gravity alone): free particles have v = (0, 0, -9.8 * 0.002) =
// (0, 0, -0.0196), within the float rounding (1e-6) of an answer to question 6 that computes in
// single precision; pinned ones stay at rest.
TEST_F(SolutionCli, ClothCsvListsEveryParticleInIndexOrder) {
  const run_result result =
      run({"--headless", "--stage", "cloth", "--N", "3", "--steps", "1", "--csv", "cloth.csv"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const csv_file csv = read_csv(work() / "cloth.csv");
  EXPECT_EQ(csv.header, csv_header);
  ASSERT_EQ(written_steps(csv, 9), (std::vector<long>{0, 1}));
  int pinned_corners = 0;
  for (std::size_t k = 0; k < 9; ++k) {
    const csv_row& initial = csv.rows[k];
    EXPECT_DOUBLE_EQ(initial.value[0], -0.5 + 0.5 * static_cast<double>(k % 3)) << k;
    EXPECT_DOUBLE_EQ(initial.value[1], -0.5 + 0.5 * static_cast<double>(k / 3)) << k;
    EXPECT_EQ(initial.value[2], 0.0) << k;
    const csv_row& first = csv.rows[9 + k];
    const bool pinned = first.value[5] == 0.0;
    pinned_corners += pinned && k != 1 && k != 3 && k != 4 && k != 5 && k != 7;
    EXPECT_EQ(first.value[3], 0.0) << k;
    EXPECT_EQ(first.value[4], 0.0) << k;
    if (pinned)
      EXPECT_EQ(first.value[2], initial.value[2]) << k << ": a pinned particle never moves";
    else
      EXPECT_NEAR(first.value[5], -0.0196, 0.0196 * 1e-6) << k;
  }
  EXPECT_EQ(pinned_corners, 2) << "two pinned corners, each with a zero velocity";
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

}  // namespace
