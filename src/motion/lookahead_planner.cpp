// Look-ahead planning over a bounded queue of moves.
//
// Each held block k has a corner speed limit c_k at its start (corner_speed with the block
// before it, or its rest speed after a stop), a length l_k and an acceleration a_k along its
// path. Speeds are planned in two passes, as in grbl's planner:
//
//   backward: b_k = min(c_k, sqrt(b_{k+1}^2 + 2 a_k l_k)), with the tail ending at 0,
//             so that from every entry speed the machine can still stop by the tail;
//   forward:  e_k = min(b_k, sqrt(e_{k-1}^2 + 2 a_{k-1} l_{k-1})),
//             so that every entry speed can be reached from the one before.
// (With a jerk limit the square roots become the S-curve reach, ramp_reach.)
//
// A block's exit is the next block's entry; its profile is the trapezoid between them.
// Ending at 0 while streaming is what makes releasing the front safe: whatever comes later,
// the plan already held can stop.
//
// When the passes run. The bounds b_k are the fixed point of the backward recursion over the
// blocks held, whenever and in whatever steps it is computed; the entries e_k likewise follow
// from the b_k and the front's entry. So a backward pass from the tail stops at the first
// bound it leaves unchanged (the blocks before it keep theirs), and the passes need to run
// only when a result is used: when the front is sent, which needs its successor's entry.
// That entry cannot change while a block beyond it is "settled": at its corner limit
// (b_k = c_k) whatever blocks come after (grbl's "planned" pointer). Without a jerk limit the
// reach rises with the speed it starts from, so bounds only rise as blocks are added (the
// tail's exit rises from 0) and a block at its corner limit is settled. With one, the reach
// falls with the start speed u while the gain w exceeds 2u (ramp_reach_least), so a pass also
// carries the least bound each block can ever fall to (from a tail exit of 0 up), and a block
// is settled once that is its corner limit. The backward pass thus runs only when no settled
// block guards the front, over the blocks added since the last pass (each once) and the ramp
// down to rest at the old tail; the forward pass runs once per block, as it comes to the
// front. Re-planning after every block added instead recomputes the whole ramp down at the
// tail each time: on an adaptive-clearing path with S-curve ramps, about 21 bounds and 21
// entries per block, each a cubic. Both orders give the same plan, bit for bit: the same
// recursions over the same values (set_eager keeps the eager order for tests and benches).
#include "gantry/motion/lookahead_planner.hpp"

#include <algorithm>  // min, max, clamp
#include <cmath>      // abs, M_PI
#include <vector>

#include "gantry/canon/arc_geometry.hpp"    // arc_chords
#include "gantry/motion/corner_speed.hpp"  // corner_speed, rest_speed
#include "gantry/motion/path_limits.hpp"   // path_limits

