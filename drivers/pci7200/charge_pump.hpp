// The watchdog (charge-pump) output: one bit of the output word toggled at a fixed rate while
// words play, so that an external charge-pump circuit enables the drives only while the card
// is really playing. When output stops for any reason (fault, stop, a crashed process) the
// bit freezes and the charge pump drops the drives.
#pragma once

#include <cstdint>
#include <span>

namespace gantry::pci7200 {

class ChargePump {
 public:
  ChargePump() = default;  // disabled: words pass unchanged
  // `bit` in 0..31; the bit is high for `half_period_ticks` ticks, then low as long.
  ChargePump(int bit, std::uint32_t half_period_ticks)
      : mask_(1u << bit), half_period_(half_period_ticks < 1 ? 1 : half_period_ticks) {}

  bool enabled() const { return mask_ != 0; }
  std::uint32_t mask() const { return mask_; }
  std::uint32_t half_period_ticks() const { return half_period_; }

  // Sets the bit in words at stream positions first_tick, first_tick + 1, ...: the level is a
  // function of the position, so the waveform is exact however the words are batched.
  void stamp(std::span<std::uint32_t> words, std::uint64_t first_tick) const {
    if (mask_ == 0) return;
    std::uint64_t tick = first_tick;
    for (std::uint32_t& w : words) {
      const bool high = ((tick++ / half_period_) & 1) == 0;
      w = high ? (w | mask_) : (w & ~mask_);
    }
  }

  // The word to rest at: the bit low and still.
  std::uint32_t idle(std::uint32_t word) const { return word & ~mask_; }

 private:
  std::uint32_t mask_ = 0;
  std::uint32_t half_period_ = 1;
};

}  // namespace gantry::pci7200
