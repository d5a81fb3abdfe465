// A headless run's answer to a stop signal (SIGINT, SIGTERM, SIGHUP; docs/limits.md): what the
// step loop and the watchdog thread share, and the watchdog, which ends the run within a second
// of the signal whatever is in progress.
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "app/options.hpp"
#include "app/run_outputs.hpp"

namespace clothlab {

// What the step loop and the stop watchdog share: the outputs are written by one of them at a
// time (the lock), and the watchdog leaves the run to the loop once the loop has seen the
// signal or is putting the files in place (taken).
struct stop_state {
  std::timed_mutex outputs;
  std::atomic<bool> taken{false};
  std::atomic<long> last_step{-1};  // the last step checked and written
};
extern stop_state stopping;  // the run's (one per process)

// Ends the run within a second of a stop signal whatever is in progress: a step of
// a large cloth (the implicit scheme at N = 1024 takes a second), a batch of GPU steps, the PNG.
// stop_grace after the signal, if the step loop has not seen it, the watchdog takes the
// outputs (waiting at most stop_grace more for a write in progress to let them go), puts the CSVs
// in place with the steps written so far, removes the OBJ's and the PNG's temporary files, and ends
// the process with 128 + the signal's number. The step in progress is lost.
class stop_watchdog {
 public:
  stop_watchdog(const options& o, run_outputs& out)
      : thread_([this, &o, &out] { watch(o, out); }) {}
  stop_watchdog(const stop_watchdog&) = delete;
  stop_watchdog& operator=(const stop_watchdog&) = delete;
  ~stop_watchdog() {
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }

 private:
  bool pause();  // sleeps 10 ms, or less when the run ends; true when it has ended
  void watch(const options& o, run_outputs& out);

  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace clothlab
