// Pin map construction from the profile's [pins] tables.
#include "gantry/hal/pin_map.hpp"

namespace gantry {

PinMap PinMap::from(const std::array<PinSettings, kAxisCount>& pins) {
  PinMap m;
  for (int i = 0; i < kAxisCount; ++i) {
    m.axes[i].step_mask = 1u << pins[i].step_bit;
    m.axes[i].dir_mask = 1u << pins[i].dir_bit;
    m.axes[i].invert_dir = pins[i].invert_dir;
    m.axes[i].step_active_low = pins[i].step_active_low;
  }
  return m;
}

std::uint32_t PinMap::idle_word() const {
  std::uint32_t w = 0;
  for (int i = 0; i < kAxisCount; ++i) {
    if (axes[i].step_active_low) w |= axes[i].step_mask;
    w |= dir_bits(i, true);
  }
  return w;
}

}  // namespace gantry
