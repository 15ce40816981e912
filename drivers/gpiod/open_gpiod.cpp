// The factory of the libgpiod card: real lines, monotonic clock.
#include "gpiod/open_gpiod.hpp"

#include "gpiod/gpiod_card.hpp"
#include "gpiod/libgpiod_lines.hpp"

namespace gantry {

std::unique_ptr<Card> open_gpiod(const GpioMap& map, std::string* error) {
  std::unique_ptr<LibgpiodLines> lines = LibgpiodLines::open(map, error);
  if (!lines) return nullptr;
  return std::make_unique<GpiodCard>(map, std::move(lines));
}

}  // namespace gantry
