// An exception from a stage's step (the student's code) is reported in one line naming the
// function that threw (src/app/step_error.hpp): the replay finds the part of the step.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "app/step_error.hpp"

namespace clothlab {
namespace {

// A stage whose part `throwing` reads past the end of its array from step `from` on, as a
// border check on the flat index would.
struct faulty_stage {
  struct settings {
    std::string throwing;  // "compute_force", "apply_force", "apply_constraints" or "step"
    long from = 1;
  } parameters;
  long steps_done = 0;
  std::vector<double> values = std::vector<double>(4);

  explicit faulty_stage(const settings& p) : parameters(p) {}
  void part(const char* name) {
    if (parameters.throwing == name && steps_done + 1 >= parameters.from)
      (void)values.at(values.size());  // std::out_of_range
  }
  void compute_force() { part("compute_force"); }
  void apply_force() { part("apply_force"); }
  void apply_constraints() { part("apply_constraints"); }
  void step() {
    part("step");
    compute_force();
    apply_force();
    apply_constraints();
    ++steps_done;
  }
};

// The stage that threw: its step `failed` throws.
long failing_step(faulty_stage& stage) {
  for (long s = 1; s <= 100; ++s) {
    try {
      stage.step();
    } catch (const std::exception&) {
      return s;
    }
  }
  return 0;
}

TEST(StepError, TheReplayNamesThePartThatThrows) {
  for (const char* part : {"compute_force", "apply_force", "apply_constraints"}) {
    const faulty_stage::settings settings{part, 7};
    faulty_stage run(settings);
    const long failed = failing_step(run);
    ASSERT_EQ(failed, 7) << part;
    faulty_stage fresh(run.parameters);
    EXPECT_EQ(part_that_throws(fresh, "spring_mesh", failed), std::string("spring_mesh::") + part);
  }
}

TEST(StepError, TheStepItselfIsNamedWhenNoPartThrowsAlone) {
  faulty_stage run({"step", 3});
  const long failed = failing_step(run);
  ASSERT_EQ(failed, 3);
  faulty_stage fresh(run.parameters);
  EXPECT_EQ(part_that_throws(fresh, "coupled_springs", failed), "coupled_springs::step");
}

TEST(StepError, TheReportIsOneLineWithTheStepAndTheError) {
  const std::runtime_error error("spring_intact(19, 0, 1, 0): outside\nthe grid");
  const std::string line = step_error_line("spring_mesh::compute_force", 5, 0.002, error);
  EXPECT_EQ(line,
            "spring_mesh::compute_force threw at step 5 (t = 0.01 s): spring_intact(19, 0, 1, "
            "0): outside\\nthe grid");
}

}  // namespace
}  // namespace clothlab
