// Pulse decoding and timing checks of the simulated card.
#include "sim/sim_card.hpp"

#include <fmt/format.h>  // fault_detail

#include <algorithm>  // min
#include <bit>        // countr_one
#include <cmath>      // llround
#include <iomanip>    // the trace's hex words
#include <limits>     // numeric_limits
#include <thread>     // sleep_until for --realtime

#include "gantry/core/bounded.hpp"  // checked_llround

#if defined(__SSE2__)
#include <emmintrin.h>  // skip_run's compares
#endif

namespace gantry {
namespace {

constexpr std::int64_t kLongAgo = std::numeric_limits<std::int64_t>::min() / 2;

// The first word from `p` on whose `mask` bits differ from `w`'s, or `stop`: eight words
// compared at a time in two SSE2 vectors where there are (x86-64 always has them), one at a
// time elsewhere. Most words are like the one before (the idle words between pulses).
const std::uint32_t* skip_run(const std::uint32_t* p, const std::uint32_t* stop, std::uint32_t w,
                              std::uint32_t mask) {
#if defined(__SSE2__)
  const __m128i want = _mm_set1_epi32(static_cast<int>(w & mask));
  const __m128i m = _mm_set1_epi32(static_cast<int>(mask));
  while (stop - p >= 8) {
    const __m128i a = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), m);
    const __m128i b = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 4)), m);
    const auto same = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi32(a, want))) |
                      static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi32(b, want))) << 16;
    if (same != 0xffffffffu) return p + std::countr_one(same) / 4;
    p += 8;
  }
#endif
  while (p != stop && ((*p ^ w) & mask) == 0) ++p;
  return p;
}

// The card decodes each driver channel (its motor); channel k's units and limits are those
// of the axis it drives (drivers.channels).
std::array<AxisLimits, kAxisCount> limits_of(const Settings& s) {
  std::array<AxisLimits, kAxisCount> out{};
  for (int k = 0; k < kAxisCount; ++k) {
    const AxisSettings& a = s.axes[s.drivers.channel_axis[k]];
    out[k] = {a.steps_per_unit, a.max_speed, a.max_accel, s.planner.corner_jump * a.max_speed};
  }
  return out;
}

}  // namespace

SimCard::SimCard(const Settings& settings, bool realtime, SimWorld world,
                 const std::string& trace_path)
    : world_(world),
      input_bits_(settings.inputs),
      pins_(PinMap::from(settings.pins)),
      step_pulse_us_(settings.card.step_pulse_us),
      dir_setup_us_(settings.card.dir_setup_us),
      realtime_(realtime),
      tick_s_(1.0 / settings.card.pacer_hz()),
      limits_(limits_of(settings)),
      monitor_(limits_, tick_s_),
      lead_s_(settings.card.lead_ms * 1e-3) {
  queue_s_ = std::max({kRealtimeQueueS, kMostLeadS, lead_s_});
  // Half the lead, as the real cards' drivers start a stream (open_pci7200, gpio_map_profile).
  start_words_ = static_cast<std::uint64_t>(std::llround(lead_s_ * settings.card.pacer_hz() / 2));
  prev_ = pins_.idle_word();  // the lines rest idle, pointing positive, before the first word
  last_dir_change_.fill(kLongAgo);
  last_step_.fill(kLongAgo);
  prev_step_.fill(kLongAgo);
  filter_ = LimitFilter(settings, settings.card.pacer_hz());
  cushion_steps_ = settings.limits.cushion_steps;
  pulse_ticks_ =
      std::max(1, static_cast<int>(std::ceil(settings.card.step_pulse_us * 1e-6 / tick_s_ - 1e-9)));
  for (int i = 0; i < kAxisCount; ++i) {
    steps_per_unit_[i] = settings.axes[settings.drivers.channel_axis[i]].steps_per_unit;
    axis_bits_ |= pins_.axes[i].step_mask | pins_.axes[i].dir_mask;
  }
  const InputRoles roles = input_roles(settings);
  estop_trip_ = roles.estop;
  limit_trip_ = roles.limits;
  // Every switch starts inactive: active-low inputs read 1.
  set_input(input_bits_.estop_bit, false, input_bits_.estop_active_low);
  set_input(input_bits_.probe_bit, false, false);
  for (int i = 0; i < kAxisCount; ++i) update_switches(i);
  if (!trace_path.empty()) {
    trace_ = std::make_unique<std::ofstream>(trace_path);
    if (!*trace_)
      throw GantryError(Diagnostic{SourceLoc{std::make_shared<const std::string>(trace_path), 0, 0},
                                   Severity::Error, "cannot write the pin trace here"});
    *trace_ << "# tick word (hex): the output word from that tick on\n0 " << std::hex
            << std::setw(8) << std::setfill('0') << prev_ << std::dec << "\n";
  }
}

