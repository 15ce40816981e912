// Stop-at-every-move trapezoid planning.
#include "gantry/motion/trapezoid_planner.hpp"

#include "gantry/motion/path_limits.hpp"  // path_limits

namespace gantry {

void TrapezoidPlanner::move(const CanonMove& m) {
  if (m.kind == MoveKind::Dwell) {
    PlannedSegment seg;
    seg.from = seg.to = m.to;
    seg.dwell_s = m.dwell_s;
    seg.loc = m.loc;
    planned_time_ += m.dwell_s;
    out_.segment(seg);
    return;
  }
  const PathLimits lim = path_limits(m, settings_);
  if (lim.length == 0) return;
  PlannedSegment seg;
  seg.from = m.from;
  seg.to = m.to;
  seg.profile = Trapezoid::plan(lim.length, 0, lim.speed, 0, lim.accel);
  seg.speed_class = m.speed_class;
  seg.loc = m.loc;
  planned_time_ += seg.profile.duration();
  out_.segment(seg);
}

}  // namespace gantry
