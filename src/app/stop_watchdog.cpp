#include "app/stop_watchdog.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/run_control.hpp"
#include "core/i18n.hpp"

namespace clothlab {

stop_state stopping;

bool stop_watchdog::pause() {
  std::unique_lock lock(mutex_);
  return wake_.wait_for(lock, std::chrono::milliseconds(10), [this] { return done_; });
}

void stop_watchdog::watch(const options& o, run_outputs& out) {
  while (stop_signal == 0 || stopping.taken) {
    if (pause())
      return;
  }
  const auto deadline = std::chrono::steady_clock::now() + stop_grace;
  while (!stopping.taken && std::chrono::steady_clock::now() < deadline) {
    if (pause())
      return;
  }
  if (stopping.taken)
    return;
  std::unique_lock lock(stopping.outputs, std::defer_lock);
  const bool locked = lock.try_lock_for(stop_grace);
  if (locked && stopping.taken)
    return;  // the loop got there first
  const int signal_number = stop_signal;
  const long step = stopping.last_step;
  std::string error;
  if (locked && step < 0) {  // still setting up: as if the run had not started
    out.close(false, false, error);
    report(tr("interrupted by %s before the run's first step was written; nothing written"),
           signal_name(signal_number));
  } else if (locked && out.close(true, false, error)) {
    if (step == o.steps) {
      report(tr("interrupted by %s after the last step; the CSV files hold every step, the OBJ "
                "and the PNG are not written"),
             signal_name(signal_number));
    } else {
      report(tr("interrupted by %s after step %ld of %ld (the steps after it had not ended %ld ms "
                "later); the CSV files hold the steps written up to it"),
             signal_name(signal_number), step, o.steps, long(stop_grace.count()));
    }
  } else {
    if (locked)
      report("%s", error.c_str());
    report(tr("interrupted by %s after step %ld of %ld; the files were being written and none "
              "is kept"),
           signal_name(signal_number), step, o.steps);
    out.discard();
  }
  std::fflush(stderr);
  std::_Exit(128 + signal_number);
}

}  // namespace clothlab
