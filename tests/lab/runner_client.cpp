#include "runner_client.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <regex>

#include "lab_check.hpp"
#include "protocol.hpp"

extern char** environ;

namespace clothlab::lab {

extern const char* const default_runner_path;  // runner_path.cpp: this build's lab_runner

namespace {

constexpr std::size_t shown_output_per_test = 64 * 1024;       // of the student's prints
constexpr std::size_t default_flood_limit = 16 * 1024 * 1024;  // output of one test, bytes
constexpr std::size_t answer_limit = 64 * 1024 * 1024;         // one answer line, bytes
constexpr double default_timeout = 10.0;                       // s, per request

// What the student's code may print in one test (CLOTHLAB_LAB_OUTPUT_LIMIT, bytes).
std::size_t flood_limit() {
  const char* text = std::getenv("CLOTHLAB_LAB_OUTPUT_LIMIT");
  if (text == nullptr || *text == '\0')
    return default_flood_limit;
  char* end = nullptr;
  const unsigned long long bytes = std::strtoull(text, &end, 10);
  return (end != text && *end == '\0' && bytes > 0) ? static_cast<std::size_t>(bytes)
                                                    : default_flood_limit;
}

// "16 MB", "1000 bytes"
std::string size_in_words(std::size_t bytes) {
  if (bytes % (1024 * 1024) == 0)
    return std::to_string(bytes >> 20) + " MB";
  if (bytes % 1024 == 0)
    return std::to_string(bytes >> 10) + " KB";
  return std::to_string(bytes) + " bytes";
}

double request_timeout() {
  const char* text = std::getenv("CLOTHLAB_LAB_TIMEOUT");
  if (text == nullptr || *text == '\0')
    return default_timeout;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  return (end != text && seconds > 0 && seconds < 1e6) ? seconds : default_timeout;
}

// A file descriptor moved to 10 or above (close-on-exec), so that the child's dup2 to 0..3 never
// meets it; closes the original.
int high_fd(int fd) {
  const int moved = ::fcntl(fd, F_DUPFD_CLOEXEC, 10);
  ::close(fd);
  return moved;
}

void close_fd(int& fd) {
  if (fd >= 0)
    ::close(fd);
  fd = -1;
}

// A signal in words, with what usually causes it in a student's code.
std::string signal_words(int signal_number) {
  switch (signal_number) {
    case SIGSEGV:
      return tr("segmentation fault (an index outside an array? a pointer to nothing?)");
    case SIGABRT:
      return tr("aborted (a failed assert, or an exception that nothing caught)");
    case SIGFPE:
      return tr("arithmetic error (an integer division by zero?)");
    case SIGBUS:
      return tr("bus error (memory that is not there)");
    case SIGILL:
      return tr("illegal instruction");
    case SIGKILL:
      return tr("killed (too much memory? a limit of the sandbox?)");
    case SIGXCPU:
      return tr("stopped: it used more processor time than allowed");
    case SIGXFSZ:
      return tr("stopped: it wrote a file larger than allowed");
    case SIGTERM:
      return tr("terminated");
    default:
      return std::string("signal ") + std::to_string(signal_number) + " (" +
             strsignal(signal_number) + ")";
  }
}

// The printable start of a line, for a message.
std::string excerpt(std::string_view line) {
  std::string out;
  for (char c : line.substr(0, 60))
    out += (c >= 32 && c < 127) ? c : '?';
  return line.size() > 60 ? out + "..." : out;
}

// Per test: the failed checks reported so far (lab_check.hpp).
int reported_checks = 0;
bool told_more_checks = false;

}  // namespace

bool check_unreported(bool ok) {
  if (ok)
    return true;
  if (runner::instance().failed_in_this_test())
    return true;  // the runner's failure said what went wrong; what follows it means nothing
  if (reported_checks < max_reported_checks) {
    ++reported_checks;
    return false;
  }
  if (!told_more_checks) {
    std::printf(tr("(more checks of this test fail; only the first %d are shown)\n"),
                max_reported_checks);
    told_more_checks = true;
  }
  return true;  // the test has failed already, reported_checks times
}

void start_test_checks() {
  reported_checks = 0;
  told_more_checks = false;
  runner::instance().start_test();
}

void quiet_rest_of_test() {
  runner::instance().quiet_rest_of_test();
}

std::string current_question() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  std::cmatch match;
  if (test != nullptr && std::regex_search(test->test_suite_name(), match, std::regex("^Q[0-9]+")))
    return match.str();
  return "lab";
}

