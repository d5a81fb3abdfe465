// The checker's side of the lab runner: starts the runner (the student's code, in a process of
// its own, tests/lab/runner/), sends it one request at a time and reads its answer, and turns
// whatever goes wrong there into the test's failure, in words: a crash (with its signal), no
// answer within the time limit, an exit before answering, an answer that is not one, a flood of
// output. The checker itself never crashes or hangs on the runner's account.
//
// Where the runner is, and how it is started:
//   CLOTHLAB_LAB_RUNNER   the runner program (default: this build's lab_runner);
//   CLOTHLAB_LAB_SANDBOX  a JSON array of words put before it (default: none), e.g.
//                         ["bwrap", "--ro-bind", "/", "/", "--"]: the grader runs it confined;
//   CLOTHLAB_LAB_TIMEOUT  seconds a request may take (default 10);
//   CLOTHLAB_LAB_OUTPUT_LIMIT  bytes the student's code may print in one test (default 16 MB;
//                         the first 64 KB are shown, the rest is read and dropped).
// The runner reads the shaders from CLOTHLAB_DATA_DIR, as every program of the project does.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace clothlab::lab {

// One runner for the whole test program, started at the first request; after a failure it is
// ended, and the next test starts a fresh one.
class runner {
 public:
  static runner& instance();

  // Sends `request` (one line, protocol.hpp) for the student's `operation` (its name in the
  // lab's words, e.g. "spring_mesh::compute_force") and returns the answer's results. On any
  // failure, the test fails with the reason and nullopt comes back; so does every later request
  // of the same test, without a word (the test has already said what went wrong).
  std::optional<std::string> ask(std::string_view operation, const std::string& request);

  // Whether a request of the current test failed (its later checks are then not reported).
  bool failed_in_this_test() const { return failed_in_test_; }
  void start_test() { failed_in_test_ = false; }
  // The rest of the test says nothing more (its failure said what is wrong) and asks nothing.
  void quiet_rest_of_test() { failed_in_test_ = true; }

  // Fails the test because the answer to `operation` is not what was asked for (`reason`), and
  // ends the runner: one that answers wrongly is not asked again.
  void reject(std::string_view operation, const std::string& reason);

  // Ends the runner (at the end of the program).
  void stop();

  ~runner() { stop(); }

 private:
  runner() = default;
  int pid_ = -1;      // the started program (the sandbox's, when there is one)
  int pid_fd_ = -1;   // pidfd of pid_ (poll tells when it ended), -1 where the kernel has none
  int channel_ = -1;  // the socket of the requests and answers (the runner's fd 3)
  int output_ = -1;   // the runner's standard output and error
  bool sandboxed_ = false;  // started behind CLOTHLAB_LAB_SANDBOX
  bool failed_in_test_ = false;
  std::size_t output_this_test_ = 0;  // bytes of the student's prints shown in this test
  std::string pending_answer_;        // bytes read past the last answer (none, normally)

  // Starts the runner; false with the reason.
  bool start(std::string& error);
  // Forwards what the runner printed (up to a limit per test); false past the flood limit.
  bool drain_output(std::size_t& total);
  // Why the runner ended (after it ended): "crashed: segmentation fault ...", ...
  std::string ending(int status) const;
  // Waits, within `milliseconds`, for the runner to end; its wait status, or -1.
  int wait_for_end(int milliseconds);
  void fail(std::string_view operation, const std::string& reason);
  void kill_and_reap();
};

// The question of the running test, from its suite's name: "Q8" for Q8ComputeForce.
std::string current_question();

// The words of CLOTHLAB_LAB_SANDBOX (a JSON array of strings); false with the reason when it is
// not one. Exposed for the harness tests.
bool parse_word_array(std::string_view json, std::vector<std::string>& words, std::string& error);

}  // namespace clothlab::lab
