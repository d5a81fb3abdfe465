// A bounded random driver over clothlab's command line (issues 12 and 22). Starting from seeds
// (the reproducers D1-D9 of issue 12, those of issue 22, and a few ordinary runs) it mutates
// command lines (values of every kind, and empty, newline-bearing and list-shaped ones for
// every option), runs the clothlab executable on each in an empty folder, and checks what
// docs/cli.md and docs/limits.md promise:
//   - the exit status is 0, 1, 2 or 3 (143 only when the driver itself sent SIGTERM after the
//     time limit), never a crash signal;
//   - exit 2 prints exactly one line on standard error naming an option, nothing on standard
//     output, and writes no file; exit 1 prints a message;
//   - every file written holds only finite numbers and whole lines, and no temporary file is
//     left behind.
// Environment: CLOTHLAB_FUZZ_ITERATIONS (default 300), CLOTHLAB_FUZZ_SECONDS (wall-clock budget,
// default 45; 0: none), CLOTHLAB_FUZZ_SEED (default 12). Exit status 0 when every run passed.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "build_paths.hpp"

namespace {

namespace fs = std::filesystem;
using arguments = std::vector<std::string>;

// The seeds: issue 12's reproducers, then runs that exercise every output.
const std::vector<arguments> seeds = {
    {"--stage", "spring", "--mass", "1e308", "--steps", "1", "--energy-csv", "e.csv"},  // D1
    {"--gravity", "0", "--mu", "0", "--ground-friction", "0", "--dt", "1e308", "--N", "2",
     "--steps", "2", "--csv", "t.csv"},                                      // D2
    {"--size", "1.7976931348623157e308", "--steps", "0", "--csv", "c.csv"},  // D3
    {"--size", "1e300", "--N", "3", "--steps", "0", "--obj", "o.obj", "--energy-csv", "e.csv"},
    {"--size", "1e-320", "--N", "3", "--steps", "0", "--obj", "o.obj"},        // D4
    {"--stage", "spring", "--sweep", "s.csv", "--sweep-K", "1e-300:1e300:3"},  // D5
    {"--stage", "spring", "--sweep", "s.csv", "--sweep-dt", "1e-300"},         // D6
    {"--stage", "spring", "--sweep", "s.csv", "--sweep-dt", "1e-9"},
    {"--steps", "1", "--png", "/dev/full"},                          // D7
    {"--wind-dir", "1e-320,0,0", "--steps", "1", "--csv", "w.csv"},  // D9
    {"--ground-z", "1e-320", "--steps", "1", "--csv", "g.csv"},
    {"--dt", "1e-320", "--steps", "1", "--csv", "d.csv"},
    {"--stage", "spring", "--K", "1e6", "--dt", "0.1", "--steps", "100", "--csv", "x.csv"},
    {"--stage", "coupled", "--chain", "3", "--steps", "20", "--csv", "c.csv", "--energy-csv",
     "e.csv", "--csv-every", "3"},
    {"--N", "5", "--steps", "20", "--wind-strength", "20", "--wind-dir", "1,1,0", "--obj", "o.obj",
     "--csv", "c.csv", "--energy-csv", "e.csv"},
    {"--N", "4", "--steps", "5", "--integrator", "rk4", "--ground-z", "none", "--pins", "none",
     "--csv", "c.csv"},
    {"--N", "4", "--steps", "5", "--scaling", "resolution-independent", "--reference-N", "8",
     "--energy-csv", "e.csv"},
    {"--stage", "coupled", "--sweep", "s.csv", "--sweep-N", "1,2,3", "--sweep-dt", "0.01,0.1",
     "--sweep-time", "0.05"},
    {"--N", "3", "--steps", "2", "--png", "p.png", "--width", "16", "--height", "16"},
    // Issue 22's reproducers.
    {"--sweep", "s.csv", "--sweep-N", "1"},  // an uncaught exception, exit 134
    {"--sweep", "s.csv", "--sweep-N", "1:3:3"},
    {"--N", "200", "--self-collision", "0.436", "--steps", "2", "--csv-every", "2", "--csv",
     "c.csv"},  // 38 s a step before D was clamped to h
    {"--steps", ""},
    {"--N", ""},
    {"--csv", ""},
    {"--energy-csv", ""},
    {"--obj", ""},
    {"--png", ""},
    {"--sweep", ""},
    {"--dt", "0.01\n0.02"},
    {"--stage", "spring\ncloth"},
    {"--N", "3", "--steps", "1", "--csv", "a\nb.csv"},
    {"--stage", "spring", "--sweep", "s.csv", "--sweep-K", "1e-320:1:3", "--sweep-dt", "0.01",
     "--sweep-time", "0.05"},
    {"--stage", "spring", "--sweep", "s.csv", "--sweep-K", "1:1e-320:3", "--sweep-dt", "0.01",
     "--sweep-time", "0.05"},
    {"--stage", "spring", "--sweep", "s.csv", "--sweep-K", "0x1p-1074:1:2", "--sweep-dt", "0.01",
     "--sweep-time", "0.05"},
    {"--N", "3", "--steps", "1", "--energy-csv", "/dev/full"},
    {"--stage", "spring", "--sweep", "/dev/full", "--sweep-dt", "0.01", "--sweep-K", "1"},
    {"--sweep", "s.csv", "--sweep-N", "1024:1024:200", "--sweep-time", "0.001"},
};

const std::vector<std::string> options = {"--stage",
                                          "--integrator",
                                          "--steps",
                                          "--dt",
                                          "--K",
                                          "--K-struct",
                                          "--K-shear",
                                          "--K-bend",
                                          "--mu",
                                          "--mass",
                                          "--gravity",
                                          "--chain",
                                          "--N",
                                          "--size",
                                          "--pins",
                                          "--wind-strength",
                                          "--wind-dir",
                                          "--ground-z",
                                          "--ground-friction",
                                          "--csv",
                                          "--csv-every",
                                          "--obj",
                                          "--energy-csv",
                                          "--scaling",
                                          "--reference-N",
                                          "--sweep",
                                          "--sweep-dt",
                                          "--sweep-K",
                                          "--sweep-N",
                                          "--sweep-time",
                                          "--width",
                                          "--height",
                                          "--png",
                                          "--backend",
                                          "--threads",
                                          "--gl",
                                          "--drag",
                                          "--drag-stiffness",
                                          "--sphere",
                                          "--sphere-friction",
                                          "--self-collision",
                                          "--tear-strain"};

const std::vector<std::string> values = {"0",
                                         "-0",
                                         "1",
                                         "-1",
                                         "2",
                                         "3",
                                         "0.5",
                                         "1e-320",
                                         "4.9e-324",
                                         "1e-9",
                                         "1e-10",
                                         "1e9",
                                         "1e10",
                                         "1e308",
                                         "1.7976931348623157e308",
                                         "1e309",
                                         "-1e308",
                                         "inf",
                                         "-inf",
                                         "nan",
                                         "NaN",
                                         "abc",
                                         "",
                                         " 1",
                                         "1 ",
                                         "0x10",
                                         "1e",
                                         "2.5",
                                         "1024",
                                         "1025",
                                         "999999999999999999999",
                                         "-9223372036854775808",
                                         "1,2,3",
                                         "0,0,0",
                                         "1e-320,0,0",
                                         "1e300,1e300,1e300",
                                         "1,2",
                                         "1:100:3",
                                         "1e-300:1e300:3",
                                         "0.001:0.1:200",
                                         "0.001:0.1:201",
                                         "none",
                                         "spring",
                                         "coupled",
                                         "cloth",
                                         "gpu",
                                         "rk4",
                                         "implicit",
                                         "verlet",
                                         "corners",
                                         "resolution-independent",
                                         "out.csv",
                                         "out.obj",
                                         "/dev/full",
                                         "/nonexistent/x.csv",
                                         "."};

std::string number_like(std::mt19937& random) {
  std::uniform_int_distribution<int> mantissa(-9, 9), exponent(-330, 330);
  return std::to_string(mantissa(random)) + "e" + std::to_string(exponent(random));
}

template <class T>
const T& pick(const std::vector<T>& list, std::mt19937& random) {
  return list[std::uniform_int_distribution<std::size_t>(0, list.size() - 1)(random)];
}

// Issue 22: the edges of a value: empty, with a newline or another control character, or
// shaped like a list (of any of the values, with a stray separator) whatever the option.
std::string edge_value(std::mt19937& random) {
  const std::string a = pick(values, random), b = pick(values, random);
  switch (std::uniform_int_distribution<int>(0, 7)(random)) {
    case 0:
      return "";
    case 1:
      return a + "\n" + b;
    case 2:
      return "\n";
    case 3:
      return a + "," + b + "," + pick(values, random);
    case 4:
      return a + ":" + b + ":" + pick(values, random);
    case 5:
      return a + (std::uniform_int_distribution<int>(0, 1)(random) == 0 ? "," : ":");
    case 6:
      return a + "\t" + b + "\r";
    default:
      return "," + a;
  }
}

arguments mutate(arguments args, std::mt19937& random) {
  const int count = std::uniform_int_distribution<int>(1, 3)(random);
  for (int m = 0; m < count; ++m) {
    const int kind = std::uniform_int_distribution<int>(0, 7)(random);
    const std::size_t at =
        args.empty() ? 0 : std::uniform_int_distribution<std::size_t>(0, args.size() - 1)(random);
    switch (kind) {
      case 0:  // another value
        if (!args.empty())
          args[at] = pick(values, random);
        break;
      case 1:  // a random number
        if (!args.empty())
          args[at] = number_like(random);
        break;
      case 2:  // an option with a value, anywhere
        args.insert(args.begin() + static_cast<long>(std::min(at, args.size())),
                    {pick(options, random), pick(values, random)});
        break;
      case 3:  // drop a word
        if (!args.empty())
          args.erase(args.begin() + static_cast<long>(at));
        break;
      case 4:  // an option without its value
        args.push_back(pick(options, random));
        break;
      case 5:  // a value of a seed's option replaced by a random number
        if (at + 1 < args.size() && args[at].rfind("--", 0) == 0)
          args[at + 1] = number_like(random);
        break;
      case 6:  // any option with an edge value: empty, a newline, a list
        args.insert(args.begin() + static_cast<long>(std::min(at, args.size())),
                    {pick(options, random), edge_value(random)});
        break;
      case 7:  // a value of a seed's option replaced by an edge value
        if (at + 1 < args.size() && args[at].rfind("--", 0) == 0)
          args[at + 1] = edge_value(random);
        break;
    }
  }
  // Keep every run short: a valid count that asks for much work is cut down (an invalid one is
  // left for clothlab to refuse). The driver's own time limit covers what this misses.
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    char* end = nullptr;
    const double x = std::strtod(args[i + 1].c_str(), &end);
    const bool number = !args[i + 1].empty() && *end == '\0' && x == x;
    if (!number)
      continue;
    auto cap = [&](const char* option, double low, double high, const char* value) {
      if (args[i] == option && x > low && x <= high)
        args[i + 1] = value;
    };
    cap("--steps", 200, 1e9, "200");
    cap("--N", 16, 1024, "16");
    cap("--reference-N", 64, 1024, "64");
    cap("--chain", 50, 1000, "50");
    cap("--width", 64, 8192, "64");
    cap("--height", 64, 8192, "64");
    cap("--sweep-time", 0.05, 1000, "0.05");
    cap("--threads", 4, 256, "4");
  }
  args.insert(args.begin(), "--headless");
  return args;
}

