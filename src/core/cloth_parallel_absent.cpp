// The stand-in for the parallel CPU path (cloth_parallel.hpp) where it is not built: it says
// why, and every function that would run it throws. Compiled in place of cloth_parallel.cpp
// (src/core/CMakeLists.txt) by the browser build (WebAssembly has no OpenMP here), by a build
// without OpenMP (Apple's clang: CLOTHLAB_NO_OPENMP), and by the student copy, which has no
// cloth_parallel.cpp (the path would answer questions 6, 8, 9 and 13).
#include <stdexcept>

#include "core/cloth_parallel.hpp"
#include "core/i18n.hpp"

namespace clothlab {

bool cloth_parallel::available() {
  return false;
}

const char* cloth_parallel::unavailable_reason() {
#if defined(__EMSCRIPTEN__)
  return tr(
      "the parallel CPU path (cpu-parallel) needs OpenMP threads, which the browser build "
      "does not have; use cpu");
#elif defined(CLOTHLAB_NO_OPENMP)
  return tr(
      "the parallel CPU path (--backend cpu-parallel) needs OpenMP, which this build does "
      "not have (CMake found none: Apple's clang has none); use --backend cpu");
#else
  return tr(
      "the parallel CPU path (--backend cpu-parallel) is in the teacher's copy: it "
      "computes questions 6, 8, 9 and 13 itself; use --backend cpu");
#endif
}

bool cloth_parallel::supports(const cloth_parameters&, std::string& error) {
  error = unavailable_reason();
  return false;
}

int cloth_parallel::threads() const {
  return 0;
}

void cloth_parallel::load(const spring_mesh&) {
  throw std::invalid_argument(unavailable_reason());
}

void cloth_parallel::step(const cloth_parameters&) {
  throw std::invalid_argument(unavailable_reason());
}

int cloth_parallel::run(const cloth_parameters&, int, double) {
  throw std::invalid_argument(unavailable_reason());
}

void cloth_parallel::read_state(spring_mesh&) const {
  throw std::invalid_argument(unavailable_reason());
}

}  // namespace clothlab
