// Step placement: each step of a segment at the tick its half step is crossed.
#include "gantry/step/step_placement.hpp"

#include <algorithm>  // max, clamp
#include <cmath>      // llround
#include <limits>     // numeric_limits

#include <fmt/format.h>  // the error message

#include "gantry/core/bounded.hpp"       // checked_llround
#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

StepPlacement::StepPlacement(const Settings& settings, const StepTiming& timing)
    : timing_(timing), backlash_(settings) {
  for (int i = 0; i < kAxisCount; ++i) steps_per_unit_[i] = settings.axes[i].steps_per_unit;
  positive_.fill(true);
  last_step_.fill(std::numeric_limits<std::int64_t>::min() / 2);
}

void StepPlacement::settings_changed(const Settings& s) {
  for (int i = 0; i < kAxisCount; ++i) steps_per_unit_[i] = s.axes[i].steps_per_unit;
  backlash_.configure(s);
}

std::int64_t StepPlacement::place(const PlannedSegment& seg, std::int64_t t0,
                                  std::int64_t cursor,
                                  const std::array<std::int64_t, kAxisCount>& pulse_end) {
  const Trapezoid& p = seg.profile;
  std::int64_t end = t0 + whole((p.duration() + seg.dwell_s) / timing_.tick_s, "ticks", seg.loc);
  events_.clear();
  const std::array<std::int64_t, kAxisCount> last_before = last_step_;
  const std::array<bool, kAxisCount> positive_before = positive_;
  for (int i = 0; i < kAxisCount; ++i) {
    next_[i] = stop_[i] = events_.size();
    head_[i] = kNoEvent;
    if (independent_ && independent_->axis() == i) continue;  // it moves on its own
    const std::int64_t target = whole(seg.to[i] * steps_per_unit_[i], "steps", seg.loc);
    const std::int64_t delta = target - position_[i];
    if (delta == 0) continue;
    const bool positive = delta > 0;
    const std::int64_t n = positive ? delta : -delta;
    // The k-th step goes out when the exact position crosses the half step before it:
    // x(f) = x0 + f (x1 - x0) reaches position + sign (k - 1/2) at the fraction below.
    // From a whole step (the usual case) that is f = (k - 1/2) / (x1 - x0); from a point
    // part-way (a segment cut by a hold) the first step comes when it is really due.
    const double x0 = seg.from[i] * steps_per_unit_[i], x1 = seg.to[i] * steps_per_unit_[i];
    const double sign = positive ? 1.0 : -1.0;
    std::int64_t last = last_step_[i];
    // At a reversal the motor first turns through the slack (backlash.hpp): `takeup` more
    // steps, before the load's, that count for nothing.
    const std::int64_t takeup = backlash_.takeup(i, positive);
    for (std::int64_t k = 1; k <= n + takeup; ++k) {
      const double crossing = static_cast<double>(position_[i]) + sign * (k - 0.5);
      const double f = x1 == x0 ? 0.0 : std::clamp((crossing - x0) / (x1 - x0), 0.0, 1.0);
      const double at = takeup == 0 ? p.time_at(f * p.length)
                                    : Backlash::motor_step_time(p, x0, x1, position_[i], positive,
                                                                takeup, backlash_.speed(i), k);
      std::int64_t tick = t0 + std::llround(at / timing_.tick_s);
      tick = std::max(tick, last + timing_.min_period_ticks);
      if (k == 1 && positive != positive_[i]) {
        // The new direction level goes out once the last pulse is over and no earlier than
        // words already sent; the step waits for the setup time after it.
        const std::int64_t dir_tick =
            std::max({cursor, pulse_end[i], tick - timing_.dir_setup_ticks});
        events_.push_back({dir_tick, i, true, positive});
        tick = std::max(tick, dir_tick + timing_.dir_setup_ticks);
      }
      events_.push_back({tick, i, false, positive, k <= takeup});
      last = tick;
    }
    last_step_[i] = last;
    positive_[i] = positive;
    end = std::max(end, last);
    stop_[i] = events_.size();
    head_[i] = events_[next_[i]].tick;  // n > 0: at least one step
  }
  // Each axis's events are in tick order already: next_event() merges the runs (no sort, no
  // allocation). The axes are as before until each event is applied.
  last_step_ = last_before;
  positive_ = positive_before;
  return end;
}

// The interpreter bounds every time and distance a file gives (docs/reliability.md); this
// is the last guard: a count that does not fit ends the run here, located, before a word of
// the segment is sent, rather than wrapping into garbled steps.
std::int64_t StepPlacement::whole(double x, const char* what, const SourceLoc& loc) {
  if (const std::optional<std::int64_t> n = checked_llround(x)) return *n;
  throw GantryError(Diagnostic{
      loc, Severity::Error,
      fmt::format("this segment needs {} {}, beyond what the step generator can place (at most "
                  "2^53); nothing of it was sent",
                  x, what)});
}

void StepPlacement::start_independent(const IndependentMotion& m, std::int64_t tick) {
  if (m.running()) independent_.emplace(m, steps_per_unit_[m.axis], timing_.tick_s, tick);
}

IndependentMotion StepPlacement::end_independent() {
  const IndependentMotion m = independent_->motion();
  independent_.reset();
  return m;
}

// Placed as place() places a path step: never before the words sent, min_period after the
// axis's last step, and a direction change set up dir_setup before its step.
std::optional<StepEvent> StepPlacement::independent_event(
    std::int64_t cursor, const std::array<std::int64_t, kAxisCount>& pulse_end) const {
  const std::optional<IndependentAxis::Step> s = independent_ ? independent_->next() : std::nullopt;
  if (!s) return std::nullopt;
  const int i = independent_->axis();
  const std::int64_t tick = std::max({static_cast<std::int64_t>(std::llround(s->tick)),
                                      last_step_[i] + timing_.min_period_ticks, cursor});
  if (s->positive != positive_[i])
    return StepEvent{std::max({cursor, pulse_end[i], tick - timing_.dir_setup_ticks}), i, true,
                     s->positive};
  return StepEvent{std::max(tick, independent_dir_tick_ + timing_.dir_setup_ticks), i, false,
                   s->positive};
}

void StepPlacement::independent_applied(const StepEvent& e) {
  applied(e);
  if (e.is_dir) {
    independent_dir_tick_ = e.tick;
  } else {
    independent_->taken();
    backlash_.turned(e.axis, e.positive);  // MI takes no slack; its direction is the slack's side
  }
}

void StepPlacement::restart(const Steps6& played) {
  position_ = played;
  last_step_.fill(std::numeric_limits<std::int64_t>::min() / 2);
  positive_.fill(true);  // the levels card.stop() left (as at construction)
  backlash_.forget();    // takeup steps may have been lost with the words not played
}

}  // namespace gantry
