// Holds, halts and resumes on the path (see motion_feeder.hpp for the model).
#include "gantry/step/motion_feeder.hpp"

#include <algorithm>  // min, max
#include <utility>    // exchange

namespace gantry {
namespace {

// The part of `s` between distances a and b along it, with s's profile for its parameters.
PlannedSegment piece(const PlannedSegment& s, double a, double b) {
  PlannedSegment p = s;
  const double length = s.profile.length;
  const Vec6 delta = s.to - s.from;
  if (length > 0) {
    p.from = s.from + delta * (a / length);
    p.to = b >= length ? s.to : s.from + delta * (b / length);
  }
  p.profile.length = std::max(0.0, b - a);
  return p;
}

// From speed `v` over `p`'s length, as fast as p's plan allows, ending no faster than its
// planned exit: the forward pass after a rest.
Trapezoid from_speed(double v, const Trapezoid& p) {
  const double exit = std::min(p.v_exit, ramp_reach(v, p.length, p.accel, p.jerk));
  return Trapezoid::plan(p.length, v, std::max({p.v_cruise, v, exit}), exit, p.accel, p.jerk);
}

}  // namespace

const char* feed_phase_name(FeedPhase p) {
  switch (p) {
    case FeedPhase::Playing:
      return "playing";
    case FeedPhase::Slowing:
      return "slowing";
    case FeedPhase::Held:
      return "held";
    case FeedPhase::Halted:
      return "halted";
  }
  return "?";
}

void MotionFeeder::request_hold(std::int64_t tick, bool pause, bool every_output) {
  every_output_.store(every_output, std::memory_order_relaxed);
  pausing_.store(pause, std::memory_order_relaxed);
  hold_at_.store(tick, std::memory_order_release);
}

void MotionFeeder::request_halt(std::int64_t tick, int cushion) {
  halt_cushion_.store(cushion, std::memory_order_relaxed);
  halt_at_.store(tick, std::memory_order_release);
}

void MotionFeeder::segment(const PlannedSegment& s) {
  switch (phase()) {
    case FeedPhase::Halted:
      return;
    case FeedPhase::Held:
      kept_.push_back({Kept::kSegment, s, nullptr});
      return;
    case FeedPhase::Slowing:
      return slow(s);
    case FeedPhase::Playing:
      break;
  }
  if (catching_up_ && s.profile.length > 0 && carry_ + 1e-9 < s.profile.v_entry) {
    PlannedSegment c = s;  // after a rest: slower than planned until it catches up
    c.profile = from_speed(carry_, s.profile);
    catching_up_ = c.profile.v_exit + 1e-9 < s.profile.v_exit;
    return play(c);
  }
  catching_up_ &= s.profile.length == 0;  // a dwell or an output changes nothing
  const double live = live_factor_.load(std::memory_order_acquire);
  if (live > 0 && s.planned_override != live && s.v_commanded > 0) {
    PlannedSegment r = s;  // planned before the operator's change: re-ramped to it
    r.planned_override = live;
    if (reramp(r, s.profile.v_entry)) return;
  }
  play(s);
}

void MotionFeeder::live_override(double factor) {
  live_factor_.store(factor, std::memory_order_release);
  override_at_.store(0, std::memory_order_release);
}

bool MotionFeeder::rest_stream() {
  if (phase() != FeedPhase::Playing || carry_ > 0 || steps_.independent_moving()) return false;
  steps_.flush();
  return true;
}

// From speed v at the start of `s` (whose planned profile leaves at its exit, the next
// segment's entry) towards the live override's cruise: up at once when it is above v; down
// at the segment's acceleration first when below, then on at that speed. Linear ramps only
// (an S-curve cut mid-ramp would restart its jerk): with a jerk limit it plays as planned.
bool MotionFeeder::reramp(const PlannedSegment& s, double v) {
  const Trapezoid& p = s.profile;
  const double live = live_factor_.load(std::memory_order_acquire);
  if (live <= 0 || s.v_commanded <= 0 || p.length <= 0 || p.jerk > 0) return false;
  const double cruise = std::min(s.v_commanded * live, s.v_machine);
  const double exit = p.v_exit;
  PlannedSegment r = s;
  r.planned_override = live;
  const double target = std::max(cruise, exit);  // never below the next segment's entry
  if (v <= target + 1e-12) {
    r.profile = Trapezoid::plan(p.length, v, std::max(target, v), exit, p.accel, 0);
    play(r);
    return true;
  }
  const double d = ramp_distance(v, target, p.accel, 0);
  if (d > p.length || ramp_distance(target, exit, p.accel, 0) > p.length - d + 1e-12) return false;
  PlannedSegment down = piece(r, 0, d);
  down.profile = Trapezoid::plan(d, v, v, target, p.accel, 0);
  PlannedSegment on = piece(r, d, p.length);
  on.profile = Trapezoid::plan(p.length - d, target, target, exit, p.accel, 0);
  play(down);
  segment(on);  // the first may have been cut by a hold or a halt
  return true;
}

void MotionFeeder::play(const PlannedSegment& s) {
  if (parked_ && (s.independent || s.profile.length > 0 || s.dwell_s > 0)) {
    if (!s.independent) steps_.start_independent(*parked_);  // a new one replaces it
    parked_.reset();
  }
  // While slowing, only a halt can cut; while playing a hold, or the live override.
  const bool playing = phase() == FeedPhase::Playing;
  const bool rerampable = playing && s.v_commanded > 0 && s.profile.length > 0 &&
                          s.profile.jerk <= 0;  // override_at_ is kNever until one comes
  const std::optional<double> cut = steps_.segment_until(
      s, {&halt_at_, playing ? &hold_at_ : nullptr, rerampable ? &override_at_ : nullptr});
  if (!cut) {
    carry_ = s.profile.v_exit;
    return;
  }
  if (halt_at_.load(std::memory_order_acquire) <= steps_.tick()) {
    rest_loc_ = s.loc;
    return halt_now();
  }
  if (hold_at_.load(std::memory_order_acquire) > steps_.tick()) {  // the live override
    override_at_ = steps_.kNever;
    const Trapezoid& p = s.profile;
    const double at = p.distance_at(*cut);
    carry_ = p.speed_at(*cut);
    if (at >= p.length) {
      carry_ = p.v_exit;
      return;
    }
    PlannedSegment rest = piece(s, at, p.length);
    rest.planned_override = live_factor_.load(std::memory_order_acquire);
    rest.profile = Trapezoid::plan(rest.profile.length, carry_, std::max(p.v_cruise, carry_),
                                   p.v_exit, p.accel, 0);  // as planned, if not re-ramped
    if (!reramp(rest, carry_)) play(rest);
    return;
  }
  rest_loc_ = s.loc;
  hold_at_ = steps_.kNever;
  hold_tick_.store(steps_.tick(), std::memory_order_release);
  const Trapezoid& p = s.profile;
  if (s.output > 0 || p.length == 0) {  // at rest already: an output, or a dwell
    PlannedSegment rest = s;
    rest.dwell_s = std::max(0.0, s.dwell_s - *cut);
    return hold_here(rest);
  }
  const double at = p.distance_at(*cut);
  carry_ = p.speed_at(*cut);
  set_phase(FeedPhase::Slowing);
  PlannedSegment rest = piece(s, at, p.length);
  rest.profile.v_entry = carry_;
  slow(rest);
}

// Slows from carry_ along `r`: to rest within it (the rest of it is kept), or to the lowest
// speed its length allows, going on into the next segment.
void MotionFeeder::slow(const PlannedSegment& r) {
  const Trapezoid& p = r.profile;
  // A corner may lower the speed at once by a little (the plan's corner jump): never enter
  // a segment faster than planned.
  carry_ = std::min(carry_, p.v_entry);
  if (r.output > 0 || p.length == 0 || carry_ <= 0) return hold_here(r);
  const double floor = ramp_floor(carry_, p.length, p.accel, p.jerk);
  if (floor > 0) {
    PlannedSegment s = r;
    const double exit = std::min(floor, p.v_exit);
    s.profile = Trapezoid::plan(p.length, carry_, carry_, exit, p.accel, p.jerk);
    return play(s);
  }
  const double d = std::min(p.length, ramp_distance(carry_, 0, p.accel, p.jerk));
  PlannedSegment s = piece(r, 0, d);
  s.profile = Trapezoid::plan(d, carry_, carry_, 0, p.accel, p.jerk);
  play(s);
  if (phase() == FeedPhase::Halted) return;
  hold_here(piece(r, d, p.length));
}

// At rest with `rest` (and everything after it) still to play.
void MotionFeeder::hold_here(const PlannedSegment& rest) {
  rest_loc_ = rest.loc;
  PlannedSegment k = rest;
  if (k.output == 0 && k.profile.length > 0) k.profile = from_speed(0, rest.profile);
  kept_.push_back({Kept::kSegment, k, nullptr});
  settle();
}

void MotionFeeder::settle() {
  carry_ = 0;
  hold_at_ = steps_.kNever;
  if (std::optional<IndependentMotion> m = steps_.rest_independent()) parked_ = m;
  if (pausing_.exchange(false)) {
    const std::uint32_t mask = every_output_.load(std::memory_order_relaxed)
                                   ? 0xFFFu
                                   : pause_mask_.load(std::memory_order_relaxed);
    for (int n = 1; n <= 12; ++n)
      if ((mask >> (n - 1) & 1u) && steps_.output_on(n)) paused_off_ |= 1u << (n - 1);
    switch_outputs(paused_off_, false);
  }
  steps_.flush();  // every word up to here reaches the card: the tool is where it stopped
  set_phase(FeedPhase::Held);
}

void MotionFeeder::switch_outputs(std::uint32_t mask, bool on) {
  if (mask == 0) return;
  for (int n = 1; n <= 12; ++n)
    if (mask >> (n - 1) & 1u) steps_.set_output(n, on);
  steps_.emit_levels();
}

void MotionFeeder::halt_now() {
  if (phase() == FeedPhase::Halted) return;
  for (const Kept& k : kept_) flushes_ += k.kind == Kept::kFlush;
  kept_.clear();
  carry_ = 0;
  halt_at_ = hold_at_ = steps_.kNever;
  parked_.reset();
  paused_off_ = 0;
  steps_.halt(halt_cushion_.exchange(0, std::memory_order_relaxed));
  set_phase(FeedPhase::Halted);
}

void MotionFeeder::flush() {
  switch (phase()) {
    case FeedPhase::Halted:
      ++flushes_;  // abandoned
      return;
    case FeedPhase::Slowing:  // at rest at the stream's end (it always ends at rest)
      settle();
      [[fallthrough]];
    case FeedPhase::Held:
      kept_.push_back({Kept::kFlush, {}, nullptr});
      return;
    case FeedPhase::Playing:
      parked_.reset();  // the stream ends at rest
      steps_.flush();
      ++flushes_;
  }
}

void MotionFeeder::settings_changed(const Settings& s) {
  switch (phase()) {
    case FeedPhase::Halted:
      return;
    case FeedPhase::Slowing:  // new values come after a Stop: at rest by now
      settle();
      [[fallthrough]];
    case FeedPhase::Held:
      kept_.push_back({Kept::kSettings, {}, std::make_shared<const Settings>(s)});
      return;
    case FeedPhase::Playing:
      steps_.settings_changed(s);
  }
}

bool MotionFeeder::flush_kept() const {
  return std::any_of(kept_.begin(), kept_.end(),
                     [](const Kept& k) { return k.kind == Kept::kFlush; });
}

void MotionFeeder::resume() {
  if (phase() != FeedPhase::Held) return;
  std::deque<Kept> replay;
  replay.swap(kept_);
  hold_at_ = steps_.kNever;
  carry_ = 0;
  catching_up_ = true;
  switch_outputs(std::exchange(paused_off_, 0), true);  // on again before anything moves
  set_phase(FeedPhase::Playing);
  // A new hold while replaying keeps the rest again, in order (segment() and the others
  // keep what arrives while held). A card fault part-way abandons what was not played,
  // the item that threw included (its flush was not counted), as a fault in play does.
  for (auto k = replay.begin(); k != replay.end(); ++k) try {
      switch (k->kind) {
        case Kept::kSegment:
          segment(k->seg);
          break;
        case Kept::kSettings:
          settings_changed(*k->settings);
          break;
        case Kept::kFlush:
          flush();
          break;
      }
    } catch (...) {
      for (; k != replay.end(); ++k) flushes_ += k->kind == Kept::kFlush;
      throw;
    }
}

void MotionFeeder::discard() {
  const FeedPhase was = phase();
  if (was != FeedPhase::Held && was != FeedPhase::Halted) return;
  for (const Kept& k : kept_) flushes_ += k.kind == Kept::kFlush;  // abandoned
  kept_.clear();
  carry_ = 0;
  hold_at_ = halt_at_ = steps_.kNever;
  parked_.reset();
  paused_off_ = 0;  // the file ends: they stay off
  if (was == FeedPhase::Halted) steps_.restart();
  set_phase(FeedPhase::Playing);
}

}  // namespace gantry
