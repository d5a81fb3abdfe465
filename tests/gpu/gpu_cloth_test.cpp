// The GPU cloth (handout section 5) against the CPU cloth: both implement docs/model.md, the
// GPU in single precision, the CPU in double precision, so the same run on both paths must stay
// within the reach of float rounding (single_precision.hpp). Runs in an off-screen context
// (OSMesa or EGL: llvmpipe here, a real GPU's driver where there is one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "agreement_cases.hpp"
#include "core/spring_mesh.hpp"
#include "gl/cloth_paths.hpp"
#include "gl/gl.hpp"
#include "gl/gl_context.hpp"
#include "gl/gpu_cloth.hpp"
#include "gl/gpu_cloth_compute.hpp"
#include "offscreen_suite.hpp"
#include "single_precision.hpp"

namespace clothlab {
namespace {

// The agreement cases and their tolerances: agreement_cases.hpp, single_precision.hpp.
constexpr int grid_size = agreement_grid_size;

class GpuCloth : public offscreen_suite<> {};

cloth_parameters small_cloth() {
  return agreement_cloth();
}

double max_position_difference(const spring_mesh& a, const spring_mesh& b) {
  return max_difference(a.particles().position, b.particles().position);
}

struct run_difference {
  double position;                     // m
  double velocity;                     // m/s
  single_precision::bounds tolerance;  // for the run's steps and coordinates
  int particles_on_ground;             // in the CPU run, at the end
  int particles_on_sphere;             // in the CPU run, at the end
};

// The CPU's run of c and the state a GPU path reached for it: the largest differences, and the
// tolerance for the coordinates the CPU run reached.
run_difference difference_of_runs(const agreement_case& c, const spring_mesh& cpu, double largest,
                                  const spring_mesh& gpu_result) {
  int on_ground = 0;
  for (std::size_t k = 0; k < cpu.particles().size(); ++k) {
    on_ground += cpu.particles().position[3 * k + 2] == c.parameters.ground_height;
  }
  return {max_position_difference(cpu, gpu_result),
          max_difference(cpu.particles().velocity, gpu_result.particles().velocity),
          tolerance_of(c, largest), on_ground, particles_on_sphere(cpu)};
}

// Runs c on the CPU and the same initial cloth, with gpu_parameters, on the fragment path.
run_difference compare_runs(const agreement_case& c, const cloth_parameters& gpu_parameters) {
  spring_mesh cpu(c.parameters);
  spring_mesh gpu_result(c.parameters);
  gpu_cloth gpu;
  std::string error;
  EXPECT_TRUE(gpu.load(cpu, error)) << error;
  double largest = largest_coordinate(cpu);
  for (int s = 0; s < c.steps; ++s) {
    cpu.step();
    gpu.step(gpu_parameters);
    largest = largest_coordinate(cpu, largest);
  }
  gpu.read_state(gpu_result);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_TRUE(cpu.particles().is_finite());
  EXPECT_TRUE(gpu_result.particles().is_finite());
  return difference_of_runs(c, cpu, largest, gpu_result);
}

// The checks of one case on one path, and its line of the test's output.
void expect_within_tolerance(const char* path, const agreement_case& c,
                             const run_difference& difference) {
  const std::string integrator(integrator_name(c.parameters.dynamics.integrator));
  std::printf(
      "  %-8s %-10s %-13s after %3d steps: max |p_gpu - p_cpu| = %.2g m (tolerance %.2g), "
      "max |v_gpu - v_cpu| = %.2g m/s (tolerance %.2g)\n",
      path, c.name, integrator.c_str(), c.steps, difference.position, difference.tolerance.position,
      difference.velocity, difference.tolerance.velocity);
  EXPECT_LE(difference.position, difference.tolerance.position) << c.name << ", " << integrator;
  EXPECT_LE(difference.velocity, difference.tolerance.velocity) << c.name << ", " << integrator;
  if (c.parameters.ground_enabled) {  // the case does test the contact
    EXPECT_GT(difference.particles_on_ground, 0) << c.name << ", " << integrator;
  }
  if (c.parameters.sphere.enabled) {
    EXPECT_GT(difference.particles_on_sphere, 0) << c.name << ", " << integrator;
  }
}

// The comparisons with the CPU need the lab's solution on both paths (questions 6 to 9, 12, 13):
// in the student copy they fail until every question is answered (label gpu-solution).
using SolutionGpuCloth = GpuCloth;

TEST_F(SolutionGpuCloth, SameRunsStayWithinTheToleranceOfTheCpu) {
  for (const agreement_case& c : agreement_cases())
    expect_within_tolerance("fragment", c, compare_runs(c, c.parameters));
}

TEST_F(SolutionGpuCloth, TheComparisonFailsWhenTheGpuRunsAnotherCloth) {
  const agreement_case pinned = agreement_cases()[0];
  cloth_parameters stiffer = pinned.parameters;
  stiffer.structural_stiffness *= 1.01;  // 1 % stiffer on the GPU only
  const run_difference difference = compare_runs(pinned, stiffer);
  EXPECT_GT(difference.position, difference.tolerance.position);
}

TEST_F(SolutionGpuCloth, SwitchingFromCpuToGpuMidRunCarriesTheState) {
  cloth_parameters p = agreement_cases()[1].parameters;  // wind
  spring_mesh cpu(p);
  for (int s = 0; s < 100; ++s)
    cpu.step();
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cpu, error)) << error;
  spring_mesh gpu_result(p);
  gpu.read_state(gpu_result);
  // Loading rounds to float: u |x| at most.
  double largest = largest_coordinate(cpu);
  EXPECT_LE(max_position_difference(cpu, gpu_result), single_precision::unit_roundoff * largest);
  constexpr int steps = 200;
  for (int s = 0; s < steps; ++s) {
    cpu.step();
    gpu.step(p);
    largest = largest_coordinate(cpu, largest);
  }
  gpu.read_state(gpu_result);
  // The load's rounding and the steps' (single_precision.hpp).
  EXPECT_LE(max_position_difference(cpu, gpu_result),
            single_precision::after(1 + steps, largest, p.dynamics.integrator, p.dynamics.time_step)
                .position);
}

