// The profile's pacer, idle word and fault inputs, carried into the GPIO line map.
#include "gpiod/gpio_map_profile.hpp"

#include "gantry/hal/pin_map.hpp"

namespace gantry {
namespace {

std::uint32_t bit_mask(int bit) {
  return bit >= 0 && bit < 32 ? 1u << bit : 0;  // -1: not wired
}

}  // namespace

void apply_profile(GpioMap& map, const Settings& settings) {
  map.pacer_hz = settings.card.pacer_hz();
  map.initial_word = PinMap::from(settings.pins).idle_word();
  const InputSettings& in = settings.inputs;
  map.estop_bits = bit_mask(in.estop_bit);
  map.limit_bits = 0;
  for (int axis = 0; axis < kAxisCount; ++axis)
    map.limit_bits |= bit_mask(in.min_bit[axis]) | bit_mask(in.max_bit[axis]);
  map.active_low_bits =
      (in.estop_active_low ? map.estop_bits : 0) | (in.limits_active_low ? map.limit_bits : 0);
}

}  // namespace gantry
