// Questions 1 and 3 in the window (src/window/frame_anatomy.hpp): the frame anatomy names, for
// each phase of the last frame, the function and the file that does it, with its measured time.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "window/frame_anatomy.hpp"

namespace clothlab {
namespace {

const anatomy_row* find_row(const std::vector<anatomy_row>& rows, const std::string& phase) {
  const auto row = std::find_if(rows.begin(), rows.end(),
                                [&](const anatomy_row& r) { return r.phase == phase; });
  return row == rows.end() ? nullptr : &*row;
}

TEST(FrameAnatomy, TheCpuClothShowsTheHandoutsSceneStructureWithItsTimes) {
  const frame_anatomy measured{.stage = stage_kind::cloth,
                               .load_seconds = 55e-6,
                               .frame = 263,
                               .steps = 8,
                               .compute_force_seconds = 137e-6,
                               .apply_force_seconds = 35e-6,
                               .constraints_seconds = 6e-6,
                               .check_seconds = 4e-6,
                               .normals_seconds = 2e-6,
                               .draw_seconds = 375e-6};
  const std::vector<anatomy_row> rows = anatomy_rows(measured);
  // load_model once: initialisation; then draw_scene's k steps of compute_force, apply_force,
  // the constraints; the normals; the drawing.
  const std::vector<std::string> order = {
      "load_model",  "draw_scene",  "8 steps, each:", "compute_force",
      "apply_force", "constraints", "normals",        "draw"};
  std::size_t next = 0;
  for (const anatomy_row& row : rows) {
    if (next < order.size() && row.phase == order[next])
      ++next;
  }
  EXPECT_EQ(next, order.size()) << "the phases are not in the handout's order";
  const anatomy_row* forces = find_row(rows, "compute_force");
  ASSERT_NE(forces, nullptr);
  EXPECT_NE(forces->where.find("spring_mesh.cpp"), std::string::npos);
  EXPECT_EQ(forces->question3, "force computation");
  EXPECT_DOUBLE_EQ(forces->seconds, 137e-6);
  EXPECT_EQ(find_row(rows, "apply_force")->question3, "numerical integration");
  const anatomy_row* constraints = find_row(rows, "constraints");
  ASSERT_NE(constraints, nullptr);
  EXPECT_NE(constraints->where.find("apply_constraints"), std::string::npos);
  EXPECT_NE(constraints->where.find("apply_ground_contact"), std::string::npos);
  EXPECT_DOUBLE_EQ(constraints->seconds, 6e-6);
  EXPECT_EQ(constraints->question3, "constraints");
  EXPECT_EQ(find_row(rows, "load_model")->question3, "initialisation");
  EXPECT_DOUBLE_EQ(find_row(rows, "load_model")->seconds, 55e-6);
  EXPECT_EQ(find_row(rows, "draw")->question3, "display");
  EXPECT_EQ(find_row(rows, "normals")->question3, "display");
}

TEST(FrameAnatomy, EachStageNamesItsOwnFile) {
  const std::vector<anatomy_row> spring = anatomy_rows({.stage = stage_kind::spring, .steps = 1});
  EXPECT_NE(find_row(spring, "compute_force")->where.find("single_spring.cpp"), std::string::npos);
  EXPECT_NE(find_row(spring, "1 step, each:"), nullptr);
  EXPECT_EQ(find_row(spring, "normals"), nullptr);  // masses and coils: no normals to compute
  const std::vector<anatomy_row> chain = anatomy_rows({.stage = stage_kind::coupled});
  EXPECT_NE(find_row(chain, "compute_force")->where.find("coupled_springs.cpp"), std::string::npos);
}

TEST(FrameAnatomy, TheGpuPathNamesItsShaders) {
  const std::vector<anatomy_row> rows =
      anatomy_rows({.stage = stage_kind::cloth, .on_gpu = true, .steps = 16});
  const anatomy_row* steps = find_row(rows, "16 GPU steps");
  ASSERT_NE(steps, nullptr);
  EXPECT_NE(steps->where.find("gpu_step.frag"), std::string::npos);
  EXPECT_EQ(find_row(rows, "compute_force"), nullptr);  // not the CPU's functions
}

TEST(FrameAnatomy, DurationsAreShort) {
  EXPECT_EQ(format_duration(850e-9), "850 ns");
  EXPECT_EQ(format_duration(81e-6), "81 us");
  EXPECT_EQ(format_duration(2.144e-3), "2.14 ms");
  EXPECT_EQ(format_duration(1.2), "1.20 s");
}

}  // namespace
}  // namespace clothlab