TEST_F(SolutionGpuCloth, PinnedParticlesStayExactlyInPlaceWithZeroVelocity) {
  cloth_parameters p = agreement_cases()[1].parameters;  // wind, the corners pinned
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  for (int s = 0; s < 1000; ++s)
    gpu.step(p);
  spring_mesh result(p);
  gpu.read_state(result);
  // The two corners that question 7 pins (any two of the four) stay; the cloth fell.
  std::size_t pinned = 0;
  double lowest = 0.0;
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    lowest = std::min(lowest, result.particles().position[3 * k + 2]);
    if (!cloth.particles().is_fixed[k])
      continue;
    ++pinned;
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(result.particles().position[3 * k + c],
                static_cast<float>(cloth.particles().position[3 * k + c]));
      EXPECT_EQ(result.particles().velocity[3 * k + c], 0.0);
    }
  }
  EXPECT_EQ(pinned, 2u);
  EXPECT_LT(lowest, -0.1);
}

TEST_F(SolutionGpuCloth, NoParticleEverEndsBelowTheGround) {
  cloth_parameters p = small_cloth();
  p.pins = pin_mode::none;
  p.ground_enabled = true;
  p.ground_height = -0.3;
  p.wind_strength = 3.0;
  p.wind_direction = {1.0, 0.0, 1.0};
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  const double ground = static_cast<float>(p.ground_height);  // z_g as the GPU holds it
  int touching = 0;
  for (int s = 0; s < 1000; ++s) {
    gpu.step(p);
    if (s % 100 != 99)
      continue;
    gpu.read_state(cloth);
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const double z = cloth.particles().position[3 * k + 2];
      ASSERT_GE(z, ground) << "particle " << k << " after " << s + 1 << " steps";
      touching += z == ground;
    }
  }
  EXPECT_GT(touching, 0);  // it did reach the ground (a free fall of 0.3 m takes 0.25 s)
}

TEST_F(GpuCloth, FirstStepOfAFreeFlatClothIsGravityTimesDtExactly) {
  cloth_parameters p = small_cloth();
  p.pins = pin_mode::none;
  p.dynamics.damping = 0.7;  // multiplies a zero velocity: no effect on the first step
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  gpu.step(p);
  gpu.read_state(cloth);
  // Flat and at rest, every spring force lies in the plane z = 0: a_z = -g0 exactly, so
  // v_z = dt (-g0) and z = dt v_z, each one float multiplication.
  const float dt = static_cast<float>(p.dynamics.time_step);
  const float expected_vz = dt * -static_cast<float>(p.dynamics.gravity);
  const float expected_z = dt * expected_vz;
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    EXPECT_EQ(cloth.particles().velocity[3 * k + 2], expected_vz) << "particle " << k;
    EXPECT_EQ(cloth.particles().position[3 * k + 2], expected_z) << "particle " << k;
  }
}

