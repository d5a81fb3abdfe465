#include "cli_support.hpp"

#include <algorithm>

namespace clothlab_cli_test {

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

std::string names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  std::string line;
  for (const std::string& name : names)
    line += (line.empty() ? "" : " ") + name;
  return line.empty() ? "nothing" : line;
}

bool has_option(const arguments& args, const std::string& option) {
  return std::find(args.begin(), args.end(), option) != args.end();
}

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

bool temporary_file_left(const fs::path& folder) {
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().filename().string().front() == '.')
      return true;
  }
  return false;
}

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
    if (how.block_sigint || how.sigint_pending) {
      sigset_t set;
      sigemptyset(&set);
      sigaddset(&set, SIGINT);
      sigprocmask(SIG_BLOCK, &set, nullptr);
      if (how.sigint_pending)
        raise(SIGINT);
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

}  // namespace clothlab_cli_test
