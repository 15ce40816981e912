// The spindle's line for the console's status and the window's readout.
#include "gantry/session/spindle_text.hpp"

#include <fmt/format.h>

namespace gantry::session {

std::string spindle_text(const ControllerStatus& s, double recorded_rpm) {
  const bool on = (s.outputs & 1u) != 0;
  const double rpm = s.spindle_rpm > 0 ? s.spindle_rpm : recorded_rpm;
  if (rpm <= 0) return on ? "spindle on" : "spindle off";
  return fmt::format("spindle {}, {:.0f} RPM{}", on ? "on" : "off", rpm,
                     s.spindle_rpm > 0 ? "" : " (set on the spindle; TR recorded it)");
}

}  // namespace gantry::session
