// The grader's GPU questions: their suites (the runner makes its off-screen OpenGL context, OSMesa,
// at its first GPU request), and the force one GPU step applied to each particle.
#pragma once

#include <gtest/gtest.h>
#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab::lab {

class OffscreenGl : public ::testing::Test {};

// One GPU step of `cloth` (from rest, without gravity or damping) with the parameters p it was
// built from; the force the shader applied to each texel k = ku + N kv, F = m v / dt (single
// precision).
inline std::vector<glm::dvec3> gpu_forces(const student::spring_mesh& cloth,
                                          const cloth_parameters& p) {
  student::spring_mesh state = cloth;
  student::gpu_cloth gpu;
  std::string error;
  const bool loaded = gpu.load(state, error);
  LAB_EXPECT_TRUE(loaded, error);
  if (!loaded)
    quiet_rest_of_test();
  gpu.step(p);
  gpu.read_state(state);
  std::vector<glm::dvec3> force;
  for (std::size_t k = 0; k < state.particles().size(); ++k)
    force.push_back(p.dynamics.mass * state.particles().get_velocity(k) / p.dynamics.time_step);
  return force;
}

}  // namespace clothlab::lab