bool parse_word_array(std::string_view json, std::vector<std::string>& words, std::string& error) {
  words.clear();
  std::size_t i = 0;
  const auto skip = [&] {
    while (i < json.size() &&
           (json[i] == ' ' || json[i] == '\t' || json[i] == '\n' || json[i] == '\r'))
      ++i;
  };
  const auto hex4 = [&](unsigned& value) {
    if (i + 4 > json.size())
      return false;
    value = 0;
    for (int d = 0; d < 4; ++d) {
      const char c = json[i++];
      value *= 16;
      if (c >= '0' && c <= '9')
        value += unsigned(c - '0');
      else if (c >= 'a' && c <= 'f')
        value += unsigned(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F')
        value += unsigned(c - 'A' + 10);
      else
        return false;
    }
    return true;
  };
  const auto utf8 = [](std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += char(cp);
    } else if (cp < 0x800) {
      out += char(0xC0 | (cp >> 6));
      out += char(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += char(0xE0 | (cp >> 12));
      out += char(0x80 | ((cp >> 6) & 0x3F));
      out += char(0x80 | (cp & 0x3F));
    } else {
      out += char(0xF0 | (cp >> 18));
      out += char(0x80 | ((cp >> 12) & 0x3F));
      out += char(0x80 | ((cp >> 6) & 0x3F));
      out += char(0x80 | (cp & 0x3F));
    }
  };
  const auto bad = [&](const char* why) {
    // (not translated: the grader's setting CLOTHLAB_LAB_SANDBOX, which a teacher reads)
    error = std::string(why) + " at character " + std::to_string(i + 1);
    words.clear();
    return false;
  };
  skip();
  if (i >= json.size() || json[i] != '[')
    return bad("expected '['");
  ++i;
  skip();
  if (i < json.size() && json[i] == ']') {
    ++i;
  } else {
    for (;;) {
      skip();
      if (i >= json.size() || json[i] != '"')
        return bad("expected a string");
      ++i;
      std::string word;
      for (;;) {
        if (i >= json.size())
          return bad("unterminated string");
        const char c = json[i++];
        if (c == '"')
          break;
        if (static_cast<unsigned char>(c) < 0x20)
          return bad("a control character in a string");
        if (c != '\\') {
          word += c;
          continue;
        }
        if (i >= json.size())
          return bad("unterminated string");
        const char e = json[i++];
        switch (e) {
          case '"':
            word += '"';
            break;
          case '\\':
            word += '\\';
            break;
          case '/':
            word += '/';
            break;
          case 'b':
            word += '\b';
            break;
          case 'f':
            word += '\f';
            break;
          case 'n':
            word += '\n';
            break;
          case 'r':
            word += '\r';
            break;
          case 't':
            word += '\t';
            break;
          case 'u': {
            unsigned cp = 0;
            if (!hex4(cp))
              return bad("a bad \\u escape");
            if (cp >= 0xD800 && cp < 0xDC00) {
              unsigned low = 0;
              if (i + 2 > json.size() || json[i] != '\\' || json[i + 1] != 'u')
                return bad("a lone surrogate");
              i += 2;
              if (!hex4(low) || low < 0xDC00 || low >= 0xE000)
                return bad("a lone surrogate");
              cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
            } else if (cp >= 0xDC00 && cp < 0xE000) {
              return bad("a lone surrogate");
            }
            if (cp == 0)
              return bad("a NUL character (a program's argument cannot hold one)");
            utf8(word, cp);
            break;
          }
          default:
            return bad("a bad escape");
        }
      }
      words.push_back(std::move(word));
      skip();
      if (i < json.size() && json[i] == ',') {
        ++i;
        continue;
      }
      if (i < json.size() && json[i] == ']') {
        ++i;
        break;
      }
      return bad("expected ',' or ']'");
    }
  }
  skip();
  if (i != json.size())
    return bad("text after the array");
  return true;
}

runner& runner::instance() {
  static runner the_runner;
  return the_runner;
}

bool runner::start(std::string& error) {
  std::vector<std::string> words;
  const char* sandbox = std::getenv("CLOTHLAB_LAB_SANDBOX");
  if (sandbox != nullptr && *sandbox != '\0') {
    std::string why;
    if (!parse_word_array(sandbox, words, why)) {
      // (not translated: the grader's setting, which a teacher reads)
      error = "CLOTHLAB_LAB_SANDBOX is not a JSON array of strings (" + why + ")";
      return false;
    }
  }
  sandboxed_ = !words.empty();
  const char* path = std::getenv("CLOTHLAB_LAB_RUNNER");
  words.emplace_back(path != nullptr && *path != '\0' ? path : default_runner_path);
  std::vector<char*> argv;
  for (std::string& w : words)
    argv.push_back(w.data());
  argv.push_back(nullptr);

  int pair[2], out[2];
  // Plain socketpair and pipe (POSIX: macOS has neither SOCK_CLOEXEC nor pipe2); high_fd moves
  // each end at once to a close-on-exec descriptor.
  if (::socketpair(AF_UNIX, SOCK_STREAM, 0, pair) != 0 || ::pipe(out) != 0) {
    error = format(tr("no socket or pipe: %s"), std::strerror(errno));
    return false;
  }
  int mine = high_fd(pair[0]), theirs = high_fd(pair[1]);
  int out_read = high_fd(out[0]), out_write = high_fd(out[1]);
  int null_fd = high_fd(::open("/dev/null", O_RDONLY | O_CLOEXEC));

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, null_fd, 0);
  posix_spawn_file_actions_adddup2(&actions, out_write, 1);
  posix_spawn_file_actions_adddup2(&actions, out_write, 2);
  posix_spawn_file_actions_adddup2(&actions, theirs, lab_protocol::channel_fd);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);  // ignored here (a write to a dead runner fails, no signal)
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setpgroup(&attributes, 0);  // its own process group: ended as a whole
  posix_spawnattr_setflags(&attributes,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  pid_t pid = -1;
  const int spawned = ::posix_spawnp(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  close_fd(theirs);
  close_fd(out_write);
  close_fd(null_fd);
  if (spawned != 0) {
    close_fd(mine);
    close_fd(out_read);
    error = format(tr("cannot start %s: %s"), words.front().c_str(), std::strerror(spawned));
    return false;
  }
  pid_ = pid;
  channel_ = mine;
  output_ = out_read;
  ::fcntl(channel_, F_SETFL, ::fcntl(channel_, F_GETFL) | O_NONBLOCK);
  ::fcntl(output_, F_SETFL, ::fcntl(output_, F_GETFL) | O_NONBLOCK);
#ifdef SYS_pidfd_open
  pid_fd_ = static_cast<int>(::syscall(SYS_pidfd_open, pid_, 0));
  if (pid_fd_ >= 0)
    ::fcntl(pid_fd_, F_SETFD, FD_CLOEXEC);
#endif
  pending_answer_.clear();
  return true;
}

bool runner::drain_output(std::size_t& total) {
  char chunk[65536];
  for (;;) {
    const ssize_t got = ::read(output_, chunk, sizeof chunk);
    if (got < 0 && errno == EINTR)
      continue;
    if (got == 0) {
      close_fd(output_);  // the runner closed its output (or ended)
      return true;
    }
    if (got < 0)
      return true;  // nothing more for now
    const std::size_t n = static_cast<std::size_t>(got);
    if (output_this_test_ < shown_output_per_test) {
      const std::size_t shown = std::min(n, shown_output_per_test - output_this_test_);
      std::fwrite(chunk, 1, shown, stdout);
      if (output_this_test_ + shown >= shown_output_per_test)
        std::printf("\n%s\n",
                    tr("[the rest of what the student's code printed in this test is not shown]"));
      std::fflush(stdout);
    }
    output_this_test_ += n;
    total += n;
    if (output_this_test_ > flood_limit())
      return false;
  }
}

int runner::wait_for_end(int milliseconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(milliseconds);
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      pid_ = -1;
      return status;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0)
      return -1;
    // Wait on the process's pidfd and its output; without a pidfd, wake up now and then to
    // ask again.
    pollfd fds[2];
    nfds_t count = 0;
    if (pid_fd_ >= 0)
      fds[count++] = {pid_fd_, POLLIN, 0};
    if (output_ >= 0)
      fds[count++] = {output_, POLLIN, 0};
    const int wait = pid_fd_ >= 0 ? static_cast<int>(std::min<long long>(left, INT_MAX))
                                  : static_cast<int>(std::min<long long>(left, 20));
    ::poll(fds, count, wait);
    std::size_t ignored = 0;
    if (output_ >= 0)
      drain_output(ignored);
  }
}

