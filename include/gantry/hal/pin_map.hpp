// Where each axis's step and direction signals sit in the card's 32-bit output word.
#pragma once

#include <array>
#include <cstdint>

#include "gantry/core/axes.hpp"          // kAxisCount
#include "gantry/settings/settings.hpp"  // PinSettings

namespace gantry {

struct AxisPins {
  std::uint32_t step_mask = 0;
  std::uint32_t dir_mask = 0;
  bool invert_dir = false;       // default: dir line low = positive travel; inverted: high
  bool step_active_low = false;  // idle high, pulse low
};

struct PinMap {
  std::array<AxisPins, kAxisCount> axes{};

  // Axis channel_axis[k] is driven through channel k's pins (VI); default: channel k = axis k.
  static PinMap from(const std::array<PinSettings, kAxisCount>& pins,
                     const std::array<int, kAxisCount>& channel_axis = {0, 1, 2, 3, 4, 5});

  // The word with every step line idle and every direction line showing positive travel.
  std::uint32_t idle_word() const;
  // The direction bit's level (as a mask contribution) for travel in `positive` direction.
  std::uint32_t dir_bits(int axis, bool positive) const {
    const AxisPins& p = axes[axis];
    return (positive == p.invert_dir) ? p.dir_mask : 0;
  }
  // The travel direction a word's direction bit shows: the inverse of dir_bits.
  bool positive(int axis, std::uint32_t word) const {
    const AxisPins& p = axes[axis];
    return ((word & p.dir_mask) != 0) == p.invert_dir;
  }
};

}  // namespace gantry
