// Where the tool is, from the interpreter at rest and from the played steps under way.
#include "gantry/session/live_position.hpp"

namespace gantry::session {

void LivePosition::snapshot(const ModalState& m, const Settings& s) {
  table_zero_ = m.zero + m.applied_offset;
  offset_ = m.machine_origin + table_zero_;
  position_ = m.position;
  for (int i = 0; i < kAxisCount; ++i) steps_per_unit_[i] = s.axes[i].steps_per_unit;
  axes_ = s.axes;
}

Vec6 LivePosition::wrapped(Vec6 p) const {
  for (int i = 0; i < kAxisCount; ++i) p[i] = reported_position(axes_[i], p[i]);
  return p;
}

Vec6 LivePosition::from_steps(const ControllerStatus& st) const {
  Vec6 p;
  for (int i = 0; i < kAxisCount; ++i)
    p[i] = static_cast<double>(st.steps[i]) / steps_per_unit_[i] - offset_[i];
  return p;
}

}  // namespace gantry::session
