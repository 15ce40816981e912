// Backlash compensation: the slack each axis's drive takes up at a reversal, as extra motor
// steps that move no load and so change no reported position.
#pragma once

#include <array>
#include <cstdint>

#include "gantry/core/axes.hpp"  // kAxisCount

namespace gantry {

struct Settings;
struct Trapezoid;

// Per axis, the slack `B` (axes.<axis>.backlash in whole motor steps) and where the motor
// stands in it: `offset` = motor steps - load steps, 0 after travel towards minus, B after
// travel towards plus. A move that reverses first turns the motor through the slack: those
// takeup steps come before the move's own steps, so the load (and the count reported) moves
// only once the slack is taken. Until an axis has moved (power-up, after an E-stop) the side
// of its slack is unknown: its first move takes none and sets it (docs/hardware.md).
class Backlash {
 public:
  explicit Backlash(const Settings& s) { configure(s); }
  // New steps per unit, backlash or limits (at rest): the offsets are kept within the slack.
  void configure(const Settings& s);

  // The takeup steps a move of `axis` towards `positive` needs before its own steps.
  std::int64_t takeup(int axis, bool positive) const {
    const Axis& a = axes_[axis];
    if (!a.known || a.slack == 0) return 0;
    return positive ? a.slack - a.offset : a.offset;
  }
  // A takeup step went into the words.
  void took_up(int axis, bool positive) { axes_[axis].offset += positive ? 1 : -1; }
  // A step of the load went into the words: the first one sets the side of the slack.
  void moved(int axis, bool positive) {
    Axis& a = axes_[axis];
    if (a.known) return;
    a.known = true;
    a.offset = positive ? a.slack : 0;
  }
  // A step taken with no compensation (MI's own turning): its direction is the slack's side.
  void turned(int axis, bool positive) {
    Axis& a = axes_[axis];
    a.known = true;
    a.offset = positive ? a.slack : 0;
  }
  // After an E-stop: the takeup steps in flight may not have played; the side is unknown.
  void forget() {
    for (Axis& a : axes_) a.known = false;
  }
  std::int64_t offset(int axis) const { return axes_[axis].offset; }
  std::int64_t slack(int axis) const { return axes_[axis].slack; }
  // The takeup's speed along the axis, steps/s: the axis's corner jump (the largest speed
  // change the planner lets it make at once), so the motor's speed rises by no more.
  double speed(int axis) const { return axes_[axis].speed; }

  // The time into `profile` (seconds) of motor step q (1-based) of a move towards
  // `positive` with `takeup` steps of slack first: the motor turns through s(t) +
  // min(speed t, takeup) steps, s(t) the load's steps along the move (`from`, `to`: the
  // segment's ends, `count`: the axis's count at its start, all in steps), and step q is due
  // where that crosses q - 1/2. So the first `takeup` steps are the slack, the load's own
  // steps keep their times once it is taken, and the motor is never faster than the load
  // plus `speed`.
  static double motor_step_time(const Trapezoid& profile, double from, double to,
                                std::int64_t count, bool positive, std::int64_t takeup,
                                double speed, std::int64_t q);

 private:
  struct Axis {
    std::int64_t slack = 0, offset = 0;
    double speed = 1;
    bool known = false;
  };
  std::array<Axis, kAxisCount> axes_{};
};

}  // namespace gantry
