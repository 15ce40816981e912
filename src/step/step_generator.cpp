// Step placement on the tick clock and packing into pulse words.
#include "gantry/step/step_generator.hpp"

#include <algorithm>  // sort, max
#include <cmath>      // llround, ceil
#include <limits>     // numeric_limits

namespace gantry {

StepTiming StepTiming::from(const CardSettings& card) {
  StepTiming t;
  t.tick_s = 1.0 / card.pacer_hz();
  auto ticks = [&](double us) {
    return static_cast<std::int64_t>(std::ceil(us * 1e-6 / t.tick_s - 1e-9));
  };
  t.pulse_ticks = std::max<std::int64_t>(1, ticks(card.step_pulse_us));
  t.dir_setup_ticks = ticks(card.dir_setup_us);
  t.min_period_ticks = t.pulse_ticks + 1;
  return t;
}

StepGenerator::StepGenerator(const Settings& settings, Card& card, std::size_t block_words)
    : pins_(PinMap::from(settings.pins)),
      timing_(StepTiming::from(settings.card)),
      card_(card),
      block_words_(block_words) {
  for (int i = 0; i < kAxisCount; ++i) steps_per_unit_[i] = settings.axes[i].steps_per_unit;
  positive_.fill(true);
  last_step_.fill(std::numeric_limits<std::int64_t>::min() / 2);
  pulse_end_.fill(0);
  level_word_ = pins_.idle_word();
  block_.reserve(block_words_);
}

void StepGenerator::segment(const PlannedSegment& seg) {
  const Trapezoid& p = seg.profile;
  const std::int64_t t0 = segment_end_;
  std::int64_t end = t0 + std::llround((p.duration() + seg.dwell_s) / timing_.tick_s);
  events_.clear();
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t target = std::llround(seg.to[i] * steps_per_unit_[i]);
    const std::int64_t delta = target - position_[i];
    if (delta == 0) continue;
    const bool positive = delta > 0;
    const std::int64_t n = positive ? delta : -delta;
    std::int64_t last = last_step_[i];
    for (std::int64_t k = 1; k <= n; ++k) {
      const double s = (static_cast<double>(k) - 0.5) / static_cast<double>(n) * p.length;
      std::int64_t tick = t0 + std::llround(p.time_at(s) / timing_.tick_s);
      tick = std::max(tick, last + timing_.min_period_ticks);
      if (k == 1 && positive != positive_[i]) {
        // The new direction level goes out once the last pulse is over and no earlier than
        // words already sent; the step waits for the setup time after it.
        const std::int64_t dir_tick =
            std::max({cursor_, pulse_end_[i], tick - timing_.dir_setup_ticks});
        events_.push_back({dir_tick, i, true, positive});
        tick = std::max(tick, dir_tick + timing_.dir_setup_ticks);
      }
      events_.push_back({tick, i, false, positive});
      last = tick;
    }
    last_step_[i] = last;
    positive_[i] = positive;
    end = std::max(end, last);
  }
  std::stable_sort(events_.begin(), events_.end(),
                   [](const Event& a, const Event& b) { return a.tick < b.tick; });
  for (const Event& e : events_) {
    emit_until(e.tick);
    apply(e);
  }
  emit_until(end);
  segment_end_ = end;
}

void StepGenerator::flush() {
  std::int64_t end = segment_end_;
  for (std::int64_t pe : pulse_end_) end = std::max(end, pe);
  emit_until(end);
  // A pulse ending exactly here needs the idle word itself sent, or its line stays active.
  for (std::int64_t pe : pulse_end_)
    if (pe == cursor_ && cursor_ > 0) {
      emit_until(cursor_ + 1);
      break;
    }
  if (!block_.empty()) {
    card_.write(block_);
    block_.clear();
  }
}

void StepGenerator::apply(const Event& e) {
  const AxisPins& ap = pins_.axes[e.axis];
  if (e.is_dir) {
    level_word_ = (level_word_ & ~ap.dir_mask) | pins_.dir_bits(e.axis, e.positive);
    return;
  }
  pulse_end_[e.axis] = e.tick + timing_.pulse_ticks;
  position_[e.axis] += e.positive ? 1 : -1;
}

std::uint32_t StepGenerator::word_at(std::int64_t tick) const {
  std::uint32_t w = level_word_;
  for (int i = 0; i < kAxisCount; ++i)
    if (tick < pulse_end_[i]) w ^= pins_.axes[i].step_mask;  // active = not idle
  return w;
}

void StepGenerator::emit_until(std::int64_t tick) {
  while (cursor_ < tick) {
    // The word only changes where a pulse ends; emit up to the next such tick in one run.
    std::int64_t next = tick;
    for (std::int64_t pe : pulse_end_)
      if (pe > cursor_ && pe < next) next = pe;
    write_run(word_at(cursor_), next - cursor_);
    cursor_ = next;
  }
}

void StepGenerator::write_run(std::uint32_t word, std::int64_t count) {
  while (count > 0) {
    const auto room = static_cast<std::int64_t>(block_words_ - block_.size());
    const std::int64_t n = std::min(room, count);
    block_.insert(block_.end(), static_cast<std::size_t>(n), word);
    count -= n;
    if (block_.size() == block_words_) {
      card_.write(block_);
      block_.clear();
    }
  }
}

}  // namespace gantry
