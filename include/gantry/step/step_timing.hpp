// The vocabulary shared by step placement and the word writer: pulse timing in whole ticks,
// and one line change (a step or a direction level) at a tick.
#pragma once

#include <cstdint>

namespace gantry {

struct CardSettings;

// Pulse timing in whole ticks, each rounded up from the profile's microseconds.
struct StepTiming {
  double tick_s = 5e-6;
  std::int64_t pulse_ticks = 1;       // step line held active this long
  std::int64_t dir_setup_ticks = 1;   // direction stable this long before the active edge
  std::int64_t min_period_ticks = 2;  // pulse plus one idle tick: the fastest step rate

  static StepTiming from(const CardSettings& card);
};

// An axis's direction level changes (is_dir) or its step pulse starts, at `tick`.
struct StepEvent {
  std::int64_t tick;
  int axis;
  bool is_dir;
  bool positive;
  bool takeup = false;  // a step of backlash compensation: the motor turns, the load does not
};

}  // namespace gantry
