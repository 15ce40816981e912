// The readout's lines for the console's status and the window.
#include "gantry/session/readout_lines.hpp"

#include <fmt/format.h>

#include "gantry/session/feed_override.hpp"  // feed_override_text
#include "gantry/session/live_position.hpp"  // shown
namespace gantry::session {

std::string state_word(const ControllerStatus& s) {
  if (s.state == MachineState::Paused && s.step_hold) return "step";
  if (s.warning) return "WARNING: about to move";
  if (s.state == MachineState::Paused && s.phase != FeedPhase::Held) return "pausing";
  return state_name(s.state);
}

std::string readout_text(std::string_view state, const Vec6& p, Units u, std::string_view names) {
  std::string out = fmt::format("{:<9}", state);
  for (int i = 0; i < kAxisCount; ++i)
    out += fmt::format("{} {:.4f}  ", names[static_cast<size_t>(i)], shown(p[i]));
  return out + units_name(u);
}
std::string spindle_text(const ControllerStatus& s, double recorded_rpm) {
  const bool on = (s.outputs & 1u) != 0;
  const double rpm = s.spindle_rpm > 0 ? s.spindle_rpm : recorded_rpm;
  if (rpm <= 0) return on ? "spindle on" : "spindle off";
  return fmt::format("spindle {}, {:.0f} RPM{}", on ? "on" : "off", rpm,
                     s.spindle_rpm > 0 ? "" : " (set on the spindle; TR recorded it)");
}

std::string speeds_text(const SpeedSettings& v, Units u, double feed_override) {
  return fmt::format("move XY {:g}, Z {:g}  jog XY {:g}, Z {:g} {}/s; {}", v.move.xy, v.move.z,
                     v.jog.xy, v.jog.z, units_name(u), feed_override_text(feed_override));
}

}  // namespace gantry::session
