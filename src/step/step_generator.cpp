// Step placement on the tick clock and packing into pulse words.
#include "gantry/step/step_generator.hpp"

#include <algorithm>  // max, min
#include <cmath>      // llround, ceil
#include <limits>     // numeric_limits

#include <fmt/format.h>  // the fault message

#include "gantry/core/bounded.hpp"  // checked_llround

namespace gantry {

StepTiming StepTiming::from(const CardSettings& card) {
  StepTiming t;
  t.tick_s = 1.0 / card.pacer_hz();
  auto ticks = [&](double us) {
    return static_cast<std::int64_t>(std::ceil(us * 1e-6 / t.tick_s - 1e-9));
  };
  t.pulse_ticks = std::max<std::int64_t>(1, ticks(card.step_pulse_us));
  t.dir_setup_ticks = ticks(card.dir_setup_us);
  t.min_period_ticks = t.pulse_ticks + 1;
  return t;
}

StepGenerator::StepGenerator(const Settings& settings, Card& card, std::size_t block_words)
    : pins_(PinMap::from(settings.pins, settings.drivers.channel_axis)),
      timing_(StepTiming::from(settings.card)),
      card_(card),
      block_words_(block_words),
      roles_(input_roles(settings)) {  // the card has them from the same profile
  for (int i = 0; i < kAxisCount; ++i) steps_per_unit_[i] = settings.axes[i].steps_per_unit;
  positive_.fill(true);
  last_step_.fill(std::numeric_limits<std::int64_t>::min() / 2);
  pulse_end_.fill(0);
  level_word_ = pins_.idle_word();
  block_.reserve(block_words_);
  if (settings.outputs.charge_pump_bit >= 0) {
    pump_mask_ = 1u << settings.outputs.charge_pump_bit;
    pump_half_ticks_ = std::max<std::int64_t>(
        1, std::llround(settings.card.pacer_hz() / (2 * settings.outputs.charge_pump_hz)));
  }
  if (settings.outputs.spindle_bit >= 0) spindle_mask_ = 1u << settings.outputs.spindle_bit;
  if (settings.spindle.pwm_bit >= 0) {
    pwm_mask_ = 1u << settings.spindle.pwm_bit;
    pwm_period_ticks_ =
        std::max<std::int64_t>(1, std::llround(settings.card.pacer_hz() / settings.spindle.pwm_hz));
    max_rpm_ = settings.spindle.max_rpm;
  }
  aux_bits_ = settings.outputs.aux_bits;
  step_log_.resize(4096);
  history_ticks_ = std::llround(settings.card.pacer_hz());
}

// At rest (the planner stopped first): pending pulses go out, then steps per unit and the
// channel pins change. The step counts stay: the next move goes from them.
void StepGenerator::settings_changed(const Settings& s) {
  flush();
  for (int i = 0; i < kAxisCount; ++i) steps_per_unit_[i] = s.axes[i].steps_per_unit;
  std::uint32_t old_lines = 0;
  for (const AxisPins& a : pins_.axes) old_lines |= a.step_mask | a.dir_mask;
  pins_ = PinMap::from(s.pins, s.drivers.channel_axis);
  card_.calibration_changed(s);
  roles_ = input_roles(s);
  set_card_trips();
  level_word_ &= ~old_lines;
  for (int i = 0; i < kAxisCount; ++i) {
    if (pins_.axes[i].step_active_low) level_word_ |= pins_.axes[i].step_mask;
    level_word_ |= pins_.dir_bits(i, positive_[i]);
  }
}

void StepGenerator::set_card_trips() {
  card_.set_trips(roles_.estop, roles_.limits.without(watch_mask_));
}

void StepGenerator::set_spindle(bool on) {
  level_word_ = on ? level_word_ | spindle_mask_ : level_word_ & ~spindle_mask_;
}

void StepGenerator::set_spindle_speed(double rpm) {
  const double duty = std::clamp(rpm / max_rpm_, 0.0, 1.0);
  pwm_high_ticks_ = pwm_mask_ ? std::llround(duty * static_cast<double>(pwm_period_ticks_)) : 0;
}

bool StepGenerator::set_output(int n, bool on) {
  if (n < 1 || n > static_cast<int>(aux_bits_.size()) || aux_bits_[n - 1] < 0) return false;
  const std::uint32_t mask = 1u << aux_bits_[n - 1];
  level_word_ = on ? level_word_ | mask : level_word_ & ~mask;
  return true;
}

void StepGenerator::emit_levels() {
  emit_until(segment_end_);
  emit_until(++segment_end_);
}

bool StepGenerator::output_on(int n) const {
  if (n < 1 || n > static_cast<int>(aux_bits_.size()) || aux_bits_[n - 1] < 0) return false;
  return (level_word_ >> aux_bits_[n - 1] & 1u) != 0;
}

Steps6 StepGenerator::played_position() const {
  return *position_at(card_.ticks_played());
}

// From the confirmed counts: back over the history kept, or on over the steps not confirmed.
std::optional<Steps6> StepGenerator::position_at(std::uint64_t tick) const {
  const auto t = static_cast<std::int64_t>(tick);
  if (t < history_from_) return std::nullopt;  // older than the history kept
  Steps6 p = confirmed_;
  const std::size_t n = step_log_.size();
  std::size_t k = log_played_;
  while (k != log_begin_) {
    const StepRecord& r = step_log_[(k + n - 1) % n];
    if (r.tick < t) break;
    p[r.axis] -= r.delta;
    k = (k + n - 1) % n;
  }
  for (k = log_played_; k != log_end_; k = (k + 1) % n) {
    const StepRecord& r = step_log_[k];
    if (r.tick >= t) break;
    p[r.axis] += r.delta;
  }
  return p;
}

void StepGenerator::watch_inputs(const InputWatch& w, std::function<void(const InputEdge&)> fired) {
  watch_mask_ = w.mask;
  set_card_trips();
  card_.watch(w);
  on_edge_ = w.mask ? std::move(fired) : nullptr;
}

// After each block the card has played up to ticks_played(): steps before it are confirmed.
// A fault stops everything: the rest of the job is dropped, and the error names where the
// tool stopped, counted from the pulses the card actually played.
// Confirmed steps stay as history for about a second of ticks: an input edge found late (a
// card that samples its inputs in its own thread) is still placed exactly.
void StepGenerator::check_card() {
  const std::uint64_t played = card_.ticks_played();
  const std::size_t n = step_log_.size();
  while (log_played_ != log_end_ &&
         static_cast<std::uint64_t>(step_log_[log_played_].tick) < played) {
    confirmed_[step_log_[log_played_].axis] += step_log_[log_played_].delta;
    log_played_ = (log_played_ + 1) % n;
  }
  const auto keep_from = static_cast<std::int64_t>(played) - history_ticks_;
  while (log_begin_ != log_played_ && step_log_[log_begin_].tick < keep_from) {
    log_begin_ = (log_begin_ + 1) % n;
    history_from_ = keep_from;
  }
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
  const Steps6 at = played_position();
  std::string where;  // the message is built once, on the way out of a run
  for (int i = 0; i < kAxisCount; ++i)
    if (at[i] != 0 || i < 3)
      where += fmt::format(" {}={:.4f}", static_cast<char>(kAxisLetters[i] - 'a' + 'A'),
                           static_cast<double>(at[i]) / steps_per_unit_[i]);
  const std::string detail = card_.fault_detail();
  throw GantryError(Diagnostic{
      current_loc_, Severity::Error,
      fmt::format("{}{}: the card stopped at {:.4f} s; the tool is at{} (the pulses played)",
                  fault_name(f), detail.empty() ? "" : " (" + detail + ")",
                  static_cast<double>(played) * timing_.tick_s, where)});
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
  if (seg.independent) {  // at rest, like an output
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
  const Trapezoid& p = seg.profile;
  std::int64_t end = t0 + whole((p.duration() + seg.dwell_s) / timing_.tick_s, "ticks");
  events_.clear();
  std::array<std::size_t, kAxisCount> next{}, stop{};  // each axis's run of events
  const std::array<std::int64_t, kAxisCount> last_before = last_step_;
  const std::array<bool, kAxisCount> positive_before = positive_;
  for (int i = 0; i < kAxisCount; ++i) {
    next[i] = stop[i] = events_.size();
    if (independent_ && independent_->axis() == i) continue;  // it moves on its own
    const std::int64_t target = whole(seg.to[i] * steps_per_unit_[i], "steps");
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
    for (std::int64_t k = 1; k <= n; ++k) {
      const double crossing = static_cast<double>(position_[i]) + sign * (k - 0.5);
      const double f = x1 == x0 ? 0.0 : std::clamp((crossing - x0) / (x1 - x0), 0.0, 1.0);
      std::int64_t tick = t0 + std::llround(p.time_at(f * p.length) / timing_.tick_s);
      tick = std::max(tick, last + timing_.min_period_ticks);
      if (k == 1 && positive != positive_[i]) {
        // The new direction level goes out once the last pulse is over and no earlier than
        // words already sent; the step waits for the setup time after it.
        const std::int64_t dir_tick =
            std::max({cursor_, pulse_end_[i], tick - timing_.dir_setup_ticks});
        events_.push_back({dir_tick, i, true, positive});
        tick = std::max(tick, dir_tick + timing_.dir_setup_ticks);
      }
      events_.push_back({tick, i, false, positive});
      last = tick;
    }
    last_step_[i] = last;
    positive_[i] = positive;
    end = std::max(end, last);
    stop[i] = events_.size();
  }
  // Each axis's events are in tick order already: merge the runs (no sort, no allocation).
  // Within a tick the lower axis goes first, and an axis's direction change before its step.
  // A stop tick cuts the merge: each axis is left as its last played event left it.
  last_step_ = last_before;
  positive_ = positive_before;
  std::int64_t stop_tick = stops.now();
  while (true) {
    int best = -1;
    for (int i = 0; i < kAxisCount; ++i)
      if (next[i] < stop[i] && (best < 0 || events_[next[i]].tick < events_[next[best]].tick))
        best = i;
    if (best < 0) break;
    const Event& e = events_[next[best]++];
    if (e.tick >= (stop_tick = stops.now())) break;
    emit_until(e.tick);
    apply(e);
    if (e.is_dir)
      positive_[e.axis] = e.positive;
    else
      last_step_[e.axis] = e.tick;
  }
  // What is left has no event (a dwell, the last pulse): it goes out a block at a time, so
  // a stop that comes meanwhile still cuts it (a dwell may last seconds).
  while ((stop_tick = stops.now()) >= end && cursor_ < end)
    emit_until(std::min(end, cursor_ + static_cast<std::int64_t>(block_words_)));
  if (stop_tick >= end) {
    segment_end_ = end;
    return std::nullopt;
  }
  stop_tick = std::max(stop_tick, std::max(t0, cursor_));
  emit_until(stop_tick);
  segment_end_ = stop_tick;
  return static_cast<double>(stop_tick - t0) * timing_.tick_s;
}

// The interpreter bounds every time and distance a file gives (docs/reliability.md); this
// is the last guard: a count that does not fit ends the run here, located, before a word of
// the segment is sent, rather than wrapping into garbled steps.
std::int64_t StepGenerator::whole(double x, const char* what) const {
  if (const std::optional<std::int64_t> n = checked_llround(x)) return *n;
  throw GantryError(Diagnostic{
      current_loc_, Severity::Error,
      fmt::format("this segment needs {} {}, beyond what the step generator can place (at most "
                  "2^53); nothing of it was sent",
                  x, what)});
}

void StepGenerator::flush() {
  if (faulted_) return;
  rest_independent();
  std::int64_t end = segment_end_;
  for (std::int64_t pe : pulse_end_) end = std::max(end, pe);
  emit_until(end);
  // A pulse ending exactly here needs the idle word itself sent, or its line stays active.
  for (std::int64_t pe : pulse_end_)
    if (pe == cursor_ && cursor_ > 0) {
      emit_until(cursor_ + 1);
      break;
    }
  segment_end_ = cursor_;  // the next segment starts after the words sent
  if (!block_.empty()) {
    card_.write(block_);
    block_.clear();
    check_card();
  }
  card_.end_stream();  // at rest: the card may run dry now
}

std::optional<IndependentMotion> StepGenerator::rest_independent() {
  if (!independent_) return std::nullopt;
  independent_->stop_from(segment_end_);
  while (const std::optional<Event> e = independent_event()) {
    emit_words(e->tick);
    play_independent(*e);
  }
  segment_end_ = std::max(segment_end_, cursor_);
  const IndependentMotion m = independent_->motion();
  independent_.reset();
  return m;
}

void StepGenerator::start_independent(const IndependentMotion& m) {
  rest_independent();
  if (m.running()) independent_.emplace(m, steps_per_unit_[m.axis], timing_.tick_s, segment_end_);
}

// Placed as segment_until places a path step: never before the words sent, min_period
// after the axis's last step, and a direction change set up dir_setup before its step.
std::optional<StepGenerator::Event> StepGenerator::independent_event() const {
  const std::optional<IndependentAxis::Step> s = independent_ ? independent_->next() : std::nullopt;
  if (!s) return std::nullopt;
  const int i = independent_->axis();
  const std::int64_t tick = std::max({static_cast<std::int64_t>(std::llround(s->tick)),
                                      last_step_[i] + timing_.min_period_ticks, cursor_});
  if (s->positive != positive_[i])
    return Event{std::max({cursor_, pulse_end_[i], tick - timing_.dir_setup_ticks}), i, true,
                 s->positive};
  return Event{std::max(tick, independent_dir_tick_ + timing_.dir_setup_ticks), i, false,
               s->positive};
}

void StepGenerator::play_independent(const Event& e) {
  apply(e);
  if (e.is_dir) {
    positive_[e.axis] = e.positive;
    independent_dir_tick_ = e.tick;
  } else {
    last_step_[e.axis] = e.tick;
    independent_->taken();
  }
}

void StepGenerator::halt() {
  independent_.reset();  // E-stop: every axis stops at once
  if (!block_.empty()) card_.write(block_);
  block_.clear();
  card_.stop(pins_.idle_word());  // outputs off, as an E-stop must
}

void StepGenerator::restart() {
  position_ = confirmed_ = played_position();
  log_begin_ = log_played_ = log_end_ = 0;
  history_from_ = static_cast<std::int64_t>(card_.ticks_played());
  pulse_end_.fill(0);
  last_step_.fill(std::numeric_limits<std::int64_t>::min() / 2);
  positive_.fill(true);  // the levels card.stop() left (as at construction)
  level_word_ = pins_.idle_word();
  faulted_ = false;
  card_.start(1.0 / timing_.tick_s);
  cursor_ = segment_end_ = static_cast<std::int64_t>(card_.ticks_played());  // its new count
}

void StepGenerator::apply(const Event& e) {
  const AxisPins& ap = pins_.axes[e.axis];
  if (e.is_dir) {
    level_word_ = (level_word_ & ~ap.dir_mask) | pins_.dir_bits(e.axis, e.positive);
    return;
  }
  pulse_end_[e.axis] = e.tick + timing_.pulse_ticks;
  position_[e.axis] += e.positive ? 1 : -1;
  if ((log_end_ + 1) % step_log_.size() == log_begin_) {
    // Full: the card's queue and the history hold more steps than ever before. Grow
    // (doubling, so this happens a few times per job at most), keeping the ring's order.
    std::vector<StepRecord> bigger;
    bigger.reserve(step_log_.size() * 2);
    std::size_t played = 0;
    for (std::size_t k = log_begin_; k != log_end_; k = (k + 1) % step_log_.size()) {
      if (k == log_played_) played = bigger.size();
      bigger.push_back(step_log_[k]);
    }
    if (log_played_ == log_end_) played = bigger.size();
    log_begin_ = 0;
    log_played_ = played;
    log_end_ = bigger.size();
    bigger.resize(step_log_.size() * 2);
    step_log_ = std::move(bigger);
  }
  step_log_[log_end_] = {e.tick, e.axis, e.positive ? 1 : -1};
  log_end_ = (log_end_ + 1) % step_log_.size();
}

std::uint32_t StepGenerator::word_at(std::int64_t tick) const {
  std::uint32_t w = level_word_;
  for (int i = 0; i < kAxisCount; ++i)
    if (tick < pulse_end_[i]) w ^= pins_.axes[i].step_mask;  // active = not idle
  return w;
}

void StepGenerator::emit_until(std::int64_t tick) {
  for (std::optional<Event> e; (e = independent_event()) && e->tick < tick;) {
    emit_words(e->tick);
    play_independent(*e);
  }
  emit_words(tick);
}

void StepGenerator::emit_words(std::int64_t tick) {
  while (cursor_ < tick) {
    // The word only changes where a pulse ends; emit up to the next such tick in one run.
    std::int64_t next = tick;
    for (std::int64_t pe : pulse_end_)
      if (pe > cursor_ && pe < next) next = pe;
    write_run(word_at(cursor_), next - cursor_);
    cursor_ = next;
  }
}

// `count` words from cursor_ on. The charge pump's bit flips every pump_half_ticks_ ticks,
// and the spindle speed's bit is high for the first pwm_high_ticks_ of each period (both by
// the tick's own number, so the square waves are unbroken across runs and blocks).
void StepGenerator::write_run(std::uint32_t word, std::int64_t count) {
  std::int64_t tick = cursor_;
  while (count > 0) {
    const auto room = static_cast<std::int64_t>(block_words_ - block_.size());
    std::int64_t n = std::min(room, count);
    std::uint32_t w = word;
    if (pump_mask_) {
      const std::int64_t phase = tick / pump_half_ticks_;
      n = std::min(n, (phase + 1) * pump_half_ticks_ - tick);
      if (phase & 1) w |= pump_mask_;
    }
    if (pwm_high_ticks_ > 0) {
      const std::int64_t phase = tick % pwm_period_ticks_;
      const bool high = phase < pwm_high_ticks_;
      n = std::min(n, (high ? pwm_high_ticks_ : pwm_period_ticks_) - phase);
      if (high) w |= pwm_mask_;
    }
    block_.insert(block_.end(), static_cast<std::size_t>(n), w);
    count -= n;
    tick += n;
    if (block_.size() == block_words_) {
      card_.write(block_);
      block_.clear();
      check_card();
    }
  }
}

}  // namespace gantry
