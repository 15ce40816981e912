// The libgpiod card as the CLI opens it for `[card] type = "gpiod"`.
#pragma once

#include <memory>
#include <string>

#include "gantry/hal/card.hpp"
#include "gpiod/gpio_map.hpp"

namespace gantry {

// Opens the chip, requests the map's lines and returns the card ready to start(); nullptr
// with every problem in `error` (one per line) when the map is invalid, the rate too high,
// the chip missing or not accessible, or a line taken. Each message names its fix.
std::unique_ptr<Card> open_gpiod(const GpioMap& map, std::string* error);

}  // namespace gantry