void SimCard::set_input(int bit, bool active, bool active_low) {
  if (bit < 0) return;
  const bool high = active != active_low;
  if (high)  // read-modify-write in one: set_switch may come from another thread
    inputs_.fetch_or(1u << bit, std::memory_order_relaxed);
  else
    inputs_.fetch_and(~(1u << bit), std::memory_order_relaxed);
}

// Several switches may share one input (ShopBot wires the proximity switches of X, Y and Z
// to input 3): a shared bit is active while any of its switches is.
void SimCard::update_switches(int axis) {
  auto at_of = [&](int i) { return static_cast<double>(steps_[i]) / steps_per_unit_[i]; };
  const double at = at_of(axis);
  const bool low = world_.min_switch[axis] && at <= *world_.min_switch[axis];
  const bool high = world_.max_switch[axis] && at >= *world_.max_switch[axis];
  const std::uint32_t before = inputs_;
  set_input(input_bits_.min_bit[axis], low, input_bits_.limits_active_low);
  set_input(input_bits_.max_bit[axis], high, input_bits_.limits_active_low);
  if (const int bit = input_bits_.home_bit[axis]; bit >= 0) {
    bool home = false;
    for (int i = 0; i < kAxisCount; ++i)
      home |= input_bits_.home_bit[i] == bit && world_.home_switch[i] &&
              (world_.home_above[i] ? at_of(i) >= *world_.home_switch[i]
                                    : at_of(i) <= *world_.home_switch[i]);
    set_input(bit, home, false);
  }
  for (const SimPositionInput& p : world_.position_inputs)
    if (p.axis == axis) set_input(p.bit, (p.above ? at >= p.at : at <= p.at) == p.high, false);
  if (axis == 2 && world_.probe_z) set_input(input_bits_.probe_bit, at <= *world_.probe_z, false);
  if (axis <= 2 && world_.probe_surface)
    set_input(input_bits_.probe_bit, at_of(2) <= world_.probe_surface(at_of(0), at_of(1)), false);
  check_trips(before);
}

// A limit switch trips the card as it becomes active, as the driver of a real card latches
// it; moving back off an active switch does not trip it again. An E-stop trips it while
// active. The limit rule is the real cards' (LimitFilter); each word is a sample of the
// inputs, and a count under way trips the card at pending_at_ unless released before.
void SimCard::check_trips(std::uint32_t before) {
  if (fault_ != CardFault::None || tick_ == 0) return;
  if (pending_at_ != UINT64_MAX && tick_ >= pending_at_) {  // its count played before this change
    fault_ = CardFault::Limit;
    return;
  }
  if (estop_trip_.tripped(inputs_)) {
    fault_ = CardFault::EStop;
    return;
  }
  if (inputs_ == before) return;  // a step that changed no input: nothing new to sample
  if (filter_.sample(limit_trip_, tick_, before, inputs_)) {
    fault_ = CardFault::Limit;
    return;
  }
  const std::uint64_t left = filter_.samples_to_trip();
  if (left == LimitFilter::kNone)
    pending_at_ = UINT64_MAX;  // released before its count: forgotten
  else if (pending_at_ == UINT64_MAX)
    pending_at_ = tick_ + 1 + left;  // the words from this one on read it active
}

// The cushion (limits.cushion_steps, esc_steps): each channel's speed from its last two
// steps, decelerating from the word after prev_ (cushion_words); decoded as any words are.
void SimCard::play_cushion(int steps) {
  if (steps <= 0) return;
  const auto now = static_cast<std::int64_t>(tick_);
  std::array<ChannelMotion, kAxisCount> motion{};
  std::array<std::int64_t, kAxisCount> since{};
  for (int k = 0; k < kAxisCount; ++k) {
    motion[k] =
        motion_from_steps(prev_step_[k], last_step_[k], last_step_positive_[k], now - 1, tick_s_);
    since[k] = std::min<std::int64_t>(now - last_step_[k], 1 << 30);
  }
  const std::vector<std::uint32_t> words =
      cushion_words(pins_, prev_, motion, since, steps, pulse_ticks_);
  const Steps6 before = steps_;
  CushionPlayed c{tick_, {}};
  for (const std::uint32_t w : words) {
    decode(w);
    ++tick_;
  }
  for (int k = 0; k < kAxisCount; ++k) c.steps[k] = steps_[k] - before[k];
  cushion_ = c;
}

