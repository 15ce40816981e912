// The baseline planner: one trapezoid per move, starting and ending at rest.
#pragma once

#include "gantry/motion/canon_move.hpp"       // MotionSink
#include "gantry/motion/planned_segment.hpp"  // SegmentSink

namespace gantry {

// Every move accelerates from rest to its path speed and decelerates to rest, within the
// limits path_limits() gives. The look-ahead planner replaces it behind MotionSink.
class TrapezoidPlanner : public MotionSink {
 public:
  TrapezoidPlanner(const Settings& settings, SegmentSink& out) : settings_(settings), out_(out) {}
  void move(const CanonMove& m) override;
  void flush() override { out_.flush(); }

  double planned_time() const { return planned_time_; }  // sum of segment durations, s

 private:
  const Settings& settings_;
  SegmentSink& out_;
  double planned_time_ = 0;
};

}  // namespace gantry
