// What every headless command shares (a run, or --sweep's stability map): the exit statuses of
// cli.md, the stop signals and what they set, one-line reports on standard error, and the
// progress line of long runs.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdio>

#include "core/i18n.hpp"

namespace clothlab {

inline constexpr int exit_failure = 1;
inline constexpr int exit_usage = 2;
inline constexpr int exit_diverged = 3;

// SIGINT, SIGTERM, SIGHUP: the handler only records the first signal; the
// step loop sees it after the step in progress, writes nothing more, closes the files (whole
// lines, renamed into place) and exits with 128 + the signal's number (130, 143, 129). A step
// that does not end within stop_grace of the signal is abandoned (stop_watchdog.hpp). A
// second signal changes nothing: timeout(1) sends two, and the first already ends the run.
// (A lock-free atomic: written by the handler, read by the step loop and the watchdog's thread.)
extern std::atomic<int> stop_signal;

// How long after a stop signal the step in progress (or a sweep's cells) may go on before the
// run ends without it, and how long the watchdog then waits for a write in progress: the run
// ends within a second of the signal (docs/limits.md).
inline constexpr std::chrono::milliseconds stop_grace{300};

// "SIGINT", "SIGTERM", "SIGHUP" ("a signal" for another number).
const char* signal_name(int signal_number);

// One line on standard error, "clothlab: " and the text, its control characters escaped (a
// file name may hold a newline).
[[gnu::format(printf, 1, 2)]] void report(const char* format, ...);

// A progress line on standard error for long runs, on a terminal only (nothing in a pipe or a
// file, so that scripts and tests see the usual output): at most once a second, rewritten in
// place, cleared at the end.
class progress_line {
 public:
  // The clock is read every `stride` calls to update().
  progress_line(const char* unit, long total, long stride)
      : unit_(unit),
        total_(total),
        stride_(std::max(stride, 1L)),
        enabled_(::isatty(STDERR_FILENO) == 1),
        last_(std::chrono::steady_clock::now()) {}
  progress_line(const progress_line&) = delete;
  progress_line& operator=(const progress_line&) = delete;
  ~progress_line() { clear(); }

  void update(long done) {
    if (!enabled_ || done % stride_ != 0)
      return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::seconds(1))
      return;
    last_ = now;
    const double percent = total_ > 0 ? 100.0 * double(done) / double(total_) : 100.0;
    std::fputc('\r', stderr);
    std::fprintf(stderr, tr("clothlab: %s %ld of %ld (%.1f %%)"), tr(unit_), done, total_, percent);
    std::fflush(stderr);
    shown_ = true;
  }

  void clear() {
    if (shown_)
      std::fputs("\r\033[K", stderr);  // back to the start of the line, erased
    shown_ = false;
  }

 private:
  const char* unit_;
  long total_;
  long stride_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_;
};

// How many steps apart the progress line reads the clock: about 65 536 particle updates, often
// enough for once a second whatever the cost of a step, rarely enough to cost nothing.
long clock_stride(std::size_t particles);

// SIGINT, SIGTERM and SIGHUP (docs/limits.md): installs their handler (a signal ignored on entry,
// as under nohup, stays ignored) and unblocks them. main.cpp calls it before anything else, so
// that a signal from the first millisecond on is reported, not fatal.
void install_stop_handlers();
// Holds the three signals back (block) or lets them through: across an exec (main.cpp's
// hand-over to another program) a signal then waits for the new program's handler.
void block_stop_signals(bool block);
// When a stop signal came before the run started: says so and returns 128 + its number; else 0.
int interrupted_before_the_run();

}  // namespace clothlab