void SimCard::stop_cushioned(std::uint32_t idle_word, int steps) {
  if (!stopped_ && fault_ == CardFault::None) play_cushion(steps);
  stop(idle_word);
}

void SimCard::set_trips(const InputTrip& estop, const InputTrip& limits) {
  estop_trip_ = estop;
  limit_trip_ = limits;
}

void SimCard::watch(const InputWatch& w) {
  watcher_.arm(w, inputs_);
  fired_.reset();
  watch_tick_ = tick_;
  watch_bits_ = inputs_;
  watch_at_ = UINT64_MAX;
}

// Each word is a sample of the inputs, as for the limit rule: the inputs last sampled at
// watch_tick_ held for the words since, so they count for those first (a debounce under way
// reaches its count there, or not), then the inputs now count once. A count under way makes
// the loop stop at watch_at_, the word where it is reached if nothing changes before.
void SimCard::sample_watch(std::uint64_t played) {
  if (fired_ || watcher_.watch().mask == 0) return;
  std::optional<InputEdge> e;
  if (played > watch_tick_ + 1 && watcher_.samples_left() != EdgeDetector::kNone)
    e = watcher_.sample(watch_bits_, watch_tick_ + 1, played - watch_tick_ - 1);
  if (!e && (played > watch_tick_ || inputs_ != watch_bits_)) e = watcher_.sample(inputs_, played);
  watch_tick_ = std::max(watch_tick_, played);
  watch_bits_ = inputs_;
  const std::uint64_t left = watcher_.samples_left();
  watch_at_ = left == EdgeDetector::kNone ? UINT64_MAX : watch_tick_ + left;
  if (!e) return;
  fired_ = e;
  watch_at_ = UINT64_MAX;
  if (watcher_.watch().stop >> e->bit & 1u) stopped_ = true;
}

// The monitor checks what follows against the new calibration; the simulated switches stay
// where they are on the table (their positions are in the profile's units).
void SimCard::calibration_changed(const Settings& s) {
  limits_ = limits_of(s);
  monitor_.set_limits(limits_);
}

void SimCard::start(double pacer_hz) {
  stopped_ = false;
  fault_ = CardFault::None;
  filter_.reset();
  pending_at_ = UINT64_MAX;
  cushion_.reset();
  tick_s_ = 1.0 / pacer_hz;
  monitor_ = KinematicsMonitor(limits_, tick_s_);
  // The tick count goes on from where it stopped: the wall clock's origin follows it, so a
  // restart neither waits for the ticks before it nor finds itself late.
  streaming_ = false;
  starting_ = false;
  late_s_.reset();
  wall_start_ = std::chrono::steady_clock::now();
  wall_start_ -= wall_at(tick_) - wall_start_;
  auto tick_of = [&](const std::optional<double>& s) {  // beyond any run's ticks: never
    const std::optional<std::int64_t> t =
        s ? checked_llround(std::max(0.0, *s) * pacer_hz) : std::nullopt;
    return t ? static_cast<std::uint64_t>(*t) : UINT64_MAX;
  };
  // Started again after a fault: the E-stop is still pressed, but a stall has passed and so
  // have the switch events before now.
  estop_tick_ = tick_of(world_.estop_at_s);
  stall_tick_ = tick_of(world_.stall_at_s);
  if (tick_ > 0 && stall_tick_ <= tick_) stall_tick_ = UINT64_MAX;
  input_ticks_.clear();
  next_input_ = 0;
  for (const SimInputEvent& e : world_.input_events) {
    input_ticks_.push_back(tick_of(e.at_s));
    if (input_ticks_.back() < tick_) ++next_input_;
  }
}

std::uint64_t SimCard::next_event_tick() const {
  const std::uint64_t input =
      next_input_ < input_ticks_.size() ? input_ticks_[next_input_] : UINT64_MAX;
  return std::min({estop_tick_, stall_tick_, input, pending_at_, watch_at_});
}

void SimCard::stop(std::uint32_t idle_word) {
  stopped_ = true;
  if (idle_word != prev_) decode(idle_word);
}

std::chrono::steady_clock::time_point SimCard::wall_at(std::uint64_t tick) const {
  return wall_start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(static_cast<double>(tick) * tick_s_));
}

std::uint64_t SimCard::clock_tick() const {
  if (!realtime_ || !streaming_) return tick_;  // at rest the clock waits for the next word
  if (starting_) return stream_first_;          // below the start threshold: nothing plays
  const double due =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count() /
      tick_s_;
  return std::min(tick_, static_cast<std::uint64_t>(std::max(0.0, due)));
}

