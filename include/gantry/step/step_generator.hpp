// Planned segments to pulse words: the exact tick of every step, on the card's clock.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <optional>

#include "gantry/hal/card.hpp"                // Card
#include "gantry/step/card_lead.hpp"          // CardLead
#include "gantry/motion/planned_segment.hpp"  // PlannedSegment, SegmentSink
#include "gantry/step/independent_axis.hpp"   // IndependentMotion
#include "gantry/step/step_log.hpp"           // StepLog
#include "gantry/step/step_placement.hpp"     // StepPlacement
#include "gantry/step/step_timing.hpp"        // StepTiming
#include "gantry/step/word_writer.hpp"        // WordWriter

namespace gantry {

// What the outputs are: the output switches (bit n-1: switch n, as SO numbers them; switch 1
// runs the spindle on ShopBot's wiring) and TR's speed on the spindle's speed output.
struct OutputLevels {
  std::uint32_t switches = 0;
  double spindle_rpm = 0;
};

// Converts each segment's straight path into step events and streams the words to a card.
// It owns and wires three parts, split as Klipper splits itersolve from stepcompress:
// StepPlacement (when each step falls: step_placement.hpp has the derivation and the pulse
// constraints), WordWriter (the events packed into pulse words with the charge pump, the
// spindle and the outputs, blocks to the card, its trips) and StepLog (the steps emitted,
// until and after the card plays them: positions after a fault, a stop or an input edge).
//
// An axis moving on its own (MI, a segment's `independent`) has its steps merged into the
// words as they are emitted, under the same constraints, whatever plays: moves, dwells,
// outputs. The path leaves that axis alone meanwhile. Whenever the stream comes to rest for
// good (flush, new settings) it comes to rest first: the words never stop under a moving axis.
class StepGenerator : public SegmentSink {
 public:
  StepGenerator(const Settings& settings, Card& card, std::size_t block_words = 4096);
  StepGenerator(const StepGenerator&) = delete;  // its parts call back into it
  StepGenerator& operator=(const StepGenerator&) = delete;

  void segment(const PlannedSegment& s) override;
  static constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
  // Ticks at which playing must stop, set by other threads at any time (kNever: none); the
  // earlier of the two counts. Read before every step, so a request arriving mid-segment
  // cuts it at the next word not yet generated.
  struct StopTicks {
    const std::atomic<std::int64_t>* a = nullptr;
    const std::atomic<std::int64_t>* b = nullptr;
    const std::atomic<std::int64_t>* c = nullptr;
    std::int64_t now() const {
      std::int64_t x = a ? a->load(std::memory_order_acquire) : kNever;
      if (b) x = std::min(x, b->load(std::memory_order_acquire));
      return c ? std::min(x, c->load(std::memory_order_acquire)) : x;
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

  const Steps6& position() const { return placement_.position(); }  // steps emitted so far
  // Steps the card has actually played (its ticks_played()): where the tool is after a
  // fault or a stop. Steps are logged until the card confirms them played.
  Steps6 played_position() const;
  // The steps the words before `tick` make: where the tool was then. Exact for ticks not
  // yet played and for about the last second played; nullopt when older.
  std::optional<Steps6> position_at(std::uint64_t tick) const { return log_.position_at(tick); }
  // Arms the card's input watch; `fired` is called once, on this thread, right after the
  // block in which the card reports the edge. An empty mask disarms it. While it is armed
  // its bits do not trip the card as limit switches (homing runs onto a switch that may be
  // one).
  void watch_inputs(const InputWatch& w, std::function<void(const InputEdge&)> fired);
  // Called after every block handed to the card (the controller publishes the position).
  void on_block(std::function<void()> f) { on_block_ = std::move(f); }
  // The spindle output bit, from the next word on.
  void set_spindle(bool on) { writer_.set_spindle(on); }
  // Output switch n (1-based, as SO numbers them), from the next word on; false when the
  // profile does not wire it.
  bool set_output(int n, bool on);
  bool output_on(int n) const { return writer_.output_on(n); }  // its level in the words
  // The spindle's speed output (spindle.pwm_bit) to `rpm`, from the next word on: a square
  // wave of duty rpm / max_rpm, by the tick's own number like the charge pump. No-op
  // when the profile wires none.
  void set_spindle_speed(double rpm);
  // The output switches and the spindle speed in the words the card has played (at its
  // ticks_played()): what the machine's outputs are now. The words emitted lead the card by
  // its queue (a second on a real card), so output_on() is not that.
  OutputLevels played_levels() const;
  // At rest: one word at the levels set since (outputs switched between segments).
  void emit_levels();
  bool faulted() const { return faulted_; }
  // E-stop: the words so far go to the card, which stops at once (after a cushion of
  // `cushion` steps, limits.esc_steps, where it can); unplayed words are lost.
  void halt(int cushion = 0);
  // After halt(): the card starts again and the step counts are the steps it played.
  void restart();
  // Confirms the steps the card has played; on a card fault, throws (once) the error naming
  // the fault and where the tool stopped. Called after every block, and by the job after
  // the card drains.
  void check_card();
  std::int64_t tick() const { return writer_.cursor(); }  // words emitted so far
  std::int64_t sent() const { return writer_.sent(); }    // ... and handed to the card
  bool independent_moving() const { return placement_.independent(); }  // MI's axis runs
  const SourceLoc& loc() const { return current_loc_; }  // the segment being generated
  // The count of the last move whose words (some at least) went to the card.
  const RunCount& ran() const { return ran_; }
  void new_run() { ran_ = {}; }                          // at rest, before a run's first move
  bool warning() const { return warning_; }              // ... is SW's warning
  const StepTiming& timing() const { return timing_; }
  // The bounded lead into a card that queues words (card_lead.hpp): its size and how the
  // generator kept up.
  const CardLead& lead() const { return lead_; }
  CardLead& lead() { return lead_; }

 private:
  void emit_until(std::int64_t tick);  // words for [tick(), tick), independent steps merged
  void play(const StepEvent& e);       // a path step or direction change into the words
  void play_independent(const StepEvent& e);
  void level_changed();  // levels_ holds from the next word on

  StepTiming timing_;
  Card& card_;
  StepPlacement placement_;
  CardLead lead_;  // before writer_: it sizes the writer's blocks
  WordWriter writer_;
  StepLog log_;
  std::int64_t segment_end_ = 0;  // where the next segment starts
  std::function<void(const InputEdge&)> on_edge_;
  std::function<void()> on_block_;
  bool faulted_ = false;
  SourceLoc current_loc_;  // the segment being generated, for the fault message
  RunCount ran_;
  bool warning_ = false;
  OutputLevels levels_;  // in the words emitted
  // Each change of levels_ and the tick it takes effect from; the front is in force at the
  // card's played tick (check_card drops what the card has played past).
  std::deque<std::pair<std::int64_t, OutputLevels>> level_changes_;
  std::array<int, kAxisCount> channel_axis_{};  // drivers.channels: a cushion's steps per axis
};

}  // namespace gantry
