// The profile's pacer, idle word and fault inputs, carried into the GPIO line map.
#include "gpiod/gpio_map_profile.hpp"

#include <algorithm>  // clamp
#include <cmath>      // llround

#include "gantry/hal/input_roles.hpp"
#include "gantry/hal/pin_map.hpp"

namespace gantry {
void apply_profile(GpioMap& map, const Settings& settings) {
  map.pacer_hz = settings.card.pacer_hz();
  // The step generator keeps at most card.lead_ms queued (docs/controller.md): a stream
  // starts with half of it, so the lead (never below this plus one block) can fill it.
  map.start_words = std::clamp<std::size_t>(
      static_cast<std::size_t>(std::llround(settings.card.lead_ms * 1e-3 * map.pacer_hz / 2)), 1,
      map.queue_words);
  map.initial_word = PinMap::from(settings.pins).idle_word();
  const InputRoles roles = input_roles(settings);
  map.estop_bits = roles.estop.mask;
  map.limit_bits = roles.limits.mask;
  map.active_low_bits = (roles.estop.mask & ~roles.estop.active_high) |
                        (roles.limits.mask & ~roles.limits.active_high);
  map.limit_rule = LimitFilter(settings, map.pacer_hz);
  map.cushion = CushionRule(settings);
}

}  // namespace gantry
