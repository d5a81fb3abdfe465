// The main of every question test program (the checker): GoogleTest, with the lab runner
// (runner_client.hpp) reset at the start of each test and ended with the program.
#if defined(__linux__)
#include <sys/prctl.h>
#endif

#include <gtest/gtest.h>

#include <csignal>

#include "core/i18n.hpp"
#include "lab_check.hpp"
#include "runner_client.hpp"

namespace {

class lab_listener : public ::testing::EmptyTestEventListener {
  void OnTestStart(const ::testing::TestInfo&) override { clothlab::lab::start_test_checks(); }
  void OnTestProgramEnd(const ::testing::UnitTest&) override {
    clothlab::lab::runner::instance().stop();
  }
};

}  // namespace

int main(int argc, char** argv) {
  // The runner, the student's code, may run as the same user as this program (./test.sh): it
  // may not read or write this process's memory (ptrace, /proc/<pid>/mem).
#if defined(__linux__)
  ::prctl(PR_SET_DUMPABLE, 0);
#endif
  std::signal(SIGPIPE, SIG_IGN);  // a runner that is gone is seen by the write that fails
  clothlab::start_messages();     // the hints in the student's language (the locale, LANGUAGE)
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::UnitTest::GetInstance()->listeners().Append(new lab_listener);
  return RUN_ALL_TESTS();
}
