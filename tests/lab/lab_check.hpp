// What the lab's grader shares: vectors printed as the handout writes them, the tolerances every
// comparison uses, and checks that say, in the handout's words, what a wrong answer does.
//
// A failed test says what is wrong in its first few messages: the checks of one test report at
// most max_reported_checks failures (one wrong sign would otherwise fail every vertex of a
// cloth, each with its message), and none after the student's code failed to answer (crashed,
// hung, threw: the runner's message says so, and the numbers that follow mean nothing).
#pragma once

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "core/i18n.hpp"

namespace clothlab::lab {

inline constexpr int max_reported_checks = 3;

// Tolerances come from the numbers. A test compares an answer with the handout's formula
// evaluated here in double precision; a right answer differs from it by rounding alone, and
// by how much depends on how it is written: with double temporaries by 1e-16 of the numbers
// involved, with float ones (glm::vec3, the handout's own v3) by 2^-24 = 6e-8 of them per
// operation. float_rounding bounds a few dozen operations in single precision: a tolerance is
// float_rounding times the size of the numbers a result is computed from (for a spring force,
// K times the size of the positions: float rounds the positions, not their small difference),
// per step for a run of several steps. Every mistake of a question changes a result by far
// more (a missing spring, a sign, a rest length, a missing dt): scripts/mutate-grader checks
// that each still fails.
inline constexpr double float_rounding = 1e-6;

// float_rounding of numbers of the given size (one step).
inline double rounding(double size) {
  return float_rounding * size;
}

// "(0.2, -1, 3.5)", with `digits` significant digits.
inline std::string text(const glm::dvec3& v, int digits = 6) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "(%.*g, %.*g, %.*g)", digits, v.x, digits, v.y, digits, v.z);
  return buffer;
}

// "0.25", with `digits` significant digits.
inline std::string number(double x, int digits = 6) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

// True when |got - expected| <= tolerance (absolute, per vector).
inline bool near(const glm::dvec3& got, const glm::dvec3& expected, double tolerance) {
  return glm::length(got - expected) <= tolerance;
}
inline bool near(double got, double expected, double tolerance) {
  return std::abs(got - expected) <= tolerance;
}

// The two values as a student reads them: "expected (0, 0, 4), got (0, 0, 4.0000305): off by
// 3.05e-05, more than the 1e-05 allowed". Printed with as many digits as it takes for them to
// read differently: two equal-looking numbers are never shown as a difference.
template <class Value>
std::string difference(const Value& got, const Value& expected, double tolerance) {
  const auto show = [](const Value& v, int digits) {
    if constexpr (std::is_same_v<Value, double>)
      return number(v, digits);
    else
      return text(v, digits);
  };
  int digits = 6;
  while (digits < 17 && show(got, digits) == show(expected, digits))
    ++digits;
  double off;
  if constexpr (std::is_same_v<Value, double>)
    off = std::abs(got - expected);
  else
    off = glm::length(got - expected);
  const std::string expected_text = show(expected, digits), got_text = show(got, digits);
  if (!std::isfinite(off))
    return "\n    " + format(tr("expected %s, got %s"), expected_text.c_str(), got_text.c_str());
  return "\n    " + format(tr("expected %s, got %s: off by %s, more than the %s allowed"),
                           expected_text.c_str(), got_text.c_str(), number(off, 3).c_str(),
                           number(tolerance, 3).c_str());
}

// What a failed comparison of a force says first: `reversed` when the answer is the expected
// force with the opposite sign (the one mistake that no other message would name), else `what`.
inline std::string force_message(const glm::dvec3& got, const glm::dvec3& expected,
                                 double tolerance, const std::string& what,
                                 const std::string& reversed) {
  return glm::length(expected) > tolerance && near(got, -expected, tolerance) ? reversed : what;
}

// A sum of forces of several kinds (the spring families), each with its name.
struct force_part {
  std::string name;
  glm::dvec3 force;
};

// The name of the part that got has reversed (got = expected - 2 part: that kind of force with
// the wrong sign, the others right), or empty.
inline std::string reversed_part(const glm::dvec3& got, const glm::dvec3& expected,
                                 const std::vector<force_part>& parts, double tolerance) {
  for (const force_part& part : parts)
    if (glm::length(part.force) > tolerance && near(got, expected - 2.0 * part.force, tolerance))
      return part.name;
  return {};
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
// the two vectors and how far apart they are. Each argument is evaluated once.
#define LAB_EXPECT_VEC(got, expected, tolerance, what)                       \
  if (const glm::dvec3 lab_got_ = (got), lab_expected_ = (expected);         \
      ::clothlab::lab::check_unreported(                                     \
          ::clothlab::lab::near(lab_got_, lab_expected_, (tolerance)))) {    \
  } else                                                                     \
    EXPECT_TRUE(::clothlab::lab::near(lab_got_, lab_expected_, (tolerance))) \
        << (what) << ::clothlab::lab::difference(lab_got_, lab_expected_, (tolerance))

// LAB_EXPECT_VEC for a force: when got is the expected force reversed, the message is
// `reversed` (a sign error, in the handout's words) instead of `what`.
#define LAB_EXPECT_FORCE(got, expected, tolerance, what, reversed)                      \
  if (const glm::dvec3 lab_got_ = (got), lab_expected_ = (expected);                    \
      ::clothlab::lab::check_unreported(                                                \
          ::clothlab::lab::near(lab_got_, lab_expected_, (tolerance)))) {               \
  } else                                                                                \
    EXPECT_TRUE(::clothlab::lab::near(lab_got_, lab_expected_, (tolerance)))            \
        << ::clothlab::lab::force_message(lab_got_, lab_expected_, (tolerance), (what), \
                                          (reversed))                                   \
        << ::clothlab::lab::difference(lab_got_, lab_expected_, (tolerance))

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
// "(3 of 25 are wrong)", on a line of its own.
inline std::string how_many_wrong(std::size_t wrong, std::size_t count) {
  return "\n    " +
         format(trn("(%zu of %zu is wrong)", "(%zu of %zu are wrong)", wrong), wrong, count);
}
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
        << ::clothlab::lab::how_many_wrong(lab_failures_.wrong, (count))

// The same for forces (LAB_EXPECT_FORCE: a reversed force is named as such).
#define LAB_EXPECT_EVERY_FORCE(k, count, got, expected, tolerance, what, reversed)               \
  if (const ::clothlab::lab::failures lab_failures_ = ::clothlab::lab::count_failures(           \
          (count),                                                                               \
          [&](std::size_t k) { return ::clothlab::lab::near((got), (expected), (tolerance)); }); \
      lab_failures_.wrong == 0) {                                                                \
  } else if (const std::size_t k = lab_failures_.first; false) {                                 \
  } else                                                                                         \
    LAB_EXPECT_FORCE(got, expected, tolerance, what, reversed)                                   \
        << ::clothlab::lab::how_many_wrong(lab_failures_.wrong, (count))
