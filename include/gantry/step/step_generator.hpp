// Planned segments to pulse words: the exact tick of every step, on the card's clock.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "gantry/hal/card.hpp"                // Card
#include "gantry/hal/pin_map.hpp"             // PinMap
#include "gantry/motion/planned_segment.hpp"  // PlannedSegment, SegmentSink
#include "gantry/step/independent_axis.hpp"   // IndependentAxis

namespace gantry {

// Pulse timing in whole ticks, each rounded up from the profile's microseconds.
struct StepTiming {
  double tick_s = 5e-6;
  std::int64_t pulse_ticks = 1;       // step line held active this long
  std::int64_t dir_setup_ticks = 1;   // direction stable this long before the active edge
  std::int64_t min_period_ticks = 2;  // pulse plus one idle tick: the fastest step rate

  static StepTiming from(const CardSettings& card);
};

// Converts each segment's straight path into step events and streams the words to a card.
//
// Step placement. A segment moves axis i by n_i = |round(to_i * spu_i) - p_i| whole steps
// from its count p_i (the commanded position is rounded once, so steps never drift). Its
// k-th step is due when the exact position crosses p_i +/- (k - 1/2), at path fraction
// f_k = (p_i +/- (k - 1/2) - x0) / (x1 - x0) with x0, x1 the ends in steps; it is placed at
// the time the profile reaches f_k * L, rounded to the nearest tick. So each axis's count
// is exact, each step is within half a tick of the ideal rounding instant, and a segment
// cut part-way (a hold) continues with the steps it would have played.
//
// Constraints are then enforced by delaying, never by dropping: a step is no earlier than
// min_period after the previous one on its axis, and when the direction changes the new
// level is set after the previous pulse has ended and at least dir_setup before the step.
//
// An axis moving on its own (MI, a segment's `independent`) has its steps merged into the
// words as they are emitted, under the same constraints, whatever plays: moves, dwells,
// outputs. The path leaves that axis alone meanwhile. Whenever the stream comes to rest for
// good (flush, new settings) it comes to rest first: the words never stop under a moving axis.
class StepGenerator : public SegmentSink {
 public:
  StepGenerator(const Settings& settings, Card& card, std::size_t block_words = 4096);

  void segment(const PlannedSegment& s) override;
  static constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
  // Ticks at which playing must stop, set by other threads at any time (kNever: none); the
  // earlier of the two counts. Read before every step, so a request arriving mid-segment
  // cuts it at the next word not yet generated.
  struct StopTicks {
    const std::atomic<std::int64_t>* a = nullptr;
    const std::atomic<std::int64_t>* b = nullptr;
    std::int64_t now() const {
      const std::int64_t x = a ? a->load(std::memory_order_acquire) : kNever;
      return b ? std::min(x, b->load(std::memory_order_acquire)) : x;
    }
  };
  // Plays `s` unless the clock reaches a stop tick first (never earlier than the words
  // already sent): then only the steps due before it play, and the result is the time into
  // the segment's profile where it was cut (the machine is then at that point of the path,
  // at that speed; the caller decides what follows).
  std::optional<double> segment_until(const PlannedSegment& s, StopTicks stop);
  void flush() override;  // plays out every pending pulse and hands the last block to the card
  // The axis moving on its own comes to rest (see IndependentAxis::stop_from), its words
  // emitted; returns what it was doing (nullopt: none), for a hold to start it again.
  std::optional<IndependentMotion> rest_independent();
  // Starts `m` from the words emitted so far (an axis already moving on its own rests first).
  void start_independent(const IndependentMotion& m);
  void settings_changed(const Settings& s) override;

