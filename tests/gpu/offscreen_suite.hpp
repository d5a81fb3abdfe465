// What the GPU tests share: a suite's off-screen OpenGL context (made before its first test,
// deleted after its last; width x height pixels of framebuffer), and the largest difference of
// two runs' values.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gl/gl_context.hpp"

namespace clothlab {

template <int width = 16, int height = 16>
class offscreen_suite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    context_ = create_offscreen_context(width, height, error).release();
    ASSERT_NE(context_, nullptr) << error;
  }
  static void TearDownTestSuite() {
    delete context_;
    context_ = nullptr;
  }
  static inline gl_context* context_ = nullptr;
};

// max |a[i] - b[i]|, a and b of the same size.
inline double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
}

}  // namespace clothlab
