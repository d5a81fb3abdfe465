// The phases of one step of every stage, as the handout names them (question 3), and what a
// caller may wrap around each: the window times them for the frame anatomy (questions 1 and 3),
// every other caller (the headless run, the benchmarks, the tests) just runs them.
#pragma once

namespace clothlab {

enum class step_phase {
  forces,       // compute_force: the forces from the positions at the start of the step
  integration,  // apply_force (or a scheme of the stability lab): v and p over dt
  constraints   // apply_constraints: what the positions may not do (the ground of question 9)
};

// The wrapper of a plain step: runs the phase, nothing around it.
struct run_phase {
  template <class Phase>
  void operator()(step_phase, Phase&& phase) const {
    phase();
  }
};

}  // namespace clothlab