struct outcome {
  int exit_code = -1;
  int signal = 0;  // the signal that ended it, 0 if none
  bool stopped_by_driver = false;
  std::string out, err;
};

std::string read_file(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// Runs clothlab in `work` with the arguments; after `limit` it is sent SIGTERM (and SIGKILL
// 10 s later).
outcome run(const arguments& args, const fs::path& work, const fs::path& logs,
            std::chrono::seconds limit) {
  std::vector<std::string> copies = args;
  std::string program = clothlab_test::executable_path;
  std::vector<char*> argv = {program.data()};
  for (std::string& a : copies)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  const fs::path out_path = logs / "stdout.txt", err_path = logs / "stderr.txt";
  const pid_t child = fork();
  if (child == 0) {
    const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || chdir(work.c_str()) != 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0)
      _exit(126);
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    execv(argv[0], argv.data());
    _exit(127);
  }
  outcome result;
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  bool killed = false;
  for (;;) {
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child || done < 0)
      break;
    const auto elapsed = std::chrono::steady_clock::now() - start;
    if (!result.stopped_by_driver && elapsed > limit) {
      kill(child, SIGTERM);
      result.stopped_by_driver = true;
    } else if (!killed && elapsed > limit + std::chrono::seconds(10)) {
      kill(child, SIGKILL);
      killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (WIFEXITED(status))
    result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status))
    result.signal = WTERMSIG(status);
  result.out = read_file(out_path);
  result.err = read_file(err_path);
  return result;
}

