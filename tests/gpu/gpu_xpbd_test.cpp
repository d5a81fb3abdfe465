// XPBD on the compute-shader path against the CPU's (src/core/xpbd.hpp): the same colours in the
// same order, single precision against double. (The teacher's copy's: the student copy has
// neither XPBD nor the compute path.)
//
// The tolerance (single_precision.hpp's reasoning, per substep): the compute path keeps each
// particle's motion over the substep apart from its position (gpu_xpbd_predict.comp), so that a
// substep rounds the positions once, p = x_prev + displacement, by u P at most (u = 2^-24,
// coordinates below P); the sweeps' corrections and the velocity v = displacement / h round
// quantities of the size h |v|, h |v| / P times smaller. The substeps carry a difference without
// growing it (one is backward Euler on the springs, which shrinks every mode, after a prediction
// that carries it), so after S = steps x substeps substeps the positions differ by at most
// u P S, and the velocities by omega_max times that. The Gauss-Seidel order adds nothing: the
// GPU's passes visit the CPU's colours in the CPU's order, and within a colour no two
// constraints share a particle. (Kept as the CPU path, v = (p - x_prev) / h would lose u P / h
// a substep: 2.2e-3 m after 200 steps of the default cloth, instead of 2.6e-6.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "agreement_cases.hpp"
#include "core/spring_mesh.hpp"
#include "gl/gl.hpp"
#include "gl/gl_context.hpp"
#include "gl/gpu_cloth_compute.hpp"
#include "offscreen_suite.hpp"
#include "single_precision.hpp"

namespace clothlab {
namespace {

class GpuXpbd : public offscreen_suite<> {};

struct xpbd_case {
  const char* name;
  cloth_parameters parameters;
  int steps;
};

// The N = 12 agreement cloth (no ground, corners pinned) stepped by XPBD at dt = 0.01 s, five
// times the Euler schemes' limit there, for 0.6 s.
std::vector<xpbd_case> xpbd_cases() {
  cloth_parameters plain = agreement_cloth();
  plain.dynamics.integrator = integrator_kind::xpbd;
  plain.dynamics.time_step = 0.01;
  cloth_parameters windy = plain;
  windy.wind_strength = 10.0;
  windy.wind_direction = {1.0, 2.0, 0.5};
  cloth_parameters dragged = plain;
  dragged.drag = {
      .enabled = true, .ku = 11, .kv = 11, .target = {0.6, 0.6, 0.3}, .stiffness = 200.0};
  cloth_parameters damped = plain;
  damped.dynamics.xpbd = {.substeps = 5, .iterations = 3, .constraint_damping = 20.0};
  return {{"plain", plain, 60},
          {"wind", windy, 60},
          {"drag", dragged, 60},
          {"damped 5 x 3", damped, 60}};
}

struct xpbd_difference {
  double position, velocity;           // m, m/s
  single_precision::bounds tolerance;  // u P S and omega_max u P S
};

xpbd_difference compare(const xpbd_case& c, const cloth_parameters& gpu_parameters) {
  spring_mesh cpu(c.parameters);
  spring_mesh gpu_result(c.parameters);
  gpu_cloth_compute gpu;
  std::string error;
  EXPECT_TRUE(gpu.load(cpu, error)) << error;
  double largest = largest_coordinate(cpu);
  for (int s = 0; s < c.steps; ++s) {
    cpu.step();
    gpu.run(gpu_parameters, 1);
    largest = largest_coordinate(cpu, largest);
  }
  gpu.read_state(gpu_result);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_TRUE(gpu_result.particles().is_finite());
  const int substeps = c.steps * c.parameters.dynamics.xpbd.substeps;
  const double position = single_precision::unit_roundoff * largest * substeps;
  return {max_difference(cpu.particles().position, gpu_result.particles().position),
          max_difference(cpu.particles().velocity, gpu_result.particles().velocity),
          {position, single_precision::stiffest_mode * position}};
}

TEST_F(GpuXpbd, ComputePathStaysWithinFloatRoundingOfTheCpu) {
  std::string why;
  for (const xpbd_case& c : xpbd_cases()) {
    ASSERT_TRUE(gpu_cloth_compute::supports(c.parameters, why)) << why;
    const xpbd_difference d = compare(c, c.parameters);
    std::printf(
        "  xpbd %-13s after %d steps: max |p_gpu - p_cpu| = %.2g m (tolerance %.2g), "
        "max |v_gpu - v_cpu| = %.2g m/s (tolerance %.2g)\n",
        c.name, c.steps, d.position, d.tolerance.position, d.velocity, d.tolerance.velocity);
    EXPECT_LE(d.position, d.tolerance.position) << c.name;
    EXPECT_LE(d.velocity, d.tolerance.velocity) << c.name;
  }
}

// The comparison can fail: a cloth 1 % stiffer on the GPU is outside the tolerance.
TEST_F(GpuXpbd, TheComparisonFailsWhenTheGpuRunsAnotherCloth) {
  const xpbd_case c = xpbd_cases()[0];
  cloth_parameters stiffer = c.parameters;
  stiffer.structural_stiffness *= 1.01;
  const xpbd_difference d = compare(c, stiffer);
  EXPECT_GT(d.position, d.tolerance.position);
}

// The fragment path stays mass-spring: it refuses XPBD by name, and says where it runs.
TEST_F(GpuXpbd, TheFragmentPathRefusesXpbdAndNamesTheComputePath) {
  cloth_parameters p = agreement_cloth();
  p.dynamics.integrator = integrator_kind::xpbd;
  std::string why;
  EXPECT_FALSE(gpu_cloth::supports(p, why));
  EXPECT_NE(why.find("xpbd"), std::string::npos) << why;
  EXPECT_NE(why.find("GPU compute"), std::string::npos) << why;
}

}  // namespace
}  // namespace clothlab
