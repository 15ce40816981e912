// Planned segments: a straight path with its speed profile, ready for step generation.
#pragma once

#include <optional>

#include "gantry/canon/canon_move.hpp"  // SpeedClass, Vec6, SourceLoc
#include "gantry/motion/trapezoid.hpp"   // Trapezoid

namespace gantry {

struct PlannedSegment {
  Vec6 from = Vec6::Zero();  // units
  Vec6 to = Vec6::Zero();
  Trapezoid profile;   // along |to - from|
  double dwell_s = 0;  // a wait with no motion (profile empty)
  bool warning = false;  // the dwell is SW's warning that the machine is about to move
  int output = 0;      // > 0: switch this output (1-based) at this point, at rest
  bool output_on = false;
  std::optional<double> spindle_rpm;  // set: at rest, the spindle speed output to this (TR)
  // Set: at rest, the axis moving on its own (MI) changes to this (comes to rest if it is
  // not running); the planned path leaves that axis alone while it runs.
  std::optional<IndependentMotion> independent;
  SpeedClass speed_class = SpeedClass::Move;
  unsigned resting_channels = 0;  // its move's (CanonMove::resting_channels)
  // The planner's speeds along the path: the file's (before the feed override) and the axes'
  // limit, and the override it was planned with. A live override change re-ramps what is not
  // yet generated from them (MotionFeeder); 0: not to be re-ramped (a dwell, SB3's steady
  // short move).
  double v_commanded = 0, v_machine = 0, planned_override = 1;
  SourceLoc loc;
  RunCount count;  // its move's (CanonMove::count)
};

class SegmentSink {
 public:
  virtual ~SegmentSink() = default;
  virtual void segment(const PlannedSegment& s) = 0;
  virtual void flush() = 0;  // no more segments: complete everything pending
  // New values for the segments that follow (see MotionSink::settings_changed).
  virtual void settings_changed(const Settings&) {}
};

}  // namespace gantry
