// Pin map construction from the profile's [pins] tables.
#include "gantry/hal/pin_map.hpp"

namespace gantry {

PinMap PinMap::from(const std::array<PinSettings, kAxisCount>& pins,
                    const std::array<int, kAxisCount>& channel_axis) {
  PinMap m;
  for (int k = 0; k < kAxisCount; ++k) {
    AxisPins& a = m.axes[channel_axis[k]];
    a.step_mask = 1u << pins[k].step_bit;
    a.dir_mask = 1u << pins[k].dir_bit;
    a.invert_dir = pins[k].invert_dir;
    a.step_active_low = pins[k].step_active_low;
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