std::string join(const arguments& args) {
  std::string line = "clothlab";
  for (const std::string& a : args) {
    std::string quoted;  // shell quoting, a newline as $'\n'
    for (char c : a)
      quoted += c == '\n'   ? std::string("'$'\\n''")
                : c == '\'' ? std::string("'\\''")
                            : std::string(1, c);
    line += " '" + quoted + "'";
  }
  return line;
}

// What is wrong with the files left in `work`; empty when nothing.
std::string check_files(const fs::path& work) {
  for (const fs::directory_entry& entry : fs::directory_iterator(work)) {
    const std::string name = entry.path().filename().string();
    if (name.front() == '.')
      return "temporary file left behind: " + name;
    if (!entry.is_regular_file())
      continue;
    const std::string text = read_file(entry.path());
    if (text.rfind("\x89PNG", 0) == 0)
      continue;  // an image (whatever its name)
    if (!text.empty() && text.back() != '\n')
      return name + ": the last line is not whole";
    std::string lower = text;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* bad : {"nan", "inf"}) {
      if (lower.find(bad) != std::string::npos)
        return name + ": holds '" + bad + "'";
    }
  }
  return {};
}

long environment_number(const char* name, long fallback) {
  const char* text = std::getenv(name);
  return text != nullptr && *text != '\0' ? std::strtol(text, nullptr, 10) : fallback;
}

}  // namespace

