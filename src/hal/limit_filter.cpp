// The limit rule every card applies, and the cushioned stop's words (limit_filter.hpp).
#include "gantry/hal/limit_filter.hpp"

#include <algorithm>  // max, min
#include <bit>        // bit_ceil, countr_zero
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
  // A step interval longer than the window is rest too (a channel's one step after a long
  // pause, or its first).
  if (interval <= 0 || interval > window || now - last > 2 * interval || now - last > window)
    return {0, positive};
  return {1.0 / static_cast<double>(interval), positive};
}

CushionStream::CushionStream(const PinMap& pins, std::uint32_t word,
                             const std::array<ChannelMotion, kAxisCount>& motion,
                             const std::array<std::int64_t, kAxisCount>& since_step, int steps,
                             int pulse_ticks)
    : pulse_(std::max(1, pulse_ticks)) {
  // Every step line idle; each pulse flips its channel's lines active.
  std::uint32_t all_steps = 0, idle_high = 0;
  for (const AxisPins& a : pins.axes) {
    all_steps |= a.steps;
    idle_high |= a.steps_idle_high;
  }
  base_ = (word & ~all_steps) | idle_high;
  // Each channel's position at the first cushion word, in steps past the half step its last
  // step crossed (the step generator places a step where the position crosses k - 1/2).
  int fast = -1;
  for (int k = 0; k < kAxisCount; ++k) {
    step_bits_[k] = pins.axes[k].steps;
    positive_[k] = pins.positive(k, word);
    rate_[k] = motion[k].rate;
    phase_[k] = std::min(0.999, motion[k].rate * static_cast<double>(since_step[k]));
    if (motion[k].rate > 0 && (fast < 0 || motion[k].rate > motion[fast].rate)) fast = k;
    active_until_[k] = std::max<std::int64_t>(0, pulse_ - since_step[k]);
    next_start_[k] = kNever;
  }
  if (fast < 0 || steps <= 0) return;  // nothing moves: nothing to play
  none_ = false;
  // Decelerating linearly over T ticks a channel covers rate T / 2: the fastest's step
  // `steps` falls within it and its step `steps` + 1 does not.
  T_ = 2.0 * (steps - phase_[fast] + 0.5) / rate_[fast];
  for (int k = 0; k < kAxisCount; ++k) {
    if (rate_[k] <= 0) continue;
    const double reach = rate_[k] * T_ / 2;  // this channel's distance, steps
    count_[k] = static_cast<int>(std::floor(reach + phase_[k] + 1e-9));
    if (count_[k] > 0)
      next_start_[k] = step_tick(k, 1, std::max<std::int64_t>(0, pulse_ + 1 - since_step[k]));
  }
}

std::int64_t CushionStream::step_tick(int k, int j, std::int64_t earliest) const {
  const double left = T_ * T_ - 2.0 * T_ * (j - phase_[k]) / rate_[k];
  const double t = T_ - std::sqrt(std::max(0.0, left));
  return std::max<std::int64_t>(earliest, std::llround(t));
}

// Done once the word after every pulse's end (all step lines idle) has been given.
bool CushionStream::done() const {
  if (none_) return true;
  std::int64_t last = 0;
  for (int k = 0; k < kAxisCount; ++k) {
    if (next_start_[k] != kNever) return false;
    last = std::max(last, active_until_[k]);
  }
  return given_ > last;
}

std::uint32_t CushionStream::next() {
  std::uint32_t w = base_;
  for (int k = 0; k < kAxisCount; ++k) {
    if (given_ == next_start_[k]) {  // a step begins
      active_until_[k] = given_ + pulse_;
      ++begun_[k];
      next_start_[k] =
          begun_[k] < count_[k] ? step_tick(k, begun_[k] + 1, given_ + pulse_ + 1) : kNever;
    }
    if (given_ < active_until_[k]) w ^= step_bits_[k];
  }
  ++given_;
  return w;
}

std::uint64_t CushionStream::alike_ahead() const {
  std::int64_t change = kNever, last = 0;
  for (int k = 0; k < kAxisCount; ++k) {
    last = std::max(last, active_until_[k]);
    if (given_ == next_start_[k])
      change = std::min(change, given_ + pulse_);  // the pulse that begins here ends
    else if (given_ < active_until_[k])
      change = std::min(change, active_until_[k]);
    else
      change = std::min(change, next_start_[k]);
  }
  if (change == kNever) change = last + 1;  // idle to the end
  return static_cast<std::uint64_t>(std::max<std::int64_t>(0, change - given_));
}

Steps6 CushionStream::steps() const {
  Steps6 out{};
  for (int k = 0; k < kAxisCount; ++k) out[k] = positive_[k] ? begun_[k] : -begun_[k];
  return out;
}

