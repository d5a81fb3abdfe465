// An off-screen OpenGL context (OSMesa) for the grader's GPU questions, made once per suite,
// and the force one GPU step applied to each particle.
#pragma once

#include <gtest/gtest.h>
#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

#include "core/spring_mesh.hpp"
#include "gl/gl_context.hpp"
#include "gl/gpu_cloth.hpp"

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

// One GPU step of `cloth` (from rest, without gravity or damping) with the parameters p it was
// built from; the force the shader applied to each texel k = ku + N kv, F = m v / dt (single
// precision).
inline std::vector<glm::dvec3> gpu_forces(const spring_mesh& cloth, const cloth_parameters& p) {
  spring_mesh state = cloth;
  gpu_cloth gpu;
  std::string error;
  EXPECT_TRUE(gpu.load(state, error)) << error;
  gpu.step(p);
  gpu.read_state(state);
  std::vector<glm::dvec3> force;
  for (std::size_t k = 0; k < state.particles().size(); ++k)
    force.push_back(p.dynamics.mass * state.particles().get_velocity(k) / p.dynamics.time_step);
  return force;
}

}  // namespace clothlab::lab