std::string runner::ending(int status) const {
  if (status == -1)
    return tr("closed its channel to the test but did not end");
  if (WIFSIGNALED(status))
    return format(tr("crashed: %s"), signal_words(WTERMSIG(status)).c_str());
  const int code = WEXITSTATUS(status);
  // A sandbox (bubblewrap, a shell) reports its program's signal n as the exit status 128 + n.
  if (sandboxed_ && code > 128 && code < 128 + 65)
    return format(tr("crashed: %s"), signal_words(code - 128).c_str());
  return format(tr("ended the program (exit status %d) before answering: does the code call "
                   "exit(), or return from a place that ends it?"),
                code);
}

void runner::fail(std::string_view operation, const std::string& reason) {
  const std::string message =
      format(tr("%s: the student's code, in %s, %s"), current_question().c_str(),
             std::string(operation).c_str(), reason.c_str());
  GTEST_NONFATAL_FAILURE_(message.c_str());
  failed_in_test_ = true;
}

void runner::kill_and_reap() {
  if (pid_ > 0) {
    ::kill(-pid_, SIGKILL);
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  pid_ = -1;
  close_fd(pid_fd_);
  close_fd(channel_);
  close_fd(output_);
  pending_answer_.clear();
}

void runner::reject(std::string_view operation, const std::string& reason) {
  kill_and_reap();
  fail(operation, reason);
}

void runner::stop() {
  if (pid_ > 0 || channel_ >= 0)
    kill_and_reap();
}

std::optional<std::string> runner::ask(std::string_view operation, const std::string& request) {
  if (failed_in_test_)
    return std::nullopt;
  if (pid_ < 0) {
    kill_and_reap();  // what is left of an earlier runner
    std::string error;
    if (!start(error)) {
      fail(operation, format(tr("could not be started: %s"), error.c_str()));
      return std::nullopt;
    }
  }
  const double timeout = request_timeout();
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout));
  const std::string out = request + "\n";
  std::size_t written = 0, printed = 0;
  std::string& answer = pending_answer_;
  char timeout_text[32];
  std::snprintf(timeout_text, sizeof timeout_text, "%g", timeout);

  // The runner is gone (or going) before answering: why, in words.
  const auto gone = [&]() -> std::optional<std::string> {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    const int group = pid_;
    const int status = wait_for_end(static_cast<int>(std::clamp<long long>(left, 100, INT_MAX)));
    const std::string reason = ending(status);
    ::kill(-group, SIGKILL);  // what it started, if anything
    kill_and_reap();
    fail(operation, reason);
    return std::nullopt;
  };

  std::size_t scanned = 0;  // bytes of `answer` known to hold no end of line
  for (;;) {
    const std::size_t end = answer.find('\n', scanned);
    scanned = answer.size();
    if (end != std::string::npos) {
      const std::string line = answer.substr(0, end);
      answer.erase(0, end + 1);
      if (line == "ok" || line.rfind("ok ", 0) == 0)
        return line.substr(2);
      if (line.rfind("error ", 0) == 0) {
        lab_protocol::reader in(std::string_view(line).substr(6));
        const std::string what = in.text(4096);
        if (in.ok() && in.at_end()) {
          fail(operation, format(tr("threw an exception: %s"), excerpt(what).c_str()));
          return std::nullopt;
        }
      }
      kill_and_reap();
      fail(operation, format(tr("answered something that is not the runner's answer ('%s'): "
                                "does it write to the runner's file descriptor 3?"),
                             excerpt(line).c_str()));
      return std::nullopt;
    }
    if (answer.size() > answer_limit) {
      kill_and_reap();
      fail(operation,
           tr("sent more than 64 MB without ending its answer: not the runner's answer"));
      return std::nullopt;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0) {
      kill_and_reap();
      fail(operation, format(tr("did not answer within %s s: an endless loop (a loop whose end "
                                "condition never holds)? Stopped"),
                             timeout_text));
      return std::nullopt;
    }
    pollfd fds[3];
    nfds_t count = 0;
    fds[count++] = {channel_, static_cast<short>(POLLIN | (written < out.size() ? POLLOUT : 0)), 0};
    const int output_slot = output_ >= 0 ? static_cast<int>(count) : -1;
    if (output_ >= 0)
      fds[count++] = {output_, POLLIN, 0};
    const int pid_slot = pid_fd_ >= 0 ? static_cast<int>(count) : -1;
    if (pid_fd_ >= 0)
      fds[count++] = {pid_fd_, POLLIN, 0};
    if (::poll(fds, count, static_cast<int>(std::min<long long>(left, INT_MAX))) < 0) {
      if (errno == EINTR)
        continue;
      kill_and_reap();
      fail(operation, format(tr("could not be waited for: %s"), std::strerror(errno)));
      return std::nullopt;
    }
    if (output_slot >= 0 && fds[output_slot].revents != 0 && !drain_output(printed)) {
      kill_and_reap();
      fail(operation, format(tr("printed more than %s in one test: a print in a loop that runs "
                                "every step? Stopped"),
                             size_in_words(flood_limit()).c_str()));
      return std::nullopt;
    }
    if ((fds[0].revents & POLLOUT) != 0) {
      const ssize_t sent =
          ::send(channel_, out.data() + written, out.size() - written, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (sent > 0)
        written += static_cast<std::size_t>(sent);
      else if (sent < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
        return gone();
    }
    if ((fds[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      char chunk[65536];
      const ssize_t got = ::read(channel_, chunk, sizeof chunk);
      if (got > 0)
        answer.append(chunk, static_cast<std::size_t>(got));
      else if (got == 0 || (errno != EAGAIN && errno != EINTR))
        return gone();
    }
    if (pid_slot >= 0 && fds[pid_slot].revents != 0) {
      // It ended: an answer it wrote before may still wait in the socket.
      char chunk[65536];
      ssize_t got;
      while ((got = ::read(channel_, chunk, sizeof chunk)) > 0)
        answer.append(chunk, static_cast<std::size_t>(got));
      if (answer.find('\n') == std::string::npos)
        return gone();
      close_fd(pid_fd_);  // answered, then ended: the next request finds out
    }
  }
}

}  // namespace clothlab::lab