void SimCard::begin_playing(std::chrono::steady_clock::time_point now) {
  wall_start_ += now - wall_at(stream_first_);
  starting_ = false;
}

void SimCard::end_stream() {
  if (starting_) begin_playing(std::chrono::steady_clock::now());
  streaming_ = false;
}

void SimCard::drain() {
  if (starting_) begin_playing(std::chrono::steady_clock::now());
  if (realtime_ && !stopped_ && fault_ == CardFault::None)
    std::this_thread::sleep_until(wall_at(tick_));
  end_stream();
}

std::string SimCard::fault_detail() const {  // a simulated stall (--sim-stall-at) needs none
  if (fault_ != CardFault::Underrun || !late_s_) return {};
  return fmt::format("the producer was {:.1f} ms late: the card's queue ran dry at {:.4f} s",
                     *late_s_ * 1e3, time_s());
}

void SimCard::write(std::span<const std::uint32_t> words) {
  if (stopped_ || fault_ != CardFault::None) return;
  if (realtime_) {
    // The queue ran dry at wall_at(tick_). Between stretches of output that is rest, and the
    // new words play from now; within one, the word at tick_ was due and missing: a real
    // card underruns there, and so does this one (the clock is never moved to hide it).
    const auto now = std::chrono::steady_clock::now();
    const auto dry = wall_at(tick_);
    if (!streaming_) {
      streaming_ = true;
      stream_first_ = tick_;
      // A new stretch on an empty queue waits for the start threshold; one that comes while
      // the last one's words still play goes on after them.
      starting_ = now > dry && start_words_ > 0;
      if (now > dry && !starting_) wall_start_ += now - dry;
    } else if (starting_) {
      // Below the start threshold nothing plays yet, so nothing is late.
    } else if (now > dry) {
      late_s_ = std::chrono::duration<double>(now - dry).count();
      fault_ = CardFault::Underrun;
      return;
    } else if (static_cast<double>(tick_ - stream_first_) * tick_s_ >= lead_s_) {
      const double held = std::chrono::duration<double>(dry - now).count();
      block_seen_ =
          std::max(block_seen_, words.size());  // the generator's block: its largest write
      const double refill = lead_s_ - static_cast<double>(block_seen_) * tick_s_;
      feed_.least_queue_s = feed_.blocks == 0 ? held : std::min(feed_.least_queue_s, held);
      feed_.worst_late_s = std::max(feed_.worst_late_s, refill - held);
      ++feed_.blocks;
    }
  }
  // Only an edge (a word unlike the one before) or an event (an input, the E-stop, a stall)
  // does anything: the words between play in one step, and the timing rules are checked at
  // the edges, as before, at their own ticks. Without a trace or an input watch, a change of
  // the other outputs alone (the charge pump's flips, every few ticks) is no edge either:
  // nothing but the trace and the watch's sampling looks at it.
  std::uint64_t event_tick = next_event_tick();
  const std::uint32_t edge_bits = !trace_ && watcher_.watch().mask == 0 ? axis_bits_ : ~0u;
  const std::uint32_t* p = words.data();
  const std::uint32_t* const end = p + words.size();
  while (p != end) {
    while (next_input_ < input_ticks_.size() && tick_ >= input_ticks_[next_input_]) {
      const SimInputEvent& e = world_.input_events[next_input_++];
      const std::uint32_t before = inputs_;
      set_input(e.bit, e.high, false);
      event_tick = next_event_tick();
      sample_watch(tick_);
      check_trips(before);
      if (stopped_ || fault_ != CardFault::None) {  // the word at this tick is not played
        if (fault_ == CardFault::Limit) play_cushion(cushion_steps_);
        return;
      }
      event_tick = next_event_tick();  // a limit input may have begun its count
    }
    if (tick_ >= watch_at_) {  // an input watched read its level long enough (or not)
      sample_watch(tick_);
      if (stopped_) return;  // the word at this tick is not played
      event_tick = next_event_tick();
    }
    if (tick_ >= event_tick && tick_ < pending_at_ && tick_ < estop_tick_ && tick_ < stall_tick_)
      event_tick = next_event_tick();  // a limit input's count ended in its release: go on
    if (tick_ >= event_tick) {
      if (tick_ >= pending_at_) {  // a limit input read active long enough
        fault_ = CardFault::Limit;
        break;
      }
      if (tick_ >= estop_tick_) {
        set_input(input_bits_.estop_bit, true, input_bits_.estop_active_low);
        fault_ = CardFault::EStop;
      } else {  // the queue ran dry here while this word was still due
        fault_ = CardFault::Underrun;
      }
      break;
    }
    // The run of words like the last one, up to the next event's tick at most.
    const std::uint64_t room = event_tick - tick_;
    const std::uint32_t* const stop = static_cast<std::uint64_t>(end - p) > room ? p + room : end;
    const std::uint32_t* const edge = skip_run(p, stop, prev_, edge_bits);
    if (edge != p) {
      tick_ += static_cast<std::uint64_t>(edge - p);
      prev_ = edge[-1];  // the output lines now (they differ from prev_ outside edge_bits only)
      p = edge;
    }
    if (p == stop) continue;  // the run reached the event (or the end of the words)
    const std::uint32_t w = *p++;
    if (((w ^ prev_) & axis_bits_) == 0 && !trace_)  // no step or direction line: no rule
      prev_ = w;
    else
      decode(w);
    event_tick = std::min(event_tick, pending_at_);  // a step may have closed a limit
    if (watcher_.watch().mask != 0) sample_watch(tick_ + 1);
    ++tick_;
    if (fault_ != CardFault::None || stopped_) break;  // a switch tripped by this word's step
  }
  if (fault_ == CardFault::Limit && !cushion_) play_cushion(cushion_steps_);
  if (starting_ && tick_ - stream_first_ >= start_words_)
    begin_playing(std::chrono::steady_clock::now());
  if (realtime_ && !starting_)  // the queue holds up to queue_s_ of words not yet played
    std::this_thread::sleep_until(wall_at(tick_) -
                                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(queue_s_)));
}

