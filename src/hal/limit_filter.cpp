// The limit rule every card applies, and the cushioned stop's words (limit_filter.hpp).
#include "gantry/hal/limit_filter.hpp"

#include <algorithm>  // max, min
#include <bit>        // countr_zero
#include <cmath>      // llround, sqrt, floor
#include <utility>    // pair

#include "gantry/settings/settings.hpp"

namespace gantry {
LimitFilter::LimitFilter(const Settings& s, double pacer_hz)
    : travel_only_(s.limits.travel_only),
      window_(std::llround(kTravelS * pacer_hz)),
      pins_(PinMap::from(s.pins)),
      min_bit_(s.inputs.min_bit),
      max_bit_(s.inputs.max_bit),
      count_(s.limits.debounce) {
  for (const AxisPins& a : pins_.axes) step_bits_ |= a.steps;
}

void LimitFilter::note_word(std::uint64_t tick, std::uint32_t before, std::uint32_t word) {
  const std::uint32_t diff = word ^ before;
  if ((diff & step_bits_) == 0) return;  // the charge pump, an output: no step
  for (int k = 0; k < kAxisCount; ++k) {
    const AxisPins& p = pins_.axes[k];
    if ((diff & p.step_mask) == 0) continue;
    const bool active = ((word & p.step_mask) != 0) != p.step_active_low;
    if (active) note_step(k, tick, pins_.positive(k, word));
  }
}

// A channel's min (max) switch counts while it has stepped towards minus (plus) within the
// window (or steps written ahead of the sample); an input of no channel always counts.
bool LimitFilter::travelling_to(std::uint32_t fresh, std::uint64_t tick) const {
  std::uint32_t owned = 0;
  const auto now = static_cast<std::int64_t>(tick);
  for (int k = 0; k < kAxisCount; ++k) {
    const bool moving = now - last_step_[k] <= window_;
    for (const auto& [bit, plus] : {std::pair{min_bit_[k], false}, std::pair{max_bit_[k], true}}) {
      if (bit < 0 || bit > 31) continue;
      owned |= 1u << bit;
      if ((fresh >> bit & 1u) && moving && last_positive_[k] == plus) return true;
    }
  }
  return (fresh & ~owned) != 0;
}

bool LimitFilter::sample(const InputTrip& limits, std::uint64_t tick, std::uint32_t before,
                         std::uint32_t bits, std::uint64_t repeat) {
  const std::uint32_t active = limits.active(bits);
  std::uint32_t fresh = active & ~limits.active(before) & ~(count_.pending() & active);
  if (fresh != 0 && travel_only_ && !travelling_to(fresh, tick)) fresh = 0;
  return count_.sample(active, fresh, repeat);
}

ChannelMotion motion_from_steps(std::int64_t prev, std::int64_t last, bool positive,
                                std::int64_t now, double tick_s) {
  const std::int64_t interval = last - prev;
  const auto window = static_cast<std::int64_t>(LimitFilter::kTravelS / tick_s);
  if (interval <= 0 || now - last > 2 * interval || now - last > window) return {0, positive};
  return {1.0 / static_cast<double>(interval), positive};
}

std::vector<std::uint32_t> cushion_words(const PinMap& pins, std::uint32_t word,
                                         const std::array<ChannelMotion, kAxisCount>& motion,
                                         const std::array<std::int64_t, kAxisCount>& since_step,
                                         int steps, int pulse_ticks) {
  // Each channel's position at the first cushion word, in steps past the half step its last
  // step crossed (the step generator places a step where the position crosses k - 1/2).
  std::array<double, kAxisCount> phase{};
  int fast = -1;
  for (int k = 0; k < kAxisCount; ++k) {
    phase[k] = std::min(0.999, motion[k].rate * static_cast<double>(since_step[k]));
    if (motion[k].rate > 0 && (fast < 0 || motion[k].rate > motion[fast].rate)) fast = k;
  }
  if (fast < 0 || steps <= 0) return {};
  const double fastest = motion[fast].rate;
  // Decelerating linearly over T ticks a channel covers rate T / 2: the fastest's step
  // `steps` falls within it and its step `steps` + 1 does not.
  const double T = 2.0 * (steps - phase[fast] + 0.5) / fastest;
  const std::int64_t p = std::max(1, pulse_ticks);
  std::array<std::vector<std::int64_t>, kAxisCount> at;  // each channel's step ticks
  std::array<std::int64_t, kAxisCount> pulse_left{};
  std::int64_t length = 0;
  for (int k = 0; k < kAxisCount; ++k) {
    pulse_left[k] = std::max<std::int64_t>(0, p - since_step[k]);
    length = std::max(length, pulse_left[k]);
    const double r = motion[k].rate;
    if (r <= 0) continue;
    const double reach = r * T / 2;  // this channel's distance, steps
    const auto n = static_cast<int>(std::floor(reach + phase[k] + 1e-9));
    std::int64_t earliest = std::max<std::int64_t>(0, p + 1 - since_step[k]);
    for (int j = 1; j <= n; ++j) {
      const double left = T * T - 2.0 * T * (j - phase[k]) / r;
      const double t = T - std::sqrt(std::max(0.0, left));
      const std::int64_t tick = std::max<std::int64_t>(earliest, std::llround(t));
      at[k].push_back(tick);
      earliest = tick + p + 1;
      length = std::max(length, tick + p);
    }
  }
  // Every step line idle, then each pulse flips its channel's lines active.
  std::uint32_t all_steps = 0, idle_high = 0;
  for (const AxisPins& a : pins.axes) {
    all_steps |= a.steps;
    idle_high |= a.steps_idle_high;
  }
  const std::uint32_t base = (word & ~all_steps) | idle_high;
  std::vector<std::uint32_t> out(static_cast<std::size_t>(length + 1), base);
  for (int k = 0; k < kAxisCount; ++k) {
    for (std::int64_t i = 0; i < pulse_left[k]; ++i)
      out[static_cast<std::size_t>(i)] ^= pins.axes[k].steps;
    for (std::int64_t tick : at[k])
      for (std::int64_t i = tick; i < tick + p; ++i)
        out[static_cast<std::size_t>(i)] ^= pins.axes[k].steps;
  }
  return out;
}

}  // namespace gantry
