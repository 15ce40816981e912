// Where each axis's step and direction signals sit in the card's 32-bit output word.
#pragma once

#include <array>
#include <cstdint>

#include "gantry/core/axes.hpp"          // kAxisCount
#include "gantry/settings/settings.hpp"  // PinSettings

namespace gantry {

// An axis's channel: its step and direction bits (the first channel naming the axis, which
// decoders read), and every channel driving it, which the words drive alike (a slaved axis
// has two, each with its own direction invert and step polarity).
struct AxisPins {
  std::uint32_t step_mask = 0;
  std::uint32_t dir_mask = 0;
  bool invert_dir = false;       // default: dir line low = positive travel; inverted: high
  bool step_active_low = false;  // idle high, pulse low
  std::uint32_t steps = 0, dirs = 0;     // every channel's step and direction bits
  std::uint32_t dirs_high_positive = 0;  // the direction bits high for positive travel
  std::uint32_t steps_idle_high = 0;     // the step bits of active-low channels
};

struct PinMap {
  std::array<AxisPins, kAxisCount> axes{};

  // Axis channel_axis[k] is driven through channel k's pins (VI); default: channel k = axis k.
  // Two channels naming one axis drive it together (a slaved axis); an axis no channel
  // names drives no pins.
  static PinMap from(const std::array<PinSettings, kAxisCount>& pins,
                     const std::array<int, kAxisCount>& channel_axis = {0, 1, 2, 3, 4, 5});

  // The word with every step line idle and every direction line showing positive travel.
  std::uint32_t idle_word() const;
  // The direction bit's level (as a mask contribution) for travel in `positive` direction.
  std::uint32_t dir_bits(int axis, bool positive) const {
    const AxisPins& p = axes[axis];
    return positive ? p.dirs_high_positive : p.dirs & ~p.dirs_high_positive;
  }
  // The travel direction a word's direction bit shows: the inverse of dir_bits.
  bool positive(int axis, std::uint32_t word) const {
    const AxisPins& p = axes[axis];
    return ((word & p.dir_mask) != 0) == p.invert_dir;
  }
};

}  // namespace gantry