int main() {
  const long iterations = environment_number("CLOTHLAB_FUZZ_ITERATIONS", 300);
  const long seconds = environment_number("CLOTHLAB_FUZZ_SECONDS", 45);
  const auto seed =
      static_cast<std::mt19937::result_type>(environment_number("CLOTHLAB_FUZZ_SEED", 12));
  std::mt19937 random(seed);

  std::string pattern = (fs::temp_directory_path() / "clothlab-fuzz-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) {
    std::perror("mkdtemp");
    return 1;
  }
  const fs::path root = pattern, work = root / "work";
  const auto start = std::chrono::steady_clock::now();
  long runs = 0, failures = 0, by_status[4] = {0, 0, 0, 0};
  for (long i = 0; i < iterations; ++i) {
    if (seconds > 0 && std::chrono::steady_clock::now() - start > std::chrono::seconds(seconds))
      break;
    // The seeds first, as they are, then mutants of them.
    arguments args;
    if (static_cast<std::size_t>(i) < seeds.size()) {
      args = seeds[static_cast<std::size_t>(i)];
      args.insert(args.begin(), "--headless");
    } else {
      args = mutate(pick(seeds, random), random);
    }
    fs::remove_all(work);
    fs::create_directory(work);
    const outcome result = run(args, work, root, std::chrono::seconds(20));
    ++runs;

    std::string problem;
    const int code = result.exit_code;
    if (result.signal != 0) {
      problem = "killed by signal " + std::to_string(result.signal);
    } else if (result.stopped_by_driver) {
      if (code != 128 + SIGTERM)
        problem = "SIGTERM after the time limit gave exit " + std::to_string(code);
    } else if (code < 0 || code > 3) {
      problem = "exit status " + std::to_string(code);
    } else if (code == 1 && result.err.empty()) {
      problem = "exit 1 without a message";
    } else if (code == 2) {
      const auto lines = std::count(result.err.begin(), result.err.end(), '\n');
      if (lines != 1 || result.err.back() != '\n')
        problem = "exit 2 with " + std::to_string(lines) + " lines on stderr";
      else if (!result.out.empty())
        problem = "exit 2 with standard output";
      else if (result.err.find("--") == std::string::npos)
        problem = "exit 2 without naming an option";
      else if (!fs::is_empty(work))
        problem = "exit 2 wrote " + fs::directory_iterator(work)->path().filename().string();
    }
    if (problem.empty())
      problem = check_files(work);
    if (code >= 0 && code <= 3)
      ++by_status[code];
    if (!problem.empty()) {
      ++failures;
      std::cout << "FAIL: " << problem << "\n  " << join(args) << "\n  stderr: " << result.err
                << "\n";
    }
  }
  fs::remove_all(root);
  std::cout << runs << " command lines (seed " << seed << "): " << by_status[0] << " exit 0, "
            << by_status[1] << " exit 1, " << by_status[2] << " exit 2, " << by_status[3]
            << " exit 3; " << failures << " failed\n";
  return failures == 0 && runs > 0 ? 0 : 1;
}
