// Gamepad readings normalised, and the kernel's code names for the profile.
#include "gamepad/gamepad_event.hpp"

#include <linux/input-event-codes.h>

#include <algorithm>
#include <array>
#include <charconv>  // from_chars
#include <span>
#include <cmath>
#include <utility>

namespace gantry {

double normalised_axis(int raw, const AxisRange& range) {
  const double half = (static_cast<double>(range.maximum) - range.minimum) / 2;
  if (half <= 0) return 0;
  const double centre = (static_cast<double>(range.maximum) + range.minimum) / 2;
  const double x = std::clamp((raw - centre) / half, -1.0, 1.0);
  const double dead = std::clamp(range.flat / half, 0.06, 0.9);
  if (std::abs(x) <= dead) return 0;
  return std::copysign((std::abs(x) - dead) / (1 - dead), x);
}

namespace {

#define GANTRY_CODE(c) std::pair<std::string_view, int>{#c, c}
// BTN_A..BTN_Y are the same codes as BTN_SOUTH..BTN_WEST; both spellings are accepted and the
// first one found is the name shown.
constexpr std::array kButtons{
    GANTRY_CODE(BTN_SOUTH),     GANTRY_CODE(BTN_EAST),       GANTRY_CODE(BTN_NORTH),
    GANTRY_CODE(BTN_WEST),      GANTRY_CODE(BTN_A),          GANTRY_CODE(BTN_B),
    GANTRY_CODE(BTN_X),         GANTRY_CODE(BTN_Y),          GANTRY_CODE(BTN_C),
    GANTRY_CODE(BTN_Z),         GANTRY_CODE(BTN_TL),         GANTRY_CODE(BTN_TR),
    GANTRY_CODE(BTN_TL2),       GANTRY_CODE(BTN_TR2),        GANTRY_CODE(BTN_SELECT),
    GANTRY_CODE(BTN_START),     GANTRY_CODE(BTN_MODE),       GANTRY_CODE(BTN_THUMBL),
    GANTRY_CODE(BTN_THUMBR),    GANTRY_CODE(BTN_TRIGGER),    GANTRY_CODE(BTN_THUMB),
    GANTRY_CODE(BTN_THUMB2),    GANTRY_CODE(BTN_TOP),        GANTRY_CODE(BTN_TOP2),
    GANTRY_CODE(BTN_PINKIE),    GANTRY_CODE(BTN_BASE),       GANTRY_CODE(BTN_BASE2),
    GANTRY_CODE(BTN_BASE3),     GANTRY_CODE(BTN_BASE4),      GANTRY_CODE(BTN_BASE5),
    GANTRY_CODE(BTN_BASE6),     GANTRY_CODE(BTN_DPAD_UP),    GANTRY_CODE(BTN_DPAD_DOWN),
    GANTRY_CODE(BTN_DPAD_LEFT), GANTRY_CODE(BTN_DPAD_RIGHT),
};
constexpr std::array kAxes{
    GANTRY_CODE(ABS_X),        GANTRY_CODE(ABS_Y),      GANTRY_CODE(ABS_Z),
    GANTRY_CODE(ABS_RX),       GANTRY_CODE(ABS_RY),     GANTRY_CODE(ABS_RZ),
    GANTRY_CODE(ABS_THROTTLE), GANTRY_CODE(ABS_RUDDER), GANTRY_CODE(ABS_WHEEL),
    GANTRY_CODE(ABS_GAS),      GANTRY_CODE(ABS_BRAKE),  GANTRY_CODE(ABS_HAT0X),
    GANTRY_CODE(ABS_HAT0Y),    GANTRY_CODE(ABS_HAT1X),  GANTRY_CODE(ABS_HAT1Y),
};
#undef GANTRY_CODE

// A name from the table, or the prefix and a number for a code without one ("BTN_300",
// as code_name shows it).
template <size_t N>
std::optional<int> find_code(const std::array<std::pair<std::string_view, int>, N>& table,
                             std::string_view prefix, std::string_view name) {
  for (const auto& [n, c] : table)
    if (n == name) return c;
  if (!name.starts_with(prefix)) return std::nullopt;
  int code = 0;
  const auto digits = name.substr(prefix.size());
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), code);
  if (ec != std::errc{} || end != digits.data() + digits.size() || code < 0 || code > KEY_MAX)
    return std::nullopt;
  return code;
}

}  // namespace

std::optional<int> button_code(std::string_view name) {
  return find_code(kButtons, "BTN_", name);
}
std::optional<int> axis_code(std::string_view name) {
  const auto c = find_code(kAxes, "ABS_", name);
  return c && *c <= ABS_MAX ? c : std::nullopt;
}

std::string code_name(GamepadEvent::Kind kind, int code) {
  if (kind == GamepadEvent::Kind::Lost) return "lost";
  for (const auto& [n, c] : kind == GamepadEvent::Kind::Axis
                                ? std::span<const std::pair<std::string_view, int>>(kAxes)
                                : std::span<const std::pair<std::string_view, int>>(kButtons))
    if (c == code) return std::string(n);
  return (kind == GamepadEvent::Kind::Axis ? "ABS_" : "BTN_") + std::to_string(code);
}

}  // namespace gantry
