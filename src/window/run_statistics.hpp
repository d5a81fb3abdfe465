// What the window measures of a run, for the panel's readouts and the output: the rates of steps,
// frames and stepping alone; the energies of the last frames (question 4); the first tear of a
// cloth. None of it changes the simulation.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <vector>

#include "core/energy.hpp"
#include "core/spring_mesh.hpp"
#include "core/wall_clock.hpp"  // seconds_since

namespace clothlab {

// Steps and frames counted over about half a second of wall-clock time.
class rate_meter {
 public:
  // Starts a new window and forgets the stepping rate shown (e.g. after the cloth changed path).
  void restart();
  // One frame: `steps` steps taken in `stepping_seconds` of stepping alone. Every half second the
  // rates are measured again over the frames since the last time.
  void add_frame(int steps, double stepping_seconds);

  double steps_per_second() const { return steps_per_second_; }
  double frames_per_second() const { return frames_per_second_; }
  // Steps per second of the stepping alone (not drawing nor the panel).
  double stepping_rate() const { return stepping_rate_; }

 private:
  using clock = std::chrono::steady_clock;
  clock::time_point window_start_ = clock::now();
  long steps_in_window_ = 0;
  long frames_in_window_ = 0;
  double stepping_seconds_in_window_ = 0.0;
  double steps_per_second_ = 0.0;
  double frames_per_second_ = 0.0;
  double stepping_rate_ = 0.0;
};

// Question 4: the energies after each of the last frames, oldest first.
class energy_record {
 public:
  static constexpr std::size_t frames_kept = 600;

  void clear();  // the history; the latest energies stay until the next record
  // The energies at simulated time `time` (s), after a frame's steps.
  void record(const energy_breakdown& energy, double time);

  const energy_breakdown& latest() const { return latest_; }
  // Kinetic, gravity, spring and total energy (J) of each frame kept.
  const std::array<std::vector<float>, 4>& values() const { return values_; }
  const std::vector<float>& times() const { return times_; }  // t of each, s

 private:
  energy_breakdown latest_;
  std::array<std::vector<float>, 4> values_;
  std::vector<float> times_;
};

// The springs the cloth has now, every family (on a GPU path, as of the last read-back).
std::size_t intact_spring_count(const spring_mesh& cloth);

// The first tear of a cloth, said once until it is whole again (reset, rebuild).
class tear_report {
 public:
  // After the steps of a frame, at `step` and time `time` (s): prints a line when the cloth has
  // fewer springs than a whole N x N cloth and had not been said to tear.
  void check(const spring_mesh& cloth, long step, double time);

 private:
  bool reported_ = false;
};

}  // namespace clothlab