TEST_F(SolutionGpuCloth, NormalTextureHoldsTheNormalsOfTheCurrentPositions) {
  cloth_parameters p = agreement_cases()[1].parameters;  // wind: a curved cloth
  spring_mesh cpu(p);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cpu, error)) << error;
  constexpr int steps = 200;
  double largest = largest_coordinate(cpu);
  for (int s = 0; s < steps; ++s) {
    cpu.step();
    gpu.step(p);
    largest = largest_coordinate(cpu, largest);
  }
  cpu.compute_normals();
  std::vector<float> texels(4 * cpu.particles().size());
  glBindTexture(GL_TEXTURE_2D, gpu.normal_texture());
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, texels.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  double normal_difference = 0.0;
  for (std::size_t k = 0; k < cpu.particles().size(); ++k) {
    for (std::size_t c = 0; c < 3; ++c) {
      normal_difference =
          std::max(normal_difference, std::abs(texels[4 * k + c] - cpu.normals()[3 * k + c]));
    }
  }
  // n = normalize(d_u x d_v), from differences of positions at least h apart: positions within
  // delta of the CPU's turn d_u and d_v by 2 delta / h at most each, so n by 4 delta / h.
  const double delta =
      single_precision::after(steps, largest, p.dynamics.integrator, p.dynamics.time_step).position;
  const double h = p.side_length / (grid_size - 1);
  std::printf("  max |n_gpu - n_cpu| = %.2g (tolerance %.2g)\n", normal_difference, 4 * delta / h);
  EXPECT_LE(normal_difference, 4 * delta / h);
  double tilt = 0.0;  // curved, whichever two corners question 7 pins: some normal leans
  for (std::size_t k = 0; k < cpu.particles().size(); ++k)
    tilt = std::max(tilt, std::hypot(cpu.normals()[3 * k], cpu.normals()[3 * k + 1]));
  EXPECT_GT(tilt, 0.01);
}

TEST_F(GpuCloth, StepLeavesTheCallersGlStateAsItFoundIt) {
  cloth_parameters p = small_cloth();
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  glViewport(1, 2, 3, 4);
  glEnable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  gpu.step(p);
  GLint viewport[4] = {};
  glGetIntegerv(GL_VIEWPORT, viewport);
  EXPECT_EQ(viewport[0], 1);
  EXPECT_EQ(viewport[1], 2);
  EXPECT_EQ(viewport[2], 3);
  EXPECT_EQ(viewport[3], 4);
  GLint framebuffer = -1;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  EXPECT_EQ(framebuffer, 0);
  EXPECT_EQ(glIsEnabled(GL_BLEND), GL_TRUE);
  GLint polygon_mode[2] = {};
  glGetIntegerv(GL_POLYGON_MODE, polygon_mode);
  EXPECT_EQ(polygon_mode[0], GL_LINE);
  glDisable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  // and blending did not leak into the step: the run still agrees with the CPU, within the
  // rounding of the load and of one step
  cloth.step();
  spring_mesh result(p);
  gpu.read_state(result);
  EXPECT_LE(max_position_difference(cloth, result),
            single_precision::after(2, largest_coordinate(cloth), p.dynamics.integrator,
                                    p.dynamics.time_step)
                .position);
}

