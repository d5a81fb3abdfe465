// What the lab's grader shares: vectors printed as the handout writes them, and a check that
// says, in the handout's words, what a wrong answer does.
#pragma once

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstdio>
#include <string>

#include "core/particle_system.hpp"

namespace clothlab::lab {

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

// Checks got against expected; on failure the message is `what` (the handout's terms), then
// the two vectors.
#define LAB_EXPECT_VEC(got, expected, tolerance, what)                              \
  EXPECT_TRUE(::clothlab::lab::near((got), (expected), (tolerance)))                \
      << (what) << "\n    expected " << ::clothlab::lab::text(expected) << ", got " \
      << ::clothlab::lab::text(got)

}  // namespace clothlab::lab
