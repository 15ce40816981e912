// Planned segments to pulse words: the exact tick of every step, on the card's clock.
#pragma once

#include <cstdint>
#include <vector>

#include "gantry/hal/card.hpp"                // Card
#include "gantry/hal/pin_map.hpp"             // PinMap
#include "gantry/motion/planned_segment.hpp"  // PlannedSegment, SegmentSink

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
// Step placement. A segment moves axis i by n_i = |round(to_i * spu_i) - round(from_i * spu_i)|
// whole steps (the commanded position is rounded once, so steps never drift). Along the
// segment's path, axis i has moved k - 1/2 steps when the path fraction reaches
// f_k = (k - 1/2) / n_i; its k-th step is placed at the time the profile reaches distance
// f_k * L, rounded to the nearest tick. So each axis's step count is exact and each step is
// within half a tick of the ideal position-rounding instant.
//
// Constraints are then enforced by delaying, never by dropping: a step is no earlier than
// min_period after the previous one on its axis, and when the direction changes the new
// level is set after the previous pulse has ended and at least dir_setup before the step.
class StepGenerator : public SegmentSink {
 public:
  StepGenerator(const Settings& settings, Card& card, std::size_t block_words = 4096);

  void segment(const PlannedSegment& s) override;
  void flush() override;  // plays out every pending pulse and hands the last block to the card
  void settings_changed(const Settings& s) override;

  const Steps6& position() const { return position_; }  // steps emitted so far
  // Steps the card has actually played (its ticks_played()): where the tool is after a
  // fault or a stop. Steps are logged until the card confirms them played.
  Steps6 played_position() const;
  // The spindle output bit, from the next word on.
  void set_spindle(bool on);
  // Output switch n (1-based, as SO numbers them), from the next word on; false when the
  // profile does not wire it.
  bool set_output(int n, bool on);
  bool faulted() const { return faulted_; }
  // Confirms the steps the card has played; on a card fault, throws (once) the error naming
  // the fault and where the tool stopped. Called after every block, and by the job after
  // the card drains.
  void check_card();
  std::int64_t tick() const { return cursor_; }  // words emitted so far
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

  void emit_until(std::int64_t tick);  // words for [cursor_, tick)
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
  std::vector<StepRecord> step_log_;  // ring [log_begin_, log_end_) of steps not yet played
  std::size_t log_begin_ = 0, log_end_ = 0;
  Steps6 confirmed_{};  // steps known played
  bool faulted_ = false;
  SourceLoc current_loc_;  // the segment being generated, for the fault message
};

}  // namespace gantry
