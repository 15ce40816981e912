// Step placement: when each step of a segment falls on the card's tick clock, and of an
// axis moving on its own (MI), under the pulse constraints.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "gantry/core/axes.hpp"               // kAxisCount, Steps6
#include "gantry/step/backlash.hpp"           // Backlash
#include "gantry/motion/planned_segment.hpp"  // PlannedSegment
#include "gantry/step/independent_axis.hpp"   // IndependentAxis
#include "gantry/step/step_timing.hpp"        // StepTiming, StepEvent

namespace gantry {

struct Settings;

// A segment moves axis i by n_i = |round(to_i * spu_i) - p_i| whole steps from its count
// p_i (the commanded position is rounded once, so steps never drift). Its k-th step is due
// when the exact position crosses p_i +/- (k - 1/2), at path fraction
// f_k = (p_i +/- (k - 1/2) - x0) / (x1 - x0) with x0, x1 the ends in steps; it is placed at
// the time the profile reaches f_k * L, rounded to the nearest tick. So each axis's count
// is exact, each step is within half a tick of the ideal rounding instant, and a segment
// cut part-way (a hold) continues with the steps it would have played.
//
// Constraints are then enforced by delaying, never by dropping: a step is no earlier than
// min_period after the previous one on its axis, and when the direction changes the new
// level is set after the previous pulse has ended and at least dir_setup before the step.
//
// The axis state (count, direction, last step) follows the events as they go into the
// words (applied), not as they are placed: a segment cut part-way leaves each axis as its
// last played event left it.
class StepPlacement {
 public:
  StepPlacement(const Settings& settings, const StepTiming& timing);
  void settings_changed(const Settings& s);  // steps per unit; the counts stay

  // Places `seg`'s path steps from tick t0, never before `cursor` (the words sent) nor a
  // direction change during a pulse (`pulse_end`); the events then come from next_event().
  // Returns the tick the segment ends: its profile and dwell, or its last step if later.
  // A count that does not fit throws, located, before any event is placed.
  std::int64_t place(const PlannedSegment& seg, std::int64_t t0, std::int64_t cursor,
                     const std::array<std::int64_t, kAxisCount>& pulse_end);
  // The placed events in tick order (within a tick the lower axis first, and an axis's
  // direction change before its step); nullptr when none is left.
  // The axes' next ticks are kept apart (head_), so the choice is six compares of one array.
  // This is the step generator's inner loop: read through next_ and stop_ into events_, it
  // was a branchy loop whose speed hung on how the compiler laid out its caller
  // (BM_StepGeneratorSixAxesAt100kHz 12.3 M words/s, 8.5 M after a change to the caller's
  // loop; 13.0 M with head_).
  const StepEvent* next_event() {
    int best = 0;
    for (int i = 1; i < kAxisCount; ++i)
      if (head_[i] < head_[best]) best = i;
    if (head_[best] == kNoEvent) return nullptr;
    const StepEvent* e = &events_[next_[best]++];
    head_[best] = next_[best] < stop_[best] ? events_[next_[best]].tick : kNoEvent;
    return e;
  }
  // `e` went into the words: its axis's direction or count and last step follow.
  void applied(const StepEvent& e) {
    if (e.is_dir) {
      positive_[e.axis] = e.positive;
    } else {
      if (e.takeup) {
        backlash_.took_up(e.axis, e.positive);
      } else {
        position_[e.axis] += e.positive ? 1 : -1;
        backlash_.moved(e.axis, e.positive);
      }
      last_step_[e.axis] = e.tick;
    }
  }

  // The axis moving on its own, if any.
  bool independent() const { return independent_.has_value(); }
  // It starts from `tick` (none was moving).
  void start_independent(const IndependentMotion& m, std::int64_t tick);
  // It comes to rest from `tick` on; its last events then come from independent_event().
  void stop_independent_from(std::int64_t tick) { independent_->stop_from(tick); }
  // It is gone (at rest, or E-stop); returns what it was doing.
  IndependentMotion end_independent();
  // Its next event, placed as a path step is: never before `cursor`, min_period after the
  // axis's last step, and a direction change set up dir_setup before its step. nullopt when
  // it has come to rest for good (or there is none).
  std::optional<StepEvent> independent_event(
      std::int64_t cursor, const std::array<std::int64_t, kAxisCount>& pulse_end) const;
  void independent_applied(const StepEvent& e);  // `e` (from independent_event) went out

  const Steps6& position() const { return position_; }  // steps after all applied events
  const std::array<bool, kAxisCount>& positive() const { return positive_; }
  const std::array<double, kAxisCount>& steps_per_unit() const { return steps_per_unit_; }
  const Backlash& backlash() const { return backlash_; }
  // After an E-stop: the counts are `played`, the levels as at construction.
  void restart(const Steps6& played);

 private:
  // `x` rounded to whole ticks or steps (`what`); a located error when it is not finite or
  // does not fit.
  static std::int64_t whole(double x, const char* what, const SourceLoc& loc);

  std::array<double, kAxisCount> steps_per_unit_{};
  StepTiming timing_;
  Backlash backlash_;  // the takeup steps at each reversal (backlash.hpp)
  Steps6 position_{};  // steps after all applied events
  std::array<bool, kAxisCount> positive_{};
  std::array<std::int64_t, kAxisCount> last_step_{};
  std::vector<StepEvent> events_;
  std::array<std::size_t, kAxisCount> next_{}, stop_{};  // each axis's run of events
  static constexpr std::int64_t kNoEvent = INT64_MAX;
  std::array<std::int64_t, kAxisCount> head_{};  // the tick of events_[next_[i]], or kNoEvent
  std::optional<IndependentAxis> independent_;
  std::int64_t independent_dir_tick_ = 0;  // when its direction level last changed
};

}  // namespace gantry
