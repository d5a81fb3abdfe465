// What the lab's grader shares: vectors printed as the handout writes them, and checks that
// say, in the handout's words, what a wrong answer does.
//
// A failed test says what is wrong in its first few messages: the checks of one test report at
// most max_reported_checks failures (one wrong sign would otherwise fail every vertex of a
// cloth, each with its message), and none after the student's code failed to answer (crashed,
// hung, threw: the runner's message says so, and the numbers that follow mean nothing).
#pragma once

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstdio>
#include <string>

namespace clothlab::lab {

inline constexpr int max_reported_checks = 3;

// "(0.2, -1, 3.5)"
inline std::string text(const glm::dvec3& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", v.x, v.y, v.z);
  return buffer;
}

// True when |got - expected| <= tolerance (absolute, per vector).
inline bool near(const glm::dvec3& got, const glm::dvec3& expected, double tolerance) {
  return glm::length(got - expected) <= tolerance;
}

// True when a check that came out `ok` needs no message: it passed, or the test has already
// failed and said enough (see above). runner_client.cpp.
bool check_unreported(bool ok);
// At the start of each test (lab_main.cpp).
void start_test_checks();
// After a failure that makes the rest of the test meaningless (a GPU program that does not
// compile): its later checks report nothing and the runner is asked nothing more.
void quiet_rest_of_test();

}  // namespace clothlab::lab

// Checks got against expected; on failure the message is `what` (the handout's terms), then
// the two vectors. Each argument is evaluated once.
#define LAB_EXPECT_VEC(got, expected, tolerance, what)                                     \
  if (const glm::dvec3 lab_got_ = (got), lab_expected_ = (expected);                       \
      ::clothlab::lab::check_unreported(                                                   \
          ::clothlab::lab::near(lab_got_, lab_expected_, (tolerance)))) {                  \
  } else                                                                                   \
    EXPECT_TRUE(::clothlab::lab::near(lab_got_, lab_expected_, (tolerance)))               \
        << (what) << "\n    expected " << ::clothlab::lab::text(lab_expected_) << ", got " \
        << ::clothlab::lab::text(lab_got_)

// A condition, with `what` on failure (followed by anything streamed with <<).
#define LAB_EXPECT_TRUE(condition, what)                                                  \
  if (const bool lab_ok_ = bool(condition); ::clothlab::lab::check_unreported(lab_ok_)) { \
  } else                                                                                  \
    EXPECT_TRUE(lab_ok_) << (what)

// The same, ending the test when it fails (reported or not).
#define LAB_ASSERT_TRUE(condition, what)                 \
  if (const bool lab_ok_ = bool(condition); lab_ok_) {   \
  } else if (::clothlab::lab::check_unreported(false)) { \
    return;                                              \
  } else                                                 \
    ASSERT_TRUE(lab_ok_) << (what)

namespace clothlab::lab {

// How many k in [0, count) fail `passes`, and the first of them.
struct failures {
  std::size_t wrong = 0, first = 0;
};
template <class Passes>
failures count_failures(std::size_t count, Passes passes) {
  failures f;
  for (std::size_t k = 0; k < count; ++k)
    if (!passes(k) && f.wrong++ == 0)
      f.first = k;
  return f;
}

}  // namespace clothlab::lab

// LAB_EXPECT_VEC for every k in [0, count) (got, expected and what use k): one message, for the
// first k that fails, with how many do.
#define LAB_EXPECT_EVERY_VEC(k, count, got, expected, tolerance, what)                           \
  if (const ::clothlab::lab::failures lab_failures_ = ::clothlab::lab::count_failures(           \
          (count),                                                                               \
          [&](std::size_t k) { return ::clothlab::lab::near((got), (expected), (tolerance)); }); \
      lab_failures_.wrong == 0) {                                                                \
  } else if (const std::size_t k = lab_failures_.first; false) {                                 \
  } else                                                                                         \
    LAB_EXPECT_VEC(got, expected, tolerance, what)                                               \
        << "\n    (" << lab_failures_.wrong << " of " << (count) << " are wrong)"
