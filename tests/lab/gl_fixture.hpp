// An off-screen OpenGL context (OSMesa) for the grader's GPU questions, made once per suite.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "gl/gl_context.hpp"

namespace clothlab::lab {

class OffscreenGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    context_ = create_offscreen_context(16, 16, error);
    ASSERT_NE(context_, nullptr) << error;
  }
  static void TearDownTestSuite() { context_.reset(); }

  static inline std::unique_ptr<gl_context> context_;
};

}  // namespace clothlab::lab
