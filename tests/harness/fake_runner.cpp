// A lab runner that misbehaves, the way a hostile or broken student's code would, to show that
// the question tests (the checkers) fail with the reason and never crash, hang or pass. The
// behaviour is named by CLOTHLAB_FAKE_RUNNER (check_harness.py):
//   forge-stdout   prints GoogleTest's "all passed" and ends at once, with exit status 0
//                  (an atexit handler makes sure of it), without answering;
//   forge-answer   answers the first request with "all passed";
//   crash          crashes (segmentation fault) on the first request;
//   hang           never answers;
//   flood          prints without end on its standard output;
//   flood-answer   writes an answer that never ends;
//   exit           ends with exit status 0 on the first request.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

constexpr int channel = 3;  // protocol.hpp

void read_one_request() {
  char c;
  while (::read(channel, &c, 1) == 1 && c != '\n') {
  }
}

void write_all(int fd, const char* text) {
  ::write(fd, text, std::strlen(text));
}

}  // namespace

int main() {
  const char* mode_text = std::getenv("CLOTHLAB_FAKE_RUNNER");
  const std::string mode = mode_text != nullptr ? mode_text : "";
  if (mode == "forge-stdout") {
    std::atexit([] { ::_exit(0); });
    std::printf("[==========] 4 tests from 1 test suite ran.\n[  PASSED  ] 4 tests.\n");
    return 0;
  }
  read_one_request();
  if (mode == "forge-answer") {
    write_all(channel, "[  PASSED  ] 4 tests: all passed, 80/80\n");
    read_one_request();
    return 0;
  }
  if (mode == "crash") {
    std::raise(SIGSEGV);
  }
  if (mode == "hang") {
    for (;;)
      ::pause();
  }
  if (mode == "flood") {
    static char line[4096];
    std::memset(line, 'x', sizeof line - 1);
    line[sizeof line - 2] = '\n';
    for (;;)
      write_all(1, line);
  }
  if (mode == "flood-answer") {
    static char line[65536];
    std::memset(line, '7', sizeof line - 1);
    for (;;)
      write_all(channel, line);
  }
  if (mode == "exit")
    std::exit(0);
  std::fprintf(stderr, "fake_runner: no CLOTHLAB_FAKE_RUNNER mode\n");
  return 3;
}
