// Pin map construction from the profile's [pins] tables.
#include "gantry/hal/pin_map.hpp"

namespace gantry {

PinMap PinMap::from(const std::array<PinSettings, kAxisCount>& pins,
                    const std::array<int, kAxisCount>& channel_axis) {
  PinMap m;
  for (int k = 0; k < kAxisCount; ++k) {
    AxisPins& a = m.axes[channel_axis[k]];
    const std::uint32_t step = 1u << pins[k].step_bit, dir = 1u << pins[k].dir_bit;
    if (a.steps == 0) {  // the axis's first channel
      a.step_mask = step;
      a.dir_mask = dir;
      a.invert_dir = pins[k].invert_dir;
      a.step_active_low = pins[k].step_active_low;
    }
    a.steps |= step;
    a.dirs |= dir;
    if (pins[k].invert_dir) a.dirs_high_positive |= dir;
    if (pins[k].step_active_low) a.steps_idle_high |= step;
  }
  return m;
}

std::uint32_t PinMap::idle_word() const {
  std::uint32_t w = 0;
  for (int i = 0; i < kAxisCount; ++i) {
    w |= axes[i].steps_idle_high;
    w |= dir_bits(i, true);
  }
  return w;
}

}  // namespace gantry
