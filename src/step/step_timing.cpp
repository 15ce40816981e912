// Pulse timing from the card's settings, in whole ticks.
#include "gantry/step/step_timing.hpp"

#include <algorithm>  // max
#include <cmath>      // ceil

#include "gantry/settings/settings.hpp"  // CardSettings

namespace gantry {

StepTiming StepTiming::from(const CardSettings& card) {
  StepTiming t;
  t.tick_s = 1.0 / card.pacer_hz();
  auto ticks = [&](double us) {
    return static_cast<std::int64_t>(std::ceil(us * 1e-6 / t.tick_s - 1e-9));
  };
  t.pulse_ticks = std::max<std::int64_t>(1, ticks(card.step_pulse_us));
  t.dir_setup_ticks = ticks(card.dir_setup_us);
  t.min_period_ticks = t.pulse_ticks + 1;
  return t;
}

}  // namespace gantry
