// When a limit switch stops the card: one rule for every card (simulated, PCI-7200, GPIO),
// from the profile's [limits] (WinCNC's lim_mode and lim_cnt), and the cushioned stop's
// words (lim_step, esc_step). docs/hardware.md, "Limit modes" and "Cushioned stop".
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "gantry/core/axes.hpp"        // kAxisCount, Steps6
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
// outputs). Done at once when nothing moves.
//
// One word at a time, without allocating: a card's real-time thread plays the words as it
// goes (the PCI-7200's feeder, the GPIO card's player), and cushion_words() below collects
// them for the simulated card, so every card plays the same words.
class CushionStream {
 public:
  CushionStream() = default;
  CushionStream(const PinMap& pins, std::uint32_t word,
                const std::array<ChannelMotion, kAxisCount>& motion,
                const std::array<std::int64_t, kAxisCount>& since_step, int steps, int pulse_ticks);

  bool done() const;
  std::uint64_t given() const { return given_; }  // words given so far: the next one's index
  std::uint32_t next();                           // the next word (not after done())
  // How many words from the next one on are alike (at least 1 unless done()): a player that
  // sleeps through runs of equal words skips them with skip().
  std::uint64_t alike_ahead() const;
  void skip(std::uint64_t n) {  // gives n words alike (n <= alike_ahead()) unreturned
    if (n == 0) return;
    next();
    given_ += n - 1;
  }
  // Each channel's steps in the words given so far, signed by the direction its line shows.
  Steps6 steps() const;
  // The steps in the words up to the `words`th, given from this state on (called on a copy
  // kept from the start: a cushion cut short by the E-stop input or a stop).
  Steps6 steps_in(std::uint64_t words) const;

 private:
  std::int64_t step_tick(int k, int j, std::int64_t earliest) const;  // channel k's step j

  std::uint32_t base_ = 0;  // the word with every step line idle
  std::array<std::uint32_t, kAxisCount> step_bits_{};
  std::array<bool, kAxisCount> positive_{};  // as the word's direction line shows
  std::array<double, kAxisCount> rate_{}, phase_{};
  std::array<int, kAxisCount> count_{};  // the steps each channel makes
  double T_ = 0;                         // ticks to rest
  std::int64_t pulse_ = 1;
  static constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
  // The state at word given_: each channel's steps begun, the tick its pulse (or the pulse
  // it was in at the start) ends, and its next step's tick.
  std::array<int, kAxisCount> begun_{};
  std::array<std::int64_t, kAxisCount> active_until_{}, next_start_{};
  std::int64_t given_ = 0;
  bool none_ = true;  // nothing moves (or default-built)
};

std::vector<std::uint32_t> cushion_words(const PinMap& pins, std::uint32_t word,
                                         const std::array<ChannelMotion, kAxisCount>& motion,
                                         const std::array<std::int64_t, kAxisCount>& since_step,
                                         int steps, int pulse_ticks);

// The profile's cushion for a card: its pins (channel k's step and direction bits, as the
// words carry them), limits.cushion_steps after a limit trip, and the step pulse's width in
// pacer ticks (card.step_pulse_us, rounded up).
struct CushionRule {
  PinMap pins;
  int limit_steps = 0;
  int pulse_ticks = 1;
  CushionRule() = default;
  explicit CushionRule(const Settings& s);
};

// The steps a real card played, read from its words (leading edges of the step lines), kept
// deep enough to find each channel's last two steps and the word in force before any tick
// still to come out of the card: the PCI-7200 notes words as its feeder hands them on, up to
// two DMA halves before they play. The non-step bits' changes are kept too (directions,
// outputs, but not `ignore`: the charge pump). Allocates only when built.
class StepTrail {
 public:
  StepTrail() = default;
  // `depth`: steps kept per channel, and twice that of other changes.
  StepTrail(const PinMap& pins, std::size_t depth, std::uint32_t ignore = 0);
  void reset(std::uint32_t word);  // a new run: nothing stepped, `word` on the lines
  void note_word(std::uint64_t tick, std::uint32_t before, std::uint32_t word);
  // The cushion beginning at tick `now` (the words before it played): the word in force,
  // each channel's motion (motion_from_steps) and ticks since its last step.
  std::uint32_t word_before(std::uint64_t now) const;
  void motion_at(std::uint64_t now, double tick_s, std::array<ChannelMotion, kAxisCount>& motion,
                 std::array<std::int64_t, kAxisCount>& since_step) const;

 private:
  struct Ring {  // the newest `mask + 1` entries
    std::vector<std::uint64_t> at;
    std::vector<std::uint32_t> word;  // the level ring's words
    std::uint64_t count = 0;
    std::uint64_t mask = 0;
  };
  PinMap pins_;
  std::uint32_t step_bits_ = 0, ignore_ = 0;
  std::array<Ring, kAxisCount> steps_;  // tick << 1 | positive
  Ring levels_;                         // ticks where the non-step bits changed, and to what
};

}  // namespace gantry