Steps6 CushionStream::steps_in(std::uint64_t words) const {
  CushionStream s = *this;
  while (static_cast<std::int64_t>(words) > s.given_ && !s.done()) s.next();
  return s.steps();
}

std::vector<std::uint32_t> cushion_words(const PinMap& pins, std::uint32_t word,
                                         const std::array<ChannelMotion, kAxisCount>& motion,
                                         const std::array<std::int64_t, kAxisCount>& since_step,
                                         int steps, int pulse_ticks) {
  CushionStream s(pins, word, motion, since_step, steps, pulse_ticks);
  std::vector<std::uint32_t> out;
  while (!s.done()) out.push_back(s.next());
  return out;
}

CushionRule::CushionRule(const Settings& s)
    : pins(PinMap::from(s.pins)),
      limit_steps(s.limits.cushion_steps),
      pulse_ticks(std::max(
          1, static_cast<int>(std::ceil(s.card.step_pulse_us * 1e-6 * s.card.pacer_hz() - 1e-9)))) {
}

StepTrail::StepTrail(const PinMap& pins, std::size_t depth, std::uint32_t ignore)
    : pins_(pins), ignore_(ignore) {
  for (const AxisPins& a : pins_.axes) step_bits_ |= a.step_mask;
  auto make = [](Ring& r, std::size_t n, bool words) {
    n = std::bit_ceil(std::max<std::size_t>(n, 2));
    r.at.assign(n, 0);
    if (words) r.word.assign(n, 0);
    r.mask = n - 1;
  };
  for (Ring& r : steps_) make(r, depth, false);
  make(levels_, 2 * depth, true);
}

void StepTrail::reset(std::uint32_t word) {
  for (Ring& r : steps_) r.count = 0;
  if (levels_.at.empty()) return;
  levels_.at[0] = 0;
  levels_.word[0] = word & ~step_bits_;
  levels_.count = 1;
}

void StepTrail::note_word(std::uint64_t tick, std::uint32_t before, std::uint32_t word) {
  const std::uint32_t diff = word ^ before;
  if (diff & step_bits_)
    for (int k = 0; k < kAxisCount; ++k) {
      const AxisPins& p = pins_.axes[k];
      Ring& r = steps_[k];
      if ((diff & p.step_mask) == 0 || r.at.empty()) continue;
      if (((word & p.step_mask) != 0) == p.step_active_low) continue;  // a pulse's end
      r.at[r.count++ & r.mask] = tick << 1 | (pins_.positive(k, word) ? 1u : 0u);
    }
  if ((diff & ~step_bits_ & ~ignore_) && !levels_.at.empty()) {
    const std::uint64_t i = levels_.count++ & levels_.mask;
    levels_.at[i] = tick;
    levels_.word[i] = word & ~step_bits_;
  }
}

std::uint32_t StepTrail::word_before(std::uint64_t now) const {
  const Ring& r = levels_;
  const std::uint64_t kept = std::min<std::uint64_t>(r.count, r.mask + 1);
  std::uint32_t w = pins_.idle_word() & ~step_bits_;
  for (std::uint64_t i = 0; i < kept; ++i) {  // newest first
    const std::uint64_t at = (r.count - 1 - i) & r.mask;
    w = r.word[at];
    if (r.at[at] < now) break;
  }
  std::uint32_t idle_high = 0;
  for (const AxisPins& a : pins_.axes) idle_high |= a.steps_idle_high & a.step_mask;
  return w | idle_high;
}

void StepTrail::motion_at(std::uint64_t now, double tick_s,
                          std::array<ChannelMotion, kAxisCount>& motion,
                          std::array<std::int64_t, kAxisCount>& since_step) const {
  constexpr std::int64_t kLongAgo = std::numeric_limits<std::int64_t>::min() / 2;
  const auto t = static_cast<std::int64_t>(now);
  for (int k = 0; k < kAxisCount; ++k) {
    const Ring& r = steps_[k];
    const std::uint64_t kept = std::min<std::uint64_t>(r.count, r.mask + 1);
    std::array<std::int64_t, 2> step{kLongAgo, kLongAgo};  // the last, the one before
    bool positive = true;
    int found = 0;
    for (std::uint64_t i = 0; i < kept && found < 2; ++i) {  // newest first
      const std::uint64_t e = r.at[(r.count - 1 - i) & r.mask];
      const auto at = static_cast<std::int64_t>(e >> 1);
      if (at >= t) continue;  // noted ahead of the cut: never played
      if (found == 0) positive = (e & 1u) != 0;
      step[static_cast<std::size_t>(found++)] = at;
    }
    motion[k] = motion_from_steps(step[1], step[0], positive, t - 1, tick_s);
    since_step[k] = std::min<std::int64_t>(t - step[0], 1 << 30);
  }
}

}  // namespace gantry