namespace gantry {
namespace {

constexpr size_t kTrailPoints = 4096;  // path points kept for SB3's minimum distance to check

}  // namespace

LookAheadPlanner::LookAheadPlanner(const Settings& settings, SegmentSink& out)
    : settings_(settings), out_(out) {}

double LookAheadPlanner::reach(double v, const Block& b) const {
  return ramp_reach(v, b.length, b.accel, settings_.planner.jerk);
}

double LookAheadPlanner::least_reach(double v, const Block& b) const {
  const double j = settings_.planner.jerk;
  if (j <= 0) return reach(v, b);  // rises with v, rounded as well: exact
  // Later passes round differently from this bound: keep well clear of it.
  return ramp_reach_least(v, b.length, b.accel, j) * (1 - 1e-9);
}

void LookAheadPlanner::move(const CanonMove& m) {
  // During a hold, a dwell or an output cannot go out before the held moves ahead of it:
  // it and everything after it wait in arrival order until resume().
  const bool at_rest = m.kind == MoveKind::Output || m.kind == MoveKind::Independent ||
                       m.kind == MoveKind::SpindleSpeed;
  if (held_ && (!deferred_.empty() || m.kind == MoveKind::Dwell || at_rest)) {
    deferred_.push_back(m);
    return;
  }
  if (m.kind == MoveKind::Stop) {  // the next corner ramps fully down and up again
    punctuated_ = true;
    return;
  }
  if (m.kind == MoveKind::Dwell || at_rest) {
    // An output switches with the machine at rest, between the moves around it; a dwell
    // waits there. The next move's start counts this stop's jump, less what the wait lets
    // the axes accelerate (start_after_stop): an output takes no time.
    stop();
    rested_s_ += m.dwell_s;
    PlannedSegment seg;
    seg.from = seg.to = m.to;
    seg.dwell_s = m.dwell_s;
    seg.warning = m.warning;
    seg.output = m.kind == MoveKind::Output ? m.output : 0;
    seg.output_on = m.output_on;
    if (m.kind == MoveKind::Independent) seg.independent = m.independent;
    if (m.kind == MoveKind::SpindleSpeed) seg.spindle_rpm = m.spindle_rpm;
    seg.loc = m.loc;
    seg.count = m.count;
    planned_time_ += m.dwell_s;
    out_.segment(seg);
    return;
  }
  if (m.kind == MoveKind::Arc) return arc(m);
  const PathLimits lim = path_limits(m, settings_);
  if (lim.length == 0) return;
  Block b;
  b.from = m.from;
  b.to = m.to;
  b.length = lim.length;
  b.unit = (m.to - m.from) / lim.length;
  b.v_commanded = nominal_path_speed(m.to - m.from, m.speeds);
  b.v_machine = lim.machine_speed;
  b.accel = lim.accel;
  b.speed_class = m.speed_class;
  b.resting_channels = m.resting_channels;
  b.loc = m.loc;
  b.count = m.count;
  b.punctuated = punctuated_;
  punctuated_ = false;
  b.u_in_long = q_.empty() ? b.unit : incoming_direction(b.from, q_.back().unit);
  set_speeds(b, q_.empty() ? nullptr : &q_.back());
  add(std::move(b));
}

// Arcs run as chords. SB3 runs a circle or an arc (SB3 L1240: "a circle or arc") of a circle
// smaller than the small-circle diameter at the ramp speed rather than the move speed: a
// circle cut into pieces by tabs keeps the speed of the whole circle.
void LookAheadPlanner::arc(const CanonMove& m) {
  CanonMove chord = m;
  chord.kind = MoveKind::Line;
  const bool small_circle = settings_.planner.mode == PlannerMode::SB3 &&
                            2 * arc_radius(m) < settings_.ramps.small_circle;
  if (small_circle) {
    const GroupSpeeds& ramp = m.speed_class == SpeedClass::Jog ? settings_.ramps.jog_ramp_speed
                                                               : settings_.ramps.move_ramp_speed;
    chord.speeds = {std::min(m.speeds.xy, ramp.xy), std::min(m.speeds.z, ramp.z),
                    std::min(m.speeds.a, ramp.a), std::min(m.speeds.b, ramp.b),
                    std::min(m.speeds.c, ramp.c)};
  }
  for (const Vec6& p : arc_chords(m, settings_.planner.chord_tolerance)) {
    chord.to = p;
    move(chord);
    chord.from = p;
  }
}

void LookAheadPlanner::set_speeds(Block& b, const Block* prev) const {
  b.v_max = std::min(b.v_commanded * override_, b.v_machine);
  b.rest = std::min(rest_speed(b.unit, b.speed_class == SpeedClass::Jog, settings_), b.v_max);
  if (!prev) {  // from rest, right after the last stop unless a dwell came between
    b.max_entry = std::min(b.rest, start_after_stop(stop_velocity_, b.unit, rested_s_, settings_));
    return;
  }
  Junction j;
  j.u_in = prev->unit;
  j.u_out = b.unit;
  j.u_in_long = b.u_in_long;
  j.v_in = prev->v_max;
  j.v_out = b.v_max;
  j.rest_in = prev->rest;
  j.rest_out = b.rest;
  j.len_in = prev->length;
  j.len_out = b.length;
  j.a_in = prev->accel;
  j.a_out = b.accel;
  j.jog_in = prev->speed_class == SpeedClass::Jog;
  j.jog_out = b.speed_class == SpeedClass::Jog;
  j.punctuated = b.punctuated;
  b.max_entry = corner_speed(j, settings_);
}

void LookAheadPlanner::feed_override(double factor) {
  override_ = std::clamp(factor, 0.01, 2.0);  // feed_override.min and max: 1 % to 200 %
  // Every held block gets its new speeds. When they are lower, the machine, already moving
  // at the front's locked entry speed, can only slow down at its acceleration: the speed
  // it can get down to by each block (`floor`) stays allowed there. The old plan was at or
  // above that floor, so the floor is within every corner's old limit.
  double floor = front_locked_ && !q_.empty() ? q_.front().entry : 0;
  for (size_t k = 0; k < q_.size(); ++k) {
    Block& b = q_[k];
    const double old_max_entry = k == 0 ? b.entry : b.max_entry;
    set_speeds(b, k == 0 || b.from_rest ? nullptr : &q_[k - 1]);
    if (floor > 0) {
      b.max_entry = std::max(b.max_entry, std::min(floor, old_max_entry));
      b.v_max = std::max(b.v_max, b.max_entry);
    }
    floor = ramp_floor(floor, b.length, b.accel, settings_.planner.jerk);
    b.back = -1;  // bounds may fall as well as rise: re-plan everything held
  }
  settled_ = planned_ = 0;
  forwarded_ = std::min<size_t>(forwarded_, front_locked_ ? 1 : 0);
  if (eager_) replan_all();
  release();
}

void LookAheadPlanner::feedhold() {
  if (held_) return;
  held_ = true;
  // From the speed the front is entered at, slow down as fast as each block allows, with
  // linear ramps (the shortest stop; S-curve ramps would stretch it). That is never faster
  // than the plan anywhere (the plan cannot slow down faster), so every corner is passed
  // within its limit, and the machine is at rest before the moves held run out.
  double v = front_locked_ && !q_.empty() ? q_.front().entry : 0;
  while (v > 0) {
    Block& b = q_.front();
    const double stop_at = ramp_distance(v, 0, b.accel, 0);
    b.entry = v;
    b.v_max = v;               // slow down only
    if (stop_at < b.length) {  // it stops inside this block: split the block there
      Block rest = b;
      b.to = b.from + b.unit * stop_at;
      b.length = stop_at;
      rest.from = b.to;
      rest.length -= stop_at;
      emit_front(0, 0);
      q_.push_front(std::move(rest));
      break;
    }
    v = ramp_floor(v, b.length, b.accel, 0);
    emit_front(v, 0);
  }
  // What is left starts from rest once resumed (feed_override re-plans it all).
  if (!q_.empty()) q_.front().from_rest = true;
  front_locked_ = false;
  settled_ = planned_ = forwarded_ = 0;
  held_length_ = 0;
  for (size_t k = 1; k < q_.size(); ++k) held_length_ += q_[k].length;
}

void LookAheadPlanner::resume() {
  if (!held_) return;
  held_ = false;
  feed_override(override_);  // re-plans what was held, the front from rest
  std::vector<CanonMove> waiting;
  waiting.swap(deferred_);
  for (const CanonMove& m : waiting) move(m);
}

// The direction from the path point at least min_distance back to `at` (SB3 measures
// direction changes over that much path, so a curve of tiny segments reads as a turn).
Vec6 LookAheadPlanner::incoming_direction(const Vec6& at, const Vec6& fallback) const {
  if (settings_.ramps.min_distance <= 0 || trail_.empty()) return fallback;
  const Vec6 d = at - trail_.front().first;
  const double n = d.norm();
  return n > 1e-12 ? Vec6(d / n) : fallback;
}

void LookAheadPlanner::add(Block b) {
  if (trail_.empty()) trail_.emplace_back(b.from, travelled_);
  travelled_ += b.length;
  trail_.emplace_back(b.to, travelled_);
  // Keep the newest point at least min_distance back as the front.
  while (trail_.size() > kTrailPoints ||
         (trail_.size() >= 2 && travelled_ - trail_[1].second >= settings_.ramps.min_distance))
    trail_.pop_front();

  // The longest stop at the highest speed feed override could allow.
  const double v_top = std::min(2 * b.v_commanded, b.v_machine);
  stop_distance_ =
      std::max(stop_distance_, ramp_distance(v_top, 0, b.accel, settings_.planner.jerk));
  if (!q_.empty()) held_length_ += b.length;
  b.back = -1;  // not planned yet
  q_.push_back(std::move(b));
  most_held_ = std::max(most_held_, q_.size());
  if (eager_) replan_all();
  release();  // streaming: the plan ends at rest after the last block held
}

void LookAheadPlanner::release() {
  if (held_) return;  // the machine waits at rest; moves keep arriving
  const size_t lookahead = static_cast<size_t>(settings_.planner.lookahead);
  while (q_.size() > 64 * lookahead || (q_.size() > lookahead && held_length_ >= stop_distance_))
    emit_front(entry(1));
}

bool LookAheadPlanner::release_front() {
  if (held_ || q_.empty()) return false;
  emit_front(q_.size() > 1 ? entry(1) : 0.0);  // the tail ends at rest
  if (q_.empty()) {                              // at rest: as after a stop
    held_length_ = 0;
    trail_.clear();
  }
  return true;
}

void LookAheadPlanner::backward(double tail_exit) {
  const size_t n = q_.size();
  const size_t first = front_locked_ ? 1 : 0;
  double exit = tail_exit;
  size_t changed = n;
  double least = 0;  // the least each bound can fall to, whatever comes after the tail
  bool settled = false;
  for (size_t k = n; k-- > first;) {
    Block& b = q_[k];
    const double bound = std::min(b.max_entry, reach(exit, b));
    if (k + 1 < n && bound == b.back) break;  // nothing before it changes either
    ++replanned_;
    b.back = bound;
    exit = bound;
    changed = k;
    if (!settled && !eager_) {  // the settled block nearest the tail guards all before it
      least = std::min(b.max_entry, least_reach(least, b));
      settled = least == b.max_entry;
      if (settled) settled_ = std::max(settled_, k + 1);
    }
  }
  planned_ = n;
  forwarded_ = std::min(forwarded_, changed);
}

void LookAheadPlanner::forward(size_t k) {
  for (; forwarded_ <= k; ++forwarded_) {
    Block& b = q_[forwarded_];
    if (forwarded_ == 0) {
      b.entry = b.back;
    } else {
      const Block& p = q_[forwarded_ - 1];
      b.entry = std::min(b.back, reach(p.entry, p));
    }
  }
}

double LookAheadPlanner::entry(size_t k) {
  if (settled_ <= k && planned_ < q_.size()) backward(0);
  forward(k);
  return q_[k].entry;
}

void LookAheadPlanner::replan_all() {
  if (q_.empty()) return;
  backward(0);
  forward(q_.size() - 1);
}

void LookAheadPlanner::emit_front(double exit, double jerk) {
  Block& b = q_.front();
  PlannedSegment seg;
  seg.from = b.from;
  seg.to = b.to;
  // SB3 runs short moves (under the minimum distance to check) at a steady speed instead
  // of speeding up and slowing down within each; from rest to rest there is no such speed.
  const double steady_speed = std::max(b.entry, exit);
  const bool steady = settings_.planner.mode == PlannerMode::SB3 &&
                      b.length < settings_.ramps.min_distance && steady_speed > 0;
  const double cruise = steady ? steady_speed : b.v_max;
  seg.profile = Trapezoid::plan(b.length, b.entry, cruise, exit, b.accel, jerk);
  seg.speed_class = b.speed_class;
  seg.resting_channels = b.resting_channels;
  seg.v_commanded = steady || jerk != settings_.planner.jerk ? 0 : b.v_commanded;
  seg.v_machine = b.v_machine;
  seg.planned_override = override_;
  seg.loc = b.loc;
  seg.count = b.count;
  planned_time_ += seg.profile.duration();
  stop_velocity_ = b.unit * exit;
  rested_s_ = 0;
  out_.segment(seg);
  q_.pop_front();
  for (size_t* i : {&settled_, &planned_, &forwarded_})
    if (*i > 0) --*i;  // the counts of front blocks shift with the queue
  if (!q_.empty()) held_length_ -= q_.front().length;
  front_locked_ = !q_.empty();
}

// The machine stops from the rest speed (SB3) even when the next move follows on the card's
// next tick (after a sync: PAUSE, a probe, reading an input): that move's start is what
// keeps the two speed jumps together within the corner jump (set_speeds, start_after_stop).
void LookAheadPlanner::stop() {
  if (held_) return;  // the held moves wait for resume()
  if (!q_.empty()) {
    // The last block may end at its rest speed (SB3 stops from the ramp speed).
    const double end = q_.back().rest;
    backward(end);
    forward(q_.size() - 1);
    while (q_.size() > 1) emit_front(q_[1].entry);
    const Block& last = q_.front();
    emit_front(std::min(end, reach(last.entry, last)));
  }
  front_locked_ = false;
  held_length_ = 0;
  trail_.clear();
}

void LookAheadPlanner::settings_changed(const Settings& s) {
  stop();  // what is planned keeps the values it was planned with
  settings_ = s;
  out_.settings_changed(s);
}

void LookAheadPlanner::flush() {
  stop();
  out_.flush();
}

}  // namespace gantry
