// Packing step events into the card's 32-bit pulse words: step and direction levels, the
// charge pump, the spindle and output bits, blocks handed to the card, the card's trips.
#pragma once

#include <algorithm>  // fill_n
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "gantry/core/axes.hpp"            // kAxisCount
#include "gantry/hal/card.hpp"             // Card, InputWatch
#include "gantry/hal/input_roles.hpp"      // InputRoles
#include "gantry/hal/pin_map.hpp"          // PinMap
#include "gantry/step/step_timing.hpp"     // StepTiming, StepEvent

namespace gantry {

struct Settings;

// The words of one block, stored once: a run of `n` copies is a fill of its memory, with
// none of vector::insert's per-call work (the runs between pulses are short: the charge
// pump flips every few ticks). Read by the card as a span.
class WordBlock {
 public:
  explicit WordBlock(std::size_t capacity) : words_(capacity) {}
  void append(std::size_t n, std::uint32_t w) {  // n <= room()
    std::fill_n(words_.data() + size_, n, w);
    size_ += n;
  }
  std::size_t room() const { return words_.size() - size_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() { size_ = 0; }
  const std::uint32_t* begin() const { return words_.data(); }
  const std::uint32_t* end() const { return words_.data() + size_; }

 private:
  std::vector<std::uint32_t> words_;
  std::size_t size_ = 0;
};

// Words go out in tick order from cursor() on: each is the levels set so far (directions,
// idle step levels, spindle, outputs) with the step lines of pulses not yet over flipped
// active, and the charge pump's and the spindle speed's square waves. They are collected
// in blocks of `block_words`; each full block goes to the card, then to `on_block`.
class WordWriter {
 public:
  WordWriter(const Settings& settings, const StepTiming& timing, Card& card,
             std::size_t block_words);

  // Called after every full block handed to the card (the generator checks the card).
  void on_block(std::function<void()> f) { on_block_ = std::move(f); }
  // New pins, the card's calibration and trips; `positive` are the axes' direction levels.
  void settings_changed(const Settings& s, const std::array<bool, kAxisCount>& positive);

  // `e` from its tick on: a direction level changes, or a step pulse starts.
  void apply(const StepEvent& e) {
    const AxisPins& ap = pins_.axes[e.axis];
    if (e.is_dir)
      level_word_ = (level_word_ & ~ap.dirs) | pins_.dir_bits(e.axis, e.positive);
    else {
      pulse_end_[e.axis] = e.tick + timing_.pulse_ticks;
      pulse_lines_[e.axis] = ap.steps & ~resting_steps_;
    }
  }
  // The channels (bit k: channel k + 1) whose step lines stay idle from the next step on,
  // their axis stepping on its other channels (squaring a slaved axis); 0: none.
  void rest_channels(unsigned channels);
  // Words for [cursor(), tick). The word only changes where a pulse ends: they go out up to
  // the next such tick in one run.
  void emit(std::int64_t tick) {
    while (cursor_ < tick) {
      std::int64_t next = tick;
      for (std::int64_t pe : pulse_end_)
        if (pe > cursor_ && pe < next) next = pe;
      write_run(word_at(cursor_), next - cursor_);
      cursor_ = next;
    }
  }
  // Plays out every pending pulse: words up to `end` and until every pulse is over (the
  // idle word itself sent when one ends exactly there).
  void finish_pulses(std::int64_t end);
  // Hands the words not yet sent to the card; false when there were none.
  bool write_block();

  std::int64_t cursor() const { return cursor_; }  // next tick to emit: words emitted so far
  std::int64_t sent() const { return sent_; }      // the tick after the last word sent to the card
  // The tick each axis's step line goes idle again.
  const std::array<std::int64_t, kAxisCount>& pulse_end() const { return pulse_end_; }
  std::size_t block_words() const { return block_words_; }

  // The spindle output bit, from the next word on.
  void set_spindle(bool on);
  // Output switch n (1-based, as SO numbers them), from the next word on; false when the
  // profile does not wire it.
  bool set_output(int n, bool on);
  bool output_on(int n) const;  // output switch n's level in the words
  // The spindle's speed output (spindle.pwm_bit) to `rpm`, from the next word on: a square
  // wave of duty rpm / max_rpm (or, in frequency mode, of rpm / max_rpm x max_hz, half high),
  // by the tick's own number like the charge pump. No-op when the profile wires none.
  void set_spindle_speed(double rpm);

  // Arms the card's input watch. While it is armed its bits do not trip the card as limit
  // switches (homing runs onto a switch that may be one).
  void watch(const InputWatch& w);

  // E-stop: the words so far go to the card, which stops at once with its outputs idle.
  void halt(int cushion = 0);
  // After halt(): the card starts again, the levels as at construction, and the words go
  // on from the tick it has played.
  void restart();

 private:
  std::uint32_t word_at(std::int64_t tick) const {
    std::uint32_t w = level_word_;
    for (int i = 0; i < kAxisCount; ++i)
      if (tick < pulse_end_[i]) w ^= pulse_lines_[i];  // active = not idle
    return w;
  }
  void write_run(std::uint32_t word, std::int64_t count);
  void set_card_trips();

  PinMap pins_;
  StepTiming timing_;
  Card& card_;
  std::size_t block_words_;
  std::array<std::int64_t, kAxisCount> pulse_end_{};
  std::array<std::uint32_t, kAxisCount> pulse_lines_{};  // the step lines of each axis's last pulse
  std::array<std::uint32_t, kAxisCount> channel_steps_{};  // each channel's step bit
  std::uint32_t resting_steps_ = 0;  // the step bits of the resting channels
  std::uint32_t level_word_ = 0;  // direction levels and idle step levels
  std::int64_t cursor_ = 0;       // next tick to emit
  std::int64_t sent_ = 0;         // next tick not yet handed to the card
  WordBlock block_;
  std::uint32_t pump_mask_ = 0, spindle_mask_ = 0;
  std::vector<int> aux_bits_;
  std::int64_t pump_half_ticks_ = 1;
  std::uint32_t pwm_mask_ = 0;
  std::vector<std::uint32_t> dac_masks_;  // spindle.dac_bits, least significant first
  std::uint32_t dac_all_ = 0;
  std::int64_t pwm_period_ticks_ = 1, pwm_high_ticks_ = 0;  // high for the first ticks of a period
  double max_rpm_ = 0;
  double frequency_ticks_hz_ = 0;  // frequency mode: ticks a period at max_rpm (0: PWM mode)
  InputRoles roles_;              // the profile's and VN's, for the card's trips
  std::uint32_t watch_mask_ = 0;  // the bits watched now
  std::function<void()> on_block_;
};

}  // namespace gantry