  const Steps6& position() const { return position_; }  // steps emitted so far
  // Steps the card has actually played (its ticks_played()): where the tool is after a
  // fault or a stop. Steps are logged until the card confirms them played.
  Steps6 played_position() const;
  // The steps the words before `tick` make: where the tool was then. Exact for ticks not
  // yet played and for about the last second played; nullopt when older.
  std::optional<Steps6> position_at(std::uint64_t tick) const;
  // Arms the card's input watch; `fired` is called once, on this thread, right after the
  // block in which the card reports the edge. An empty mask disarms it. While it is armed
  // its bits do not trip the card as limit switches (homing runs onto a switch that may be
  // one).
  void watch_inputs(const InputWatch& w, std::function<void(const InputEdge&)> fired);
  // Called after every block handed to the card (the controller publishes the position).
  void on_block(std::function<void()> f) { on_block_ = std::move(f); }
  // The spindle output bit, from the next word on.
  void set_spindle(bool on);
  // Output switch n (1-based, as SO numbers them), from the next word on; false when the
  // profile does not wire it.
  bool set_output(int n, bool on);
  bool output_on(int n) const;  // output switch n's level in the words
  // The spindle's speed output (spindle.pwm_bit) to `rpm`, from the next word on: a square
  // wave of duty rpm / max_rpm, by the tick's own number like the charge pump. No-op
  // when the profile wires none.
  void set_spindle_speed(double rpm);
  // At rest: one word at the levels set since (outputs switched between segments).
  void emit_levels();
  bool faulted() const { return faulted_; }
  // E-stop: the words so far go to the card, which stops at once; unplayed words are lost.
  void halt();
  // After halt(): the card starts again and the step counts are the steps it played.
  void restart();
  // Confirms the steps the card has played; on a card fault, throws (once) the error naming
  // the fault and where the tool stopped. Called after every block, and by the job after
  // the card drains.
  void check_card();
  std::int64_t tick() const { return cursor_; }          // words emitted so far
  const SourceLoc& loc() const { return current_loc_; }  // the segment being generated
  // The count of the last move whose words (some at least) went to the card.
  const RunCount& ran() const { return ran_; }
  void new_run() { ran_ = {}; }                          // at rest, before a run's first move
  bool warning() const { return warning_; }              // ... is SW's warning
  const StepTiming& timing() const { return timing_; }

 private:
  struct Event {
    std::int64_t tick;
    int axis;
    bool is_dir;
    bool positive;
  };
  struct StepRecord {
    std::int64_t tick;
    int axis;
    int delta;
  };

  void emit_until(std::int64_t tick);  // words for [cursor_, tick), independent steps merged
  void emit_words(std::int64_t tick);  // words for [cursor_, tick)
  // The independent axis's next event, its tick constrained as a path step's would be.
  std::optional<Event> independent_event() const;
  void play_independent(const Event& e);
  void apply(const Event& e);
  std::uint32_t word_at(std::int64_t tick) const;
  void write_run(std::uint32_t word, std::int64_t count);

  std::array<double, kAxisCount> steps_per_unit_{};
  PinMap pins_;
  StepTiming timing_;
  Card& card_;
  std::size_t block_words_;

  Steps6 position_{};  // steps after all applied events
  std::array<bool, kAxisCount> positive_{};
  std::array<std::int64_t, kAxisCount> last_step_{};
  std::array<std::int64_t, kAxisCount> pulse_end_{};
  std::uint32_t level_word_ = 0;  // direction levels and idle step levels
  std::int64_t cursor_ = 0;       // next tick to emit
  std::int64_t segment_end_ = 0;  // where the next segment starts
  std::vector<Event> events_;
  std::vector<std::uint32_t> block_;
  std::uint32_t pump_mask_ = 0, spindle_mask_ = 0;
  std::vector<int> aux_bits_;
  std::int64_t pump_half_ticks_ = 1;
  std::uint32_t pwm_mask_ = 0;
  std::int64_t pwm_period_ticks_ = 1, pwm_high_ticks_ = 0;  // high for the first ticks of a period
  double max_rpm_ = 0;
  // A ring of steps: [log_begin_, log_played_) played (kept as history), [log_played_,
  // log_end_) not yet confirmed played.
  std::vector<StepRecord> step_log_;
  std::size_t log_begin_ = 0, log_played_ = 0, log_end_ = 0;
  Steps6 confirmed_{};  // steps known played: the count at log_played_
  std::int64_t history_ticks_ = 0;
  std::int64_t history_from_ = 0;  // steps before this tick are no longer kept
  std::function<void(const InputEdge&)> on_edge_;
  InputRoles roles_;              // the profile's and VN's, for the card's trips
  std::uint32_t watch_mask_ = 0;  // the bits watched now
  void set_card_trips();
  std::function<void()> on_block_;
  bool faulted_ = false;
  SourceLoc current_loc_;  // the segment being generated, for the fault message
  RunCount ran_;
  // `x` rounded to whole ticks or steps (`what`); a located error when it is not finite or
  // does not fit.
  std::int64_t whole(double x, const char* what) const;
  bool warning_ = false;
  std::optional<IndependentAxis> independent_;
  std::int64_t independent_dir_tick_ = 0;  // when its direction level last changed
};

}  // namespace gantry