void SimCard::decode(std::uint32_t w) {
  const std::uint32_t diff = w ^ prev_;
  if ((diff & axis_bits_) == 0) {  // only other outputs changed (the charge pump, mostly)
    prev_ = w;
    trace_word(w);
    return;
  }
  const auto t = static_cast<std::int64_t>(tick_);
  const double tick_us = tick_s_ * 1e6;
  constexpr double eps = 1e-6;  // microseconds: tolerance for the tick arithmetic only
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisPins& ap = pins_.axes[i];
    const bool step_changed = (diff & ap.step_mask) != 0;
    const bool active = ((w & ap.step_mask) != 0) != ap.step_active_low;
    // Order within one word: a trailing edge ends the pulse, then a direction change is
    // judged, then a leading edge is a step. A direction change in the very word where the
    // pulse ends is after the pulse, not during it.
    if (step_changed && !active) {
      if (static_cast<double>(t - pulse_start_[i]) * tick_us < step_pulse_us_ - eps)
        violation(i, TimingRule::PulseWidth);
      pulse_active_[i] = false;
    }
    if (diff & ap.dir_mask) {
      if (pulse_active_[i]) violation(i, TimingRule::DirDuringPulse);
      last_dir_change_[i] = t;
    }
    if (step_changed && active) {
      if (static_cast<double>(t - last_dir_change_[i]) * tick_us < dir_setup_us_ - eps)
        violation(i, TimingRule::DirSetup);
      const bool positive = pins_.positive(i, w);
      steps_[i] += positive ? 1 : -1;
      prev_step_[i] = last_step_[i];
      last_step_[i] = t;
      filter_.note_step(i, tick_, positive);
      last_step_positive_[i] = positive;
      monitor_.on_step(i, t, positive);
      update_switches(i);
      pulse_start_[i] = t;
      pulse_active_[i] = true;
    }
  }
  prev_ = w;
  trace_word(w);
}

void SimCard::trace_word(std::uint32_t w) {
  if (trace_)
    *trace_ << tick_ << ' ' << std::hex << std::setw(8) << std::setfill('0') << w << std::dec
            << '\n';
}

void SimCard::violation(int axis, TimingRule rule) {
  ++violation_count_;
  if (violations_.size() < 16) violations_.push_back({tick_, axis, rule});
}

const KinematicsMonitor& SimCard::kinematics() {
  if (!monitor_finished_) monitor_.finish();
  monitor_finished_ = true;
  return monitor_;
}

const char* rule_name(TimingRule r) {
  switch (r) {
    case TimingRule::PulseWidth:
      return "step pulse shorter than step_pulse_us";
    case TimingRule::DirSetup:
      return "step less than dir_setup_us after a direction change";
    case TimingRule::DirDuringPulse:
      return "direction changed during a step pulse";
  }
  return "?";
}

}  // namespace gantry
