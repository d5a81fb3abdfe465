// What the command line's tests share (cli_*_test.cpp): the fixture `cli`, which runs the
// clothlab executable as a subprocess in an empty directory of its own, the processes started
// by hand (signals, another user), and the readers of what a run wrote (the CSV of states).
#pragma once

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

namespace clothlab_cli_test {

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

std::string read_file(const fs::path& path);

std::string join(const arguments& args);

// The names of what a folder holds, for a failure's message: "s.csv s.obj", or "nothing".
std::string names_in(const fs::path& folder);

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

bool has_option(const arguments& args, const std::string& option);

// --headless, and small values for the options that the case does not set itself.
arguments headless_run(const arguments& extra);

std::size_t count_lines(const std::string& text);

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
csv_file read_csv(const fs::path& path);

// The steps present in the CSV, each with its particles listed exactly once in index order.
std::vector<long> written_steps(const csv_file& csv, long particle_count);

constexpr const char* csv_header = "step,t,particle,x,y,z,vx,vy,vz";

// The tests that follow the cloth's motion need the lab's solution (questions 6 to 9, 13): in
// the student copy they fail until every question is answered (label cli-solution).
using SolutionCli = cli;

bool temporary_file_left(const fs::path& folder);

// A process started by the tests below, with what they need that cli::start() does not do.
struct spawn_settings {
  std::vector<std::string> argv;  // argv[0]: the program
  fs::path folder;                // its working folder; stdout and stderr go beside it
  bool block_sigint = false;      // start it with SIGINT blocked
  // Start it with SIGINT blocked and already pending (raised before the exec, which keeps it):
  // a signal that arrived before any code of clothlab ran, whatever the machine's load.
  bool sigint_pending = false;
  uid_t user = 0;                        // 0: as the test; else setuid to it (the test is root)
  std::vector<std::string> environment;  // NAME=VALUE added

  spawn_settings(std::vector<std::string> command, fs::path in)
      : argv(std::move(command)), folder(std::move(in)) {}
};

// Starts the process; returns its pid once it has replaced the forked copy of the test (a
// close-on-exec pipe closes), so that a signal sent after it reaches clothlab, not the copy.
pid_t spawn(const spawn_settings& how);

struct ended {
  bool exited = false;  // false: killed by a signal
  int code = -1;        // the exit status, or the signal
  std::string err;
};

ended wait_for(pid_t child, const fs::path& folder);

arguments clothlab_command(const arguments& args);

}  // namespace clothlab_cli_test
