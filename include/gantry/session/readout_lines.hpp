// Lines of the readout the console's status and the window both show: the state and the
// position, the spindle, the speeds and the feed override.
#pragma once

#include <string>
#include <string_view>
#include "gantry/core/vec6.hpp"           // Vec6
#include "gantry/machine/controller.hpp"  // ControllerStatus
#include "gantry/settings/settings.hpp"   // SpeedSettings, Units

namespace gantry::session {

// The state word the readout starts with: "step" (held after a step), "WARNING: about to
// move" (SW's warning), "pausing" (slowing to a hold), else the state's name.
std::string state_word(const ControllerStatus& s);
// The position readout: the state word, X Y Z A B C (`p`, working coordinates), the units.
// `names`: the axes' letters (axis_names: W for the profile's W axis).
std::string readout_text(std::string_view state, const Vec6& p, Units u,
                         std::string_view names = "XYZABC");
// "spindle on, 18000 RPM", "spindle off". `recorded_rpm`: TR's value when the profile wires
// no speed output (the card then carries none, and the RPM is only what TR recorded).
// The spindle: on or off (output switch 1, ShopBot's wiring) and its speed, as the card
// plays them.
std::string spindle_text(const ControllerStatus& s, double recorded_rpm);
// "move XY 2, Z 0.5  jog XY 6, Z 3 in/s; feed 100 %": VS's speeds and the live override.
std::string speeds_text(const SpeedSettings& v, Units u, double feed_override);

}  // namespace gantry::session
