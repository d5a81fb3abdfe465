// A run stopped by SIGINT, SIGTERM or SIGHUP (docs/limits.md, "Exit status"): whole lines,
// whole steps, no OBJ or PNG, no temporary file, at any moment of the run.
#include "cli_support.hpp"

namespace {

using namespace clothlab_cli_test;

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

// SIGINT at any moment, from the first microsecond to past the end of the run: the run either
// ends whole (exit 0, every file there) or reports the signal in one line with exit 130, the
// OBJ not written and the CSV of whole lines; never a death by the signal, never a temporary
// file left (the first milliseconds, before the handler is installed, and the last ones, while
// the OBJ is written, are the moments to watch). The process starts with SIGINT blocked, so
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
  // A signal that came before any code of clothlab ran (held back until then) is reported, and
  // nothing is written. (Raised in the child before its exec: a kill after the spawn could come
  // after clothlab's first steps on a loaded machine.)
  {
    spawn_settings how{clothlab_command(run), work()};
    how.sigint_pending = true;
    const pid_t child = spawn(how);
    const ended result = wait_for(child, work());
    EXPECT_TRUE(result.exited && result.code == 130) << result.code << ": " << result.err;
    EXPECT_EQ(count_lines(result.err), 1u) << result.err;
    EXPECT_TRUE(fs::is_empty(work())) << "the interrupted run left " << names_in(work());
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

// A signal after the last step, while the OBJ is being written: the OBJ is not written, as
// docs/limits.md says of an interrupted run.
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

}  // namespace
