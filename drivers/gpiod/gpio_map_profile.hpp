// The parts of the GPIO line map that the machine profile already says: the pacer rate, the
// idle output word, and which input bits are the E-stop and the limit switches.
#pragma once

#include "gantry/settings/settings.hpp"
#include "gpiod/gpio_map.hpp"

namespace gantry {

// Sets map.pacer_hz, initial_word (the pins' idle word, so opening the card makes no step
// edge), estop_bits, limit_bits (min and max switches; home switches do not fault) and
// active_low_bits from `settings`. The chip path and line offsets stay the map's own.
void apply_profile(GpioMap& map, const Settings& settings);

}  // namespace gantry