// cloth_paths::read_normals reads the drawn normal texture through a framebuffer (OpenGL ES, the
// web build's GL, has no glGetTexImage): the texture's texels, on each GPU path that runs here,
// with the caller's read framebuffer bound again.
TEST_F(GpuCloth, ReadNormalsGivesTheTexelsOfTheDrawnNormalTexture) {
  cloth_parameters p = small_cloth();
  p.wind_strength = 3.0;
  cloth_paths paths(p);
  paths.check_compute_offered();
  GLuint callers_framebuffer = 0;
  glGenFramebuffers(1, &callers_framebuffer);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, callers_framebuffer);
  for (const cloth_backend backend : {cloth_backend::gpu, cloth_backend::gpu_compute}) {
    std::string error;
    if (backend == cloth_backend::gpu_compute && !paths.compute_offered(error)) {
      std::printf("  no compute path here: %s\n", error.c_str());
      continue;
    }
    ASSERT_TRUE(paths.load(backend, error)) << error;
    paths.run(20);
    std::vector<float> normals;
    paths.read_normals(normals);
    GLint bound = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &bound);
    EXPECT_EQ(static_cast<GLuint>(bound), callers_framebuffer);
    std::vector<float> texels(normals.size());
    glBindTexture(GL_TEXTURE_2D, paths.textures().normal);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, texels.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    EXPECT_EQ(normals, texels);
    EXPECT_GT(std::abs(normals[0]) + std::abs(normals[1]) + std::abs(normals[2]), 0.5f);  // unit
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &callers_framebuffer);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GpuCloth, GridTooLargeForTheTexturesIsRefusedNamingNAndTheLimit) {
  GLint max_texture_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size);
  GLint max_viewport[2] = {};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_viewport);
  const int limit = std::min({max_texture_size, max_viewport[0], max_viewport[1]});
  ASSERT_GT(limit, 0);
  std::string error;
  EXPECT_FALSE(gpu_cloth::check_grid_size(limit + 1, error));
  EXPECT_NE(error.find("N=" + std::to_string(limit + 1)), std::string::npos) << error;
  EXPECT_NE(error.find(std::to_string(limit)), std::string::npos) << error;
  EXPECT_TRUE(gpu_cloth::check_grid_size(limit, error)) << error;
  EXPECT_FALSE(gpu_cloth::check_grid_size(1, error));
  EXPECT_NE(error.find("N=1"), std::string::npos) << error;
}

TEST_F(GpuCloth, StepBeforeLoadIsRefused) {
  gpu_cloth gpu;
  EXPECT_THROW(gpu.step(small_cloth()), std::logic_error);
}

TEST_F(GpuCloth, IntegratorsOtherThanTheTwoEulersAreRefusedByName) {
  std::string error;
  EXPECT_TRUE(gpu_cloth::supports_integrator(integrator_kind::semi_implicit, error));
  EXPECT_TRUE(gpu_cloth::supports_integrator(integrator_kind::explicit_euler, error));
  for (integrator_kind integrator : all_integrators) {
    if (integrator == integrator_kind::semi_implicit ||
        integrator == integrator_kind::explicit_euler) {
      continue;
    }
    const std::string name(integrator_name(integrator));
    EXPECT_FALSE(gpu_cloth::supports_integrator(integrator, error)) << name;
    EXPECT_NE(error.find(name), std::string::npos) << error;

    cloth_parameters p = small_cloth();
    spring_mesh cloth(p);
    gpu_cloth gpu;
    ASSERT_TRUE(gpu.load(cloth, error)) << error;
    p.dynamics.integrator = integrator;
    EXPECT_THROW(gpu.step(p), std::invalid_argument) << name;
  }
}

}  // namespace
}  // namespace clothlab

namespace clothlab {
namespace {

// The GPU paths run the drag, the sphere and tearing; self-collision is the CPU's alone and is
// refused by name.
TEST(GpuClothSupport, SelfCollisionIsRefusedByName) {
  cloth_parameters p;
  std::string error;
  EXPECT_TRUE(gpu_cloth::supports(p, error)) << error;
  p.drag.enabled = true;
  p.sphere.enabled = true;
  p.tear_strain = 0.2;
  EXPECT_TRUE(gpu_cloth::supports(p, error)) << error;
  p.self_collision_thickness = 0.01;
  EXPECT_FALSE(gpu_cloth::supports(p, error));
  EXPECT_NE(error.find("--self-collision"), std::string::npos) << error;
  EXPECT_NE(error.find("GPU"), std::string::npos) << error;
}

}  // namespace
}  // namespace clothlab

