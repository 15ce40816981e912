// What the simulated machine does besides playing pulses: its switches and its operator.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "gantry/core/vec6.hpp"          // Vec6, kAxisCount
#include "gantry/settings/settings.hpp"  // Settings, InputSettings

namespace gantry {

// An input bit set to a level at a machine time (an operator's button, a sensor).
struct SimInputEvent {
  double at_s = 0;
  int bit = 0;
  bool high = true;
};

// An input bit that reads `high` while an axis is at or beyond a position (at or above it for
// `above`, at or below it otherwise), and the other level elsewhere: a cam or a sensor on the
// table.
struct SimPositionInput {
  int bit = 0;
  bool high = true;
  int axis = 0;
  double at = 0;
  bool above = true;
};

struct SimWorld {
  // Limit switches: active once the axis is at or beyond the position (units), on the low
  // and on the high side.
  std::array<std::optional<double>, kAxisCount> min_switch{}, max_switch{};
  // Proximity (home) switches: active at or below the position, or at or above it for the
  // axes marked in home_above (a Z homing upwards).
  std::array<std::optional<double>, kAxisCount> home_switch{};
  std::array<bool, kAxisCount> home_above{};
  std::optional<double> probe_z;  // a surface: the probe input is active at or below this Z
  // A shaped part instead (digitizing, TC): the probe is active at or below its height at X, Y.
  std::function<double(double x, double y)> probe_surface;
  std::optional<double> estop_at_s;         // the operator presses E-stop at this machine time
  std::optional<double> stall_at_s;         // the producer stalls here: words still due underrun
  std::vector<SimInputEvent> input_events;  // in time order
  std::vector<SimPositionInput> position_inputs;

  // The level the switches at fixed places (home, limit, plate, position inputs) give input
  // `bit` with the tool at `at` (`bits`: the profile's wiring); nullopt when none drives it.
  std::optional<bool> level_at(int bit, const Vec6& at, const InputSettings& bits) const;
  // Whether anything here but a person brings input `bit` to `high` while the tool rests: an
  // input event at or after `from_s`, or (`at` given) the switches with the tool there.
  bool can_set(int bit, bool high, const InputSettings& bits, double from_s,
               const std::optional<Vec6>& at) const;
};

// The profile's simulated machine ([simulator]): its proximity switches, each on the side
// homing.<axis>.direction points to, and its Z zero plate.
SimWorld simulated_world(const Settings& s);

}  // namespace gantry
