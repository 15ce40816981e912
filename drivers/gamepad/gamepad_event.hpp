// A gamepad's buttons and sticks as the pendant bindings see them: one normalised event per
// change, named by the kernel's codes (linux/input-event-codes.h), whatever the device.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace gantry {

struct GamepadEvent {
  enum class Kind { Button, Axis, Lost };
  Kind kind = Kind::Button;
  int code = 0;      // BTN_* or ABS_* (Lost: 0)
  double value = 0;  // a button 0 or 1; an axis -1 to 1, 0 inside its dead zone
};

// A stick's raw range as the device reports it (EVIOCGABS): minimum, maximum and the flat
// band around the centre that reads as rest.
struct AxisRange {
  int minimum = -32768;
  int maximum = 32767;
  int flat = 0;
};

// A raw reading as -1..1. The band of `flat` around the centre (or 6 % of the half range,
// whichever is wider: worn sticks rest off centre and a jog must not creep) reads 0; outside
// it the value rises from 0 so a gentle push gives a slow jog rather than a jump.
double normalised_axis(int raw, const AxisRange& range);

// Profile names of codes: "BTN_SOUTH", "BTN_A", "ABS_X", "ABS_HAT0X" ... (the kernel's names).
std::optional<int> button_code(std::string_view name);
std::optional<int> axis_code(std::string_view name);
std::string code_name(GamepadEvent::Kind kind, int code);

}  // namespace gantry
