// The cycle time of a program's moves (cycle_timer.hpp).
#include "gantry/motion/cycle_timer.hpp"

namespace gantry {

CycleTimer::CycleTimer(const Settings& settings, double feed_override, MotionSink* also)
    : planner_(settings, segments_), also_(also) {
  planner_.feed_override(feed_override);
}

void CycleTimer::move(const CanonMove& m) {
  planner_.move(m);
  if (also_) also_->move(m);
}

void CycleTimer::flush() {
  planner_.flush();
  if (also_) also_->flush();
}

void CycleTimer::settings_changed(const Settings& s) {
  planner_.settings_changed(s);
  if (also_) also_->settings_changed(s);
}

}  // namespace gantry
