// The step generator's wiring: segments through step placement into the word writer, the
// steps logged, the card checked after every block.
#include "gantry/step/step_generator.hpp"

#include <algorithm>  // max, min
#include <cmath>      // llround

#include <fmt/format.h>  // the fault message

namespace gantry {

StepGenerator::StepGenerator(const Settings& settings, Card& card, std::size_t block_words)
    : timing_(StepTiming::from(settings.card)),
      card_(card),
      placement_(settings, timing_),
      lead_(settings, card, block_words),
      writer_(settings, timing_, card, lead_.block_words()),
      log_(std::llround(settings.card.pacer_hz())),
      channel_axis_(settings.drivers.channel_axis) {
  writer_.on_block([this] {
    check_card();
    lead_.after_block(writer_.sent(), [this] { check_card(); });
  });
}

// At rest (the planner stopped first): pending pulses go out, then steps per unit and the
// channel pins change. The step counts stay: the next move goes from them.
void StepGenerator::settings_changed(const Settings& s) {
  flush();
  placement_.settings_changed(s);
  writer_.settings_changed(s, placement_.positive());
  channel_axis_ = s.drivers.channel_axis;
}

void StepGenerator::emit_levels() {
  emit_until(segment_end_);
  emit_until(++segment_end_);
}

// A cushioned stop's words are the card's own: the words written played up to its start,
// then each axis made its first channel's cushion steps.
Steps6 StepGenerator::played_position() const {
  if (const std::optional<CushionPlayed> c = card_.cushion_played())
    if (std::optional<Steps6> p = position_at(c->from)) {
      std::array<bool, kAxisCount> added{};
      for (int k = 0; k < kAxisCount; ++k)
        if (const int axis = channel_axis_[k]; !added[axis]) {
          (*p)[axis] += c->steps[k];
          added[axis] = true;
        }
      return *p;
    }
  return *position_at(card_.ticks_played());
}

void StepGenerator::watch_inputs(const InputWatch& w, std::function<void(const InputEdge&)> fired) {
  writer_.watch(w);
  on_edge_ = w.mask ? std::move(fired) : nullptr;
}

// After each block the card has played up to ticks_played(): steps before it are confirmed.
// A fault stops everything: the rest of the job is dropped, and the error names when the
// card stopped.
void StepGenerator::check_card() {
  const std::uint64_t played = card_.ticks_played();
  // A cushion's words are the card's, not ours: the log confirms ours up to its start (and
  // keeps its history from there, however long the cushion took).
  const std::optional<CushionPlayed> cushion = card_.cushion_played();
  log_.confirm(cushion ? std::min(played, cushion->from) : played);
  while (level_changes_.size() > 1 && level_changes_[1].first <= static_cast<std::int64_t>(played))
    level_changes_.pop_front();
  if (on_block_) on_block_();
  if (on_edge_)
    if (const std::optional<InputEdge> e = card_.watch_fired()) {
      auto fired = std::move(on_edge_);
      on_edge_ = nullptr;
      fired(*e);
    }
  const CardFault f = card_.fault();
  if (f == CardFault::None || faulted_) return;
  faulted_ = true;
  // Where the tool stopped is said by the controller: it knows the operator's frame (a
  // restored or homed origin, the zero), which step counts alone do not.
  std::string detail = card_.fault_detail();
  // Read again: a real card's thread publishes its cushion before its fault, but may have
  // done both since the read above.
  if (const std::optional<CushionPlayed> c = card_.cushion_played()) {
    std::int64_t most = 0;
    for (std::int64_t n : c->steps) most = std::max(most, n < 0 ? -n : n);
    detail += fmt::format("{}cushioned: {} more steps at most after the hit, counted",
                          detail.empty() ? "" : "; ", most);
  }
  throw GantryError(Diagnostic{current_loc_, Severity::Error,
                               fmt::format("{}{}: the card stopped at {:.4f} s", fault_name(f),
                                           detail.empty() ? "" : " (" + detail + ")",
                                           static_cast<double>(played) * timing_.tick_s)});
}

void StepGenerator::segment(const PlannedSegment& seg) {
  segment_until(seg, {});
}

std::optional<double> StepGenerator::segment_until(const PlannedSegment& seg, StopTicks stops) {
  if (faulted_) return std::nullopt;
  current_loc_ = seg.loc;
  warning_ = seg.warning;
  const std::int64_t t0 = segment_end_;
  if (seg.count.moves > 0 && stops.now() > t0) ran_ = seg.count;  // some of it plays
  if (seg.independent) {                                          // at rest, like an output
    if (stops.now() <= t0) return 0.0;
    emit_until(segment_end_);
    start_independent(*seg.independent);
    return std::nullopt;
  }
  if (seg.output > 0) {  // at rest: the words so far keep the old level, one word the new
    if (stops.now() <= t0) return 0.0;
    emit_until(segment_end_);
    set_output(seg.output, seg.output_on);  // checked by SO: it is wired
    emit_levels();
    return std::nullopt;
  }
  if (seg.spindle_rpm) {  // at rest, as an output
    if (stops.now() <= t0) return 0.0;
    emit_until(segment_end_);
    set_spindle_speed(*seg.spindle_rpm);
    emit_levels();
    return std::nullopt;
  }
  writer_.rest_channels(seg.resting_channels);  // squaring a slaved axis (docs/hardware.md)
  const std::int64_t end = placement_.place(seg, t0, writer_.cursor(), writer_.pulse_end());
  // The words go out to the end of the block being filled at most, then the stop ticks are
  // read again: a full block is where the bounded lead waits (CardLead::after_block), and a
  // hold that arrives meanwhile cuts the words at that block's end, not at the next event
  // (a step period later: 0.55 ms at 2 in/s) or after a dwell's next block. So the words
  // generated ahead of the card's clock never exceed the lead, and neither does a hold's
  // latency.
  const auto block = static_cast<std::int64_t>(writer_.block_words());
  const auto block_end = [&] { return writer_.sent() + block; };
  // The events in tick order; a stop tick cuts them: each axis is left as its last played
  // event left it.
  std::int64_t stop_tick = stops.now();
  bool stopped = false;
  while (const StepEvent* e = placement_.next_event()) {
    while (!(stopped = e->tick >= (stop_tick = stops.now())) && e->tick >= block_end())
      emit_until(block_end());  // a full block: the lead may wait here
    if (stopped) break;
    emit_until(e->tick);
    play(*e);
  }
  // What is left has no event (a dwell, the last pulse): it goes out a block at a time, so
  // a stop that comes meanwhile still cuts it (a dwell may last seconds).
  while ((stop_tick = stops.now()) >= end && writer_.cursor() < end)
    emit_until(std::min(end, block_end()));
  if (stop_tick >= end) {
    segment_end_ = end;
    return std::nullopt;
  }
  stop_tick = std::max(stop_tick, std::max(t0, writer_.cursor()));
  emit_until(stop_tick);
  segment_end_ = stop_tick;
  return static_cast<double>(stop_tick - t0) * timing_.tick_s;
}

void StepGenerator::flush() {
  if (faulted_) return;
  rest_independent();
  writer_.finish_pulses(segment_end_);
  segment_end_ = writer_.cursor();  // the next segment starts after the words sent
  if (writer_.write_block()) check_card();
  lead_.rest();
  card_.end_stream();  // at rest: the card may run dry now
}

std::optional<IndependentMotion> StepGenerator::rest_independent() {
  if (!placement_.independent()) return std::nullopt;
  placement_.stop_independent_from(segment_end_);
  while (const std::optional<StepEvent> e =
             placement_.independent_event(writer_.cursor(), writer_.pulse_end())) {
    writer_.emit(e->tick);
    play_independent(*e);
  }
  segment_end_ = std::max(segment_end_, writer_.cursor());
  return placement_.end_independent();
}

void StepGenerator::start_independent(const IndependentMotion& m) {
  rest_independent();
  placement_.start_independent(m, segment_end_);
}

void StepGenerator::halt(int cushion) {
  if (placement_.independent()) placement_.end_independent();  // E-stop: every axis stops at once
  writer_.halt(cushion);
  levels_.switches = 0;  // the card idles with every output off; the next words too (restart)
  level_changes_.clear();
  level_changed();
}

bool StepGenerator::set_output(int n, bool on) {
  if (!writer_.set_output(n, on)) return false;
  const std::uint32_t bit = 1u << (n - 1);
  levels_.switches = on ? levels_.switches | bit : levels_.switches & ~bit;
  level_changed();
  return true;
}

void StepGenerator::set_spindle_speed(double rpm) {
  writer_.set_spindle_speed(rpm);
  levels_.spindle_rpm = rpm;
  level_changed();
}

void StepGenerator::level_changed() {
  level_changes_.emplace_back(writer_.cursor(), levels_);
}

OutputLevels StepGenerator::played_levels() const {
  const auto played = static_cast<std::int64_t>(card_.ticks_played());
  OutputLevels at;  // before the first change: as the card started, all off
  for (const auto& [tick, l] : level_changes_) {
    if (tick > played) break;
    at = l;
  }
  return at;
}

void StepGenerator::restart() {
  const Steps6 played = played_position();
  placement_.restart(played);
  faulted_ = false;
  writer_.restart();
  // From the card's count after it started again: a real card counts from 0 again (the
  // simulated card goes on), and a log left at the old count found no position after it.
  log_.restart(played, writer_.cursor());
  segment_end_ = writer_.cursor();
}

void StepGenerator::play(const StepEvent& e) {
  writer_.apply(e);
  if (!e.is_dir && !e.takeup) log_.record(e.tick, e.axis, e.positive ? 1 : -1);
  placement_.applied(e);
}

void StepGenerator::play_independent(const StepEvent& e) {
  writer_.apply(e);
  if (!e.is_dir) log_.record(e.tick, e.axis, e.positive ? 1 : -1);
  placement_.independent_applied(e);
}

void StepGenerator::emit_until(std::int64_t tick) {
  if (placement_.independent())
    for (std::optional<StepEvent> e;
         (e = placement_.independent_event(writer_.cursor(), writer_.pulse_end())) &&
         e->tick < tick;) {
      writer_.emit(e->tick);
      play_independent(*e);
    }
  writer_.emit(tick);
}

}  // namespace gantry
