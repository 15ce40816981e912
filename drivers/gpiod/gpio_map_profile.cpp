// The profile's pacer, idle word and fault inputs, carried into the GPIO line map.
#include "gpiod/gpio_map_profile.hpp"

#include "gantry/hal/input_roles.hpp"
#include "gantry/hal/pin_map.hpp"

namespace gantry {
void apply_profile(GpioMap& map, const Settings& settings) {
  map.pacer_hz = settings.card.pacer_hz();
  map.initial_word = PinMap::from(settings.pins).idle_word();
  const InputRoles roles = input_roles(settings);
  map.estop_bits = roles.estop.mask;
  map.limit_bits = roles.limits.mask;
  map.active_low_bits = (roles.estop.mask & ~roles.estop.active_high) |
                        (roles.limits.mask & ~roles.limits.active_high);
}

}  // namespace gantry
