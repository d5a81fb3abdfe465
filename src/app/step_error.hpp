// An exception thrown by a step of a CPU stage (the student's code: a neighbour outside the
// grid, an index past the end) ends a headless run with exit 1 and one line naming the function
// that threw, not std::terminate's "terminate called" and exit 134.
#pragma once

#include <cstdio>
#include <exception>
#include <functional>
#include <string>
#include <utility>

#include "app/command_line.hpp"  // one_line
#include "core/i18n.hpp"

namespace clothlab {

// The part of the step (Stage::compute_force, apply_force or apply_constraints, as `class_name`
// ::part) that throws at step `failed_step` (1 the first): `fresh`, a stage made like the one
// that threw, replays the steps before it (the CPU path is deterministic), then runs the parts
// one by one. "Stage::step" when none of them throws alone (the step's own code did, or the
// replay ran differently).
template <class Stage>
std::string part_that_throws(Stage& fresh, const std::string& class_name, long failed_step) {
  const std::string whole = class_name + "::step";
  try {
    for (long s = 1; s < failed_step; ++s)
      fresh.step();
  } catch (...) {
    return whole;
  }
  const std::pair<const char*, std::function<void()>> parts[] = {
      {"compute_force", [&] { fresh.compute_force(); }},
      {"apply_force", [&] { fresh.apply_force(); }},
      {"apply_constraints", [&] { fresh.apply_constraints(); }}};
  for (const auto& [name, run] : parts) {
    try {
      run();
    } catch (...) {
      return class_name + "::" + name;
    }
  }
  return whole;
}

// The one line that reports it: "<function> threw at step S (t = T s): <what>".
inline std::string step_error_line(const std::string& function, long step, double time_step,
                                   const std::exception& error) {
  return format(tr("%s threw at step %ld (t = %g s): %s"), function.c_str(), step,
                double(step) * time_step, one_line(error.what()).c_str());
}

}  // namespace clothlab
