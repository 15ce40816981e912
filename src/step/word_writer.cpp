// Packing step events into pulse words and blocks for the card.
#include "gantry/step/word_writer.hpp"

#include <algorithm>  // max, min, clamp
#include <cmath>      // llround

#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

WordWriter::WordWriter(const Settings& settings, const StepTiming& timing, Card& card,
                       std::size_t block_words)
    : pins_(PinMap::from(settings.pins, settings.drivers.channel_axis)),
      timing_(timing),
      card_(card),
      block_words_(block_words),
      block_(block_words),
      roles_(input_roles(settings)) {  // the card has them from the same profile
  pulse_end_.fill(0);
  level_word_ = pins_.idle_word();
  if (settings.outputs.charge_pump_bit >= 0) {
    pump_mask_ = 1u << settings.outputs.charge_pump_bit;
    pump_half_ticks_ = std::max<std::int64_t>(
        1, std::llround(settings.card.pacer_hz() / (2 * settings.outputs.charge_pump_hz)));
  }
  if (settings.outputs.spindle_bit >= 0) spindle_mask_ = 1u << settings.outputs.spindle_bit;
  if (settings.spindle.pwm_bit >= 0) {
    pwm_mask_ = 1u << settings.spindle.pwm_bit;
    pwm_period_ticks_ =
        std::max<std::int64_t>(1, std::llround(settings.card.pacer_hz() / settings.spindle.pwm_hz));
    max_rpm_ = settings.spindle.max_rpm;
    if (settings.spindle.speed_mode == SpindleSettings::SpeedMode::Frequency) {
      frequency_ticks_hz_ = settings.card.pacer_hz() / settings.spindle.max_hz;
      pwm_period_ticks_ = 2;
    }
  }
  if (!settings.spindle.dac_bits.empty()) {
    max_rpm_ = settings.spindle.max_rpm;
    for (int b : settings.spindle.dac_bits) {
      dac_masks_.push_back(1u << b);
      dac_all_ |= 1u << b;
    }
  }
  aux_bits_ = settings.outputs.aux_bits;
  for (int k = 0; k < kAxisCount; ++k) channel_steps_[k] = 1u << settings.pins[k].step_bit;
}

void WordWriter::rest_channels(unsigned channels) {
  resting_steps_ = 0;
  for (int k = 0; k < kAxisCount; ++k)
    if (channels >> k & 1u) resting_steps_ |= channel_steps_[k];
}

// At rest: the channel pins change, the levels of the lines that stay are kept.
void WordWriter::settings_changed(const Settings& s,
                                  const std::array<bool, kAxisCount>& positive) {
  std::uint32_t old_lines = 0;
  for (const AxisPins& a : pins_.axes) old_lines |= a.steps | a.dirs;
  pins_ = PinMap::from(s.pins, s.drivers.channel_axis);
  for (int k = 0; k < kAxisCount; ++k) channel_steps_[k] = 1u << s.pins[k].step_bit;
  card_.calibration_changed(s);
  roles_ = input_roles(s);
  set_card_trips();
  level_word_ &= ~old_lines;
  for (int i = 0; i < kAxisCount; ++i) {
    level_word_ |= pins_.axes[i].steps_idle_high;
    level_word_ |= pins_.dir_bits(i, positive[i]);
  }
}

void WordWriter::set_card_trips() {
  card_.set_trips(roles_.estop, roles_.limits.without(watch_mask_));
}

void WordWriter::watch(const InputWatch& w) {
  watch_mask_ = w.mask;
  set_card_trips();
  card_.watch(w);
}

void WordWriter::set_spindle(bool on) {
  level_word_ = on ? level_word_ | spindle_mask_ : level_word_ & ~spindle_mask_;
}

void WordWriter::set_spindle_speed(double rpm) {
  const double duty = std::clamp(rpm / max_rpm_, 0.0, 1.0);
  if (!dac_masks_.empty()) {  // a D/A converter's word: the levels, as outputs stand
    const double top = static_cast<double>((std::uint64_t{1} << dac_masks_.size()) - 1);
    const auto word = static_cast<std::uint64_t>(std::llround(duty * top));
    level_word_ &= ~dac_all_;
    for (size_t k = 0; k < dac_masks_.size(); ++k)
      if (word >> k & 1u) level_word_ |= dac_masks_[k];
    return;
  }
  if (frequency_ticks_hz_ > 0) {
    // Frequency mode: a square wave of duty x max_hz, half high, in whole ticks (the period
    // at least two); 0 RPM holds the line low.
    if (!pwm_mask_ || duty <= 0) {
      pwm_high_ticks_ = 0;
      return;
    }
    pwm_period_ticks_ = std::max<std::int64_t>(2, std::llround(frequency_ticks_hz_ / duty));
    pwm_high_ticks_ = pwm_period_ticks_ / 2;
    return;
  }
  pwm_high_ticks_ = pwm_mask_ ? std::llround(duty * static_cast<double>(pwm_period_ticks_)) : 0;
}

