// The spindle as the front ends show it: on or off (output switch 1, ShopBot's wiring) and
// its speed, as the card plays them.
#pragma once

#include <string>

#include "gantry/machine/controller.hpp"  // ControllerStatus

namespace gantry::session {

// "spindle on, 18000 RPM", "spindle off". `recorded_rpm`: TR's value when the profile wires
// no speed output (the card then carries none, and the RPM is only what TR recorded).
std::string spindle_text(const ControllerStatus& s, double recorded_rpm);

}  // namespace gantry::session
