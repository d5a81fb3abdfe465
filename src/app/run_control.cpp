#include "app/run_control.hpp"

#include <csignal>
#include <cstdarg>

#include "app/command_line.hpp"  // one_line
#include "core/i18n.hpp"

namespace clothlab {

std::atomic<int> stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

namespace {

extern "C" void on_stop_signal(int signal_number) {
  int none = 0;
  stop_signal.compare_exchange_strong(none, signal_number);
}

constexpr int stop_signals[] = {SIGINT, SIGTERM, SIGHUP};

}  // namespace

const char* signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
  }
  return "a signal";
}

void report(const char* format, ...) {
  char text[2048];
  std::va_list arguments;
  va_start(arguments, format);
  std::vsnprintf(text, sizeof text, format, arguments);
  va_end(arguments);
  std::fprintf(stderr, tr("clothlab: %s\n"), one_line(text).c_str());
}

long clock_stride(std::size_t particles) {
  return std::max(1L, 65536L / static_cast<long>(std::max<std::size_t>(particles, 1)));
}

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigset_t handled;
  sigemptyset(&handled);
  for (int signal_number : stop_signals) {
    struct sigaction before {};
    sigaction(signal_number, nullptr, &before);
    if (before.sa_handler == SIG_IGN)
      continue;  // ignored by whoever started clothlab (nohup): it stays ignored
    sigaction(signal_number, &action, nullptr);
    sigaddset(&handled, signal_number);
  }
  // A signal blocked across exec (hand_over in main.cpp) arrives now, at its handler.
  sigprocmask(SIG_UNBLOCK, &handled, nullptr);
}

void block_stop_signals(bool block) {
  sigset_t set;
  sigemptyset(&set);
  for (int signal_number : stop_signals)
    sigaddset(&set, signal_number);
  sigprocmask(block ? SIG_BLOCK : SIG_UNBLOCK, &set, nullptr);
}

int interrupted_before_the_run() {
  if (stop_signal == 0)
    return 0;
  report(tr("interrupted by %s before the run started; nothing written"), signal_name(stop_signal));
  return 128 + stop_signal;
}

}  // namespace clothlab