bool WordWriter::set_output(int n, bool on) {
  if (n < 1 || n > static_cast<int>(aux_bits_.size()) || aux_bits_[n - 1] < 0) return false;
  const std::uint32_t mask = 1u << aux_bits_[n - 1];
  level_word_ = on ? level_word_ | mask : level_word_ & ~mask;
  return true;
}

bool WordWriter::output_on(int n) const {
  if (n < 1 || n > static_cast<int>(aux_bits_.size()) || aux_bits_[n - 1] < 0) return false;
  return (level_word_ >> aux_bits_[n - 1] & 1u) != 0;
}

void WordWriter::finish_pulses(std::int64_t end) {
  for (std::int64_t pe : pulse_end_) end = std::max(end, pe);
  emit(end);
  // A pulse ending exactly here needs the idle word itself sent, or its line stays active.
  for (std::int64_t pe : pulse_end_)
    if (pe == cursor_ && cursor_ > 0) {
      emit(cursor_ + 1);
      break;
    }
}

bool WordWriter::write_block() {
  if (block_.empty()) return false;
  card_.write(block_);
  block_.clear();
  sent_ = cursor_;
  return true;
}

void WordWriter::halt(int cushion) {
  if (!block_.empty()) card_.write(block_);
  block_.clear();
  sent_ = cursor_;
  if (cushion > 0)
    card_.stop_cushioned(pins_.idle_word(), cushion);  // outputs off after it
  else
    card_.stop(pins_.idle_word());  // outputs off, as an E-stop must
}

void WordWriter::restart() {
  pulse_end_.fill(0);
  level_word_ = pins_.idle_word();
  card_.start(1.0 / timing_.tick_s);
  cursor_ = static_cast<std::int64_t>(card_.ticks_played());  // its new count
  sent_ = cursor_;
}

// `count` words from cursor_ on. The charge pump's bit flips every pump_half_ticks_ ticks,
// and the spindle speed's bit is high for the first pwm_high_ticks_ of each period (both by
// the tick's own number, so the square waves are unbroken across runs and blocks). Where
// they stand is found once per run (a division) and stepped on from flip to flip: the pump
// splits a run every few ticks.
void WordWriter::write_run(std::uint32_t word, std::int64_t count) {
  std::int64_t tick = cursor_;
  std::int64_t pump_phase = 0, pump_flip = 0, pwm_base = 0;  // pwm_base: the period's first tick
  auto locate = [&] {  // at the start, and after a block (its callback may change the speed)
    pump_phase = tick / pump_half_ticks_;
    pump_flip = (pump_phase + 1) * pump_half_ticks_;
    pwm_base = tick - tick % pwm_period_ticks_;
  };
  locate();
  while (count > 0) {
    const auto room = static_cast<std::int64_t>(block_.room());
    std::int64_t n = std::min(room, count);
    std::uint32_t w = word;
    if (pump_mask_) {
      if (tick == pump_flip) {
        ++pump_phase;
        pump_flip += pump_half_ticks_;
      }
      n = std::min(n, pump_flip - tick);
      if (pump_phase & 1) w |= pump_mask_;
    }
    if (pwm_high_ticks_ > 0) {
      if (tick == pwm_base + pwm_period_ticks_) pwm_base = tick;
      const bool high = tick - pwm_base < pwm_high_ticks_;
      n = std::min(n, pwm_base + (high ? pwm_high_ticks_ : pwm_period_ticks_) - tick);
      if (high) w |= pwm_mask_;
    }
    // Eight at a time: a fill of a constant eight words is two vector stores.
    auto left = static_cast<std::size_t>(n);
    for (; left >= 8; left -= 8) block_.append(8, w);
    block_.append(left, w);
    count -= n;
    tick += n;
    if (block_.size() == block_words_) {
      card_.write(block_);
      block_.clear();
      sent_ = tick;
      if (on_block_) on_block_();
      locate();
    }
  }
}

}  // namespace gantry