namespace clothlab {
namespace {

using GpuBatch = GpuCloth;

// run(p, count) is count steps: the same state, bit for bit, as count calls of step(p).
TEST_F(GpuBatch, ABatchIsTheSameAsSingleSteps) {
  cloth_parameters p = small_cloth();
  p.wind_strength = 3.0;
  spring_mesh one_by_one(p);
  spring_mesh batched(p);
  gpu_cloth a, b;
  std::string error;
  ASSERT_TRUE(a.load(one_by_one, error)) << error;
  ASSERT_TRUE(b.load(batched, error)) << error;
  for (int s = 0; s < 40; ++s)
    a.step(p);
  EXPECT_EQ(b.run(p, 40), 0);
  a.read_state(one_by_one);
  b.read_state(batched);
  EXPECT_EQ(one_by_one.particles().position, batched.particles().position);
  EXPECT_EQ(one_by_one.particles().velocity, batched.particles().velocity);
}

// The check on the GPU names the same step as reading the state back after every step and
// looking for a speed past the bound: a free cloth under 100 g passes 50 m/s at its 6th step
// (9.81 m/s gained per step of 0.01 s).
TEST_F(GpuBatch, TheGpuDivergenceCheckNamesTheStepThatReadingBackFinds) {
  cloth_parameters p = small_cloth();
  p.pins = pin_mode::none;
  p.dynamics.gravity = 981.0;
  p.dynamics.damping = 0.0;
  p.dynamics.time_step = 0.01;
  const double bound = 50.0;  // m/s
  spring_mesh cloth(p);
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  int read_back_step = 0;
  for (int s = 1; s <= 200 && read_back_step == 0; ++s) {
    gpu.step(p);
    gpu.read_state(cloth);
    for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
      const glm::dvec3 v = cloth.particles().get_velocity(k);
      if (!std::isfinite(glm::length(v)) || glm::length(v) > bound)
        read_back_step = s;
    }
  }
  ASSERT_EQ(read_back_step, 6);
  spring_mesh again(p);
  ASSERT_TRUE(gpu.load(again, error)) << error;
  EXPECT_EQ(gpu.run(p, 200, bound), read_back_step);
  // A stable cloth: nothing found.
  cloth_parameters stable = small_cloth();
  spring_mesh calm(stable);
  ASSERT_TRUE(gpu.load(calm, error)) << error;
  EXPECT_EQ(gpu.run(stable, 100, bound), 0);
}

TEST_F(GpuBatch, TheGpuDivergenceCheckSeesANotANumber) {
  cloth_parameters p = small_cloth();
  p.pins = pin_mode::none;
  spring_mesh cloth(p);
  cloth.particles().velocity[3 * 5 + 1] = std::nan("");
  gpu_cloth gpu;
  std::string error;
  ASSERT_TRUE(gpu.load(cloth, error)) << error;
  EXPECT_EQ(gpu.run(p, 3, 1e6), 1);
}

}  // namespace
}  // namespace clothlab

// BEGIN TEACHER (the student copy has no compute path: its step shader would hold the answers
// of questions 9, 12 and 13)
namespace clothlab {
namespace {

using SolutionGpuCompute = GpuCloth;

// The compute-shader path against the CPU: the same cases and tolerances as the fragment path.
TEST_F(SolutionGpuCompute, SameRunsStayWithinTheToleranceOfTheCpu) {
  std::string error;
  if (!gpu_cloth_compute::available(error))
    GTEST_SKIP() << error;
  for (const agreement_case& c : agreement_cases()) {
    spring_mesh cpu(c.parameters);
    spring_mesh result(c.parameters);
    gpu_cloth_compute gpu;
    ASSERT_TRUE(gpu.load(cpu, error)) << error;
    double largest = largest_coordinate(cpu);
    for (int s = 0; s < c.steps; ++s) {
      cpu.step();
      largest = largest_coordinate(cpu, largest);
    }
    gpu.run(c.parameters, c.steps);
    gpu.read_state(result);
    expect_within_tolerance("compute", c, difference_of_runs(c, cpu, largest, result));
  }
}

// It can fail: a 1 % stiffer cloth on the compute path leaves the tolerance. (The student copy
// has no compute path: its step shader would hold question 12's answer.)
TEST_F(SolutionGpuCompute, TheComparisonFailsForAnotherCloth) {
  std::string error;
  if (!gpu_cloth_compute::available(error))
    GTEST_SKIP() << error;
  cloth_parameters p = small_cloth();
  cloth_parameters stiffer = p;
  stiffer.structural_stiffness *= 1.01;
  spring_mesh cpu(p);
  spring_mesh result(p);
  gpu_cloth_compute gpu;
  ASSERT_TRUE(gpu.load(cpu, error)) << error;
  double largest = largest_coordinate(cpu);
  for (int s = 0; s < semi_implicit_steps; ++s) {
    cpu.step();
    largest = largest_coordinate(cpu, largest);
  }
  gpu.run(stiffer, semi_implicit_steps);
  gpu.read_state(result);
  EXPECT_GT(max_position_difference(cpu, result),
            single_precision::after(semi_implicit_steps, largest, p.dynamics.integrator,
                                    p.dynamics.time_step)
                .position);
}

}  // namespace
}  // namespace clothlab
// END TEACHER
