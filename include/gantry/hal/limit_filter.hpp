// When a limit switch stops the card: one rule for every card (simulated, PCI-7200, GPIO),
// from the profile's [limits] (WinCNC's lim_mode and lim_cnt), and the cushioned stop's
// words (lim_step, esc_step). docs/hardware.md, "Limit modes" and "Cushioned stop".
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "gantry/core/axes.hpp"        // kAxisCount
#include "gantry/hal/debounce.hpp"     // Debounce
#include "gantry/hal/input_roles.hpp"  // InputTrip
#include "gantry/hal/pin_map.hpp"      // PinMap

namespace gantry {

struct Settings;

// Decides, sample by sample, whether a limit input trips the card.
//
// - A limit input counts as it becomes active (never while it stays active: the tool that
//   stopped on a switch can move off it).
// - limits.travel_only (lim_mode 1): a channel's min (max) switch counts only while that
//   channel has stepped towards minus (plus) within kTravelS; an input of no channel (VN's
//   limit inputs) always counts.
// - limits.debounce (lim_cnt): it trips once it has read active in that many consecutive
//   samples; released before, it is forgotten.
//
// A card feeds it the steps it plays (note_step from a decoder, or note_word from the words
// themselves) and its input samples; channel k's switches are inputs.<k's letter>, as on the
// simulated card. Not thread-safe: the card's playing thread owns it.
class LimitFilter {
 public:
  static constexpr double kTravelS = 0.05;
  static constexpr std::uint64_t kNone = Debounce::kNone;

  LimitFilter() = default;
  // The profile's rule and wiring; `pacer_hz` sizes the travel window in ticks.
  LimitFilter(const Settings& s, double pacer_hz);

  // Channel `k` stepped at `tick`, towards plus or minus.
  void note_step(int k, std::uint64_t tick, bool positive) {
    last_step_[k] = static_cast<std::int64_t>(tick);
    last_positive_[k] = positive;
  }
  // The card plays `word` at `tick`, after `before`: its step lines' leading edges are steps.
  void note_word(std::uint64_t tick, std::uint32_t before, std::uint32_t word);
  // The input sample `bits` (the one before was `before`), standing for `repeat` consecutive
  // samples alike (a card that skips runs of words with nothing new). True: the card trips.
  bool sample(const InputTrip& limits, std::uint64_t tick, std::uint32_t before, std::uint32_t bits,
              std::uint64_t repeat = 1);
  // Inputs still counting: how many more samples alike trip the card; kNone when none count.
  std::uint64_t samples_to_trip() const { return count_.samples_left(); }
  void reset() { count_.reset(); }
  bool travel_only() const { return travel_only_; }
  int debounce() const { return count_.needed(); }

 private:
  bool travelling_to(std::uint32_t fresh, std::uint64_t tick) const;

  bool travel_only_ = false;
  std::int64_t window_ = 0;  // kTravelS in ticks
  PinMap pins_;              // channel k's step and direction bits (channels, not axes)
  std::uint32_t step_bits_ = 0;
  std::array<int, kAxisCount> min_bit_{-1, -1, -1, -1, -1, -1}, max_bit_{-1, -1, -1, -1, -1, -1};
  static constexpr std::int64_t kLongAgo = std::numeric_limits<std::int64_t>::min() / 2;
  std::array<std::int64_t, kAxisCount> last_step_{kLongAgo, kLongAgo, kLongAgo,
                                                  kLongAgo, kLongAgo, kLongAgo};
  std::array<bool, kAxisCount> last_positive_{};
  Debounce count_;  // limits.debounce: the inputs counting their samples
};

// A channel's motion at the instant a cushioned stop begins: its step rate (steps per tick,
// 0 at rest) and its direction.
struct ChannelMotion {
  double rate = 0;
  bool positive = true;
};

// Each channel's step rate from its last two steps before `now`: 1 / their interval while
// the last one is within two intervals (and kTravelS) of `now`, else 0 (at rest).
ChannelMotion motion_from_steps(std::int64_t prev, std::int64_t last, bool positive,
                                std::int64_t now, double tick_s);

// The cushioned stop's words (WinCNC's lim_step, esc_step), for the ticks after `word` (the
// last word played): every channel still moving goes on the way it went, its rate falling
// linearly to rest, so that the fastest makes `steps` more steps and each other one its
// share (rate / fastest rate of them, rounded to whole steps); step k of a channel falls
// where its decelerating position crosses k - 1/2, no sooner than `min_period` ticks after
// its step before (`since_step[k]`: ticks from channel k's last step to the first cushion
// word; a pulse still running goes on to its width).
// The last word has every step line idle; nothing else of `word` changes (directions,
// outputs). Empty when nothing moves.
std::vector<std::uint32_t> cushion_words(const PinMap& pins, std::uint32_t word,
                                         const std::array<ChannelMotion, kAxisCount>& motion,
                                         const std::array<std::int64_t, kAxisCount>& since_step,
                                         int steps, int pulse_ticks);

}  // namespace gantry
