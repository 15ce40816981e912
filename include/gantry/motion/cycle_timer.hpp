// A program's cycle time: its moves planned as the machine would run them, without running
// them (what `gantry estimate`, the preview and the check before a run report).
#pragma once

#include "gantry/canon/canon_move.hpp"            // MotionSink
#include "gantry/motion/lookahead_planner.hpp"  // LookAheadPlanner
#include "gantry/settings/settings.hpp"          // Settings

namespace gantry {

// Plans every move it receives and sums the planned durations; each move also goes on to
// `also` (a preview drawing them), when given. Operator waits (PAUSE with no time) count 0.
class CycleTimer : public MotionSink {
 public:
  CycleTimer(const Settings& settings, double feed_override, MotionSink* also = nullptr);
  void move(const CanonMove& m) override;
  void flush() override;
  void settings_changed(const Settings& s) override;
  double seconds() const { return planner_.planned_time(); }

 private:
  class Discard : public SegmentSink {
   public:
    void segment(const PlannedSegment&) override {}
    void flush() override {}
  };
  Discard segments_;
  LookAheadPlanner planner_;
  MotionSink* also_;
};

}  // namespace gantry
