// What the simulated machine does besides playing pulses: its switches and its operator.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "gantry/core/axes.hpp"  // kAxisCount

namespace gantry {

// An input bit set to a level at a machine time (an operator's button, a sensor).
struct SimInputEvent {
  double at_s = 0;
  int bit = 0;
  bool high = true;
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
};

}  // namespace gantry
