// Plays planned segments through the step generator, and can bring the motion to rest at any
// point of the path (a hold: pause, stop, key up) or stop the pulses at once (a halt: E-stop).
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "gantry/motion/planned_segment.hpp"  // PlannedSegment, SegmentSink
#include "gantry/step/step_generator.hpp"     // StepGenerator

namespace gantry {

// Playing: segments play as planned. Slowing: a hold began; every segment is played slowing
// down at its own acceleration until the machine is at rest. Held: at rest part-way along the
// path; what is left is kept for resume(). Halted: the pulses stopped at once; nothing plays
// until discard().
enum class FeedPhase { Playing, Slowing, Held, Halted };

const char* feed_phase_name(FeedPhase p);

// A hold slows down along the path, never off it: from the speed at the cut, each segment's
// remaining length is run with speed v(s)^2 = v_cut^2 - 2 a s at that segment's acceleration
// a. The plan it replaces reached no segment end faster than a allows to slow down, so the
// hold's speed is never above the plan's anywhere: every corner is taken no faster than
// planned, and every axis stays within its limits. After resume() the kept path starts from
// rest: each segment accelerates from the speed the one before it reached, up to its planned
// cruise and exit speeds (a forward pass: slower than the plan until it catches up).
//
// An axis moving on its own (MI) comes to rest with a hold, after the path, and starts again
// with the first motion after resume(); a discard, a halt or the stream's end forgets it.
//
// Threads: segment(), flush(), settings_changed(), resume() and discard() belong to the thread
// that feeds the card; request_hold(), request_halt() and phase() may be called from any.
class MotionFeeder : public SegmentSink {
 public:
  explicit MotionFeeder(StepGenerator& steps) : steps_(steps) {}

  void segment(const PlannedSegment& s) override;
  void flush() override;
  void settings_changed(const Settings& s) override;

  // Slows to rest from the card's tick `tick` on (0: as soon as possible; a tick already
  // generated means the next word). `pause`: the operator's pause, which also switches off
  // the outputs of pause_outputs() while held (VN output modes 2 and 5), or with
  // `every_output` every output switch on (a stop switch: the spindle stops); resume()
  // switches them on again.
  void request_hold(std::int64_t tick = 0, bool pause = false, bool every_output = false);
  // Output switches (bit n-1: switch n) that a pause turns off.
  void pause_outputs(std::uint32_t mask) { pause_mask_.store(mask, std::memory_order_relaxed); }
  // Stops the pulses at `tick` (0: at once): the card is stopped, unplayed words dropped.
  // `cushion` > 0 (the operator's E-stop with limits.esc_steps): the card decelerates every
  // moving channel to rest within that many steps first (Card::stop_cushioned).
  void request_halt(std::int64_t tick = 0, int cushion = 0);
  FeedPhase phase() const { return phase_.load(std::memory_order_acquire); }
  // Held: plays what was kept, from rest, and what follows.
  void resume();
  // Held or Halted: forgets what was kept; the next segment starts where the tool is.
  void discard();
  // Held or playing: the pulses stop here and now (E-stop with nothing cut mid-segment).
  void halt_now();
  // Whether a flush arrived while held (the stream's end is among what was kept).
  bool flush_kept() const;
  // Flushes done: played out, or abandoned by a halt or a discard.
  std::uint64_t flushes_completed() const { return flushes_; }
  // The source line of the segment where the hold or halt came to rest.
  const SourceLoc& rest_loc() const { return rest_loc_; }
  // The path is at rest (the last segment played ended at rest). Feeder thread.
  bool at_rest() const { return carry_ <= 0; }
  // Playing at rest with no axis moving on its own: the words so far go to the card and the
  // stream ends there (the card may run dry at rest). False when that cannot be done now.
  bool rest_stream();
  // The operator's feed override changed to `factor` (any thread): the segment playing
  // re-ramps to it from the next word not generated, and so does every segment planned with
  // another factor, until the planner's own come (they carry the factor they were planned
  // with). The change is within the axes' limits: from the speed at the cut, towards the new
  // cruise at the segment's acceleration, leaving at the planned exit speed.
  void live_override(double factor);
  // The tick of the first word of the last hold's ramp down (the first word that differs
  // from the plan), or -1 before any: what the hold-latency bench and tests measure. Any thread.
  std::int64_t hold_tick() const { return hold_tick_.load(std::memory_order_acquire); }

 private:
  struct Kept {  // what arrived while held, in order
    enum Kind { kSegment, kSettings, kFlush } kind;
    PlannedSegment seg;
    std::shared_ptr<const gantry::Settings> settings;
  };
  void play(const PlannedSegment& s);  // as given, until a hold or halt cuts it
  // `s` from speed `v` at its start towards the live override's cruise; false when it cannot
  // (then it plays as planned).
  bool reramp(const PlannedSegment& s, double v);
  void slow(const PlannedSegment& s);  // slowing from carry_
  void hold_here(const PlannedSegment& rest);
  void settle();                                     // at rest: held
  void switch_outputs(std::uint32_t mask, bool on);  // bit n-1: output n, in one word at rest
  void set_phase(FeedPhase p) { phase_.store(p, std::memory_order_release); }

  StepGenerator& steps_;
  std::atomic<FeedPhase> phase_{FeedPhase::Playing};
  std::atomic<std::int64_t> hold_at_{StepGenerator::kNever}, halt_at_{StepGenerator::kNever};
  std::atomic<int> halt_cushion_{0};  // the next halt's cushion, steps
  // The live override: its factor (0: none set) and the tick from which it re-ramps.
  std::atomic<double> live_factor_{0};
  std::atomic<std::int64_t> override_at_{StepGenerator::kNever};
  double carry_ = 0;          // the speed the last segment played ended at
  bool catching_up_ = false;  // after a rest: below the plan's speeds until it reaches them
  std::deque<Kept> kept_;
  SourceLoc rest_loc_;
  std::atomic<std::int64_t> hold_tick_{-1};
  std::uint64_t flushes_ = 0;
  std::optional<IndependentMotion> parked_;  // rested by a hold, to start again on resume
  std::atomic<bool> pausing_{false}, every_output_{false};
  std::atomic<std::uint32_t> pause_mask_{0};
  std::uint32_t paused_off_ = 0;  // switched off by the pause, to switch on at resume
};

}  // namespace gantry
