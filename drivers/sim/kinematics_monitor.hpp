// Reconstructs each axis's velocity and acceleration from step times alone, and keeps the
// worst ratio of each to the axis's limit: the independent check that motion stayed legal.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "gantry/core/axes.hpp"  // kAxisCount

namespace gantry {

struct AxisLimits {
  double steps_per_unit = 1, max_speed = 1, max_accel = 1;
  double max_jump = 0;  // a speed change the axis may make at once (a corner), units/s
};

// Method. Steps are grouped into windows of consecutive steps in one direction spanning at
// least `window_s` (or cut short by a reversal). A window from step j to step j+n holds
// exactly n steps of travel, so its mean velocity n / (spu * dt) is exact up to the tick
// rounding of its two ends; under constant acceleration that mean is the velocity at the
// window's mid-time. Acceleration is the change of mean velocity between adjacent windows
// over the distance between their mid-times. Windows share their boundary step, so no
// motion is left out. A long window (10 ms at the default) keeps tick rounding below 0.1 %
// of the velocity; it averages, so it can hide a brief excess but never invent one.
//
// Corners: a planner may change an axis's speed at once by up to max_jump (the corner jump,
// as steppers start at their start speed). Such a change lands between two windows, so the
// acceleration ratio counts only the change beyond max_jump: (|dv| - max_jump) / (a dt).
// With max_jump 0 the ratio is the plain one; with more it is a joint bound on corners and
// acceleration, which tolerates a sustained excess up to max_jump / dt (docs/planner.md).
//
// Violations. A window faster than its axis's max_speed, or a change between windows beyond
// the jump faster than its max_accel, by more than kTolerance (0.1 %: a window's tick rounding
// stays below it) is a violation: counted, and the first few kept for the run's report.
class KinematicsMonitor {
 public:
  static constexpr double kTolerance = 1.001;
  struct Violation {
    std::int64_t tick;  // where it was seen: the window's start (for a change, between two)
    int axis;
    bool accel;    // an acceleration; otherwise a velocity
    double ratio;  // of the limit
  };

  KinematicsMonitor(const std::array<AxisLimits, kAxisCount>& limits, double tick_s,
                    double window_s = 0.010);

  void on_step(int axis, std::int64_t tick, bool positive);
  void finish();  // closes the open windows at the end of a run
  // New limits (a recalibration at rest): the open windows close under the old ones.
  void set_limits(const std::array<AxisLimits, kAxisCount>& limits) {
    finish();
    for (Window& w : axes_) w.have_prev = false;
    limits_ = limits;
  }

  double max_velocity_ratio() const;
  double max_accel_ratio() const;
  double velocity_ratio(int axis) const { return axes_[axis].max_v_ratio; }
  double accel_ratio(int axis) const { return axes_[axis].max_a_ratio; }
  std::uint64_t violations() const { return violation_count_; }
  const std::vector<Violation>& first_violations() const { return violations_; }

 private:
  struct Window {
    bool open = false;
    bool positive = true;
    std::int64_t first = 0, last = 0, intervals = 0;
    bool have_prev = false;
    double prev_v = 0, prev_mid = 0;
    double max_v_ratio = 0, max_a_ratio = 0;
  };
  void close(int axis);
  void check(int axis, std::int64_t tick, bool accel, double ratio);

  std::array<AxisLimits, kAxisCount> limits_;
  double tick_s_;
  std::int64_t window_ticks_;
  std::array<Window, kAxisCount> axes_{};
  std::uint64_t violation_count_ = 0;
  std::vector<Violation> violations_;  // the first few
};

}  // namespace gantry
