// The per-tick work of the GPIO card: queue to lines, lines to input word, faults.
#include "gpiod/tick_player.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>

namespace gantry {
namespace {

constexpr int kWriteOperation = 1, kReadOperation = 2;

// Calls f(b) for every set bit b of `bits`, lowest first.
template <typename F>
void for_each_bit(std::uint32_t bits, F f) {
  while (bits) {
    f(std::countr_zero(bits));
    bits &= bits - 1;
  }
}

std::uint64_t pack(const InputTrip& t) {
  return std::uint64_t{t.mask} << 32 | (t.active_high & t.mask);
}

InputTrip unpack(std::uint64_t w) {
  return {static_cast<std::uint32_t>(w >> 32), static_cast<std::uint32_t>(w)};
}

}  // namespace

void TickPlayer::set_trips(const InputTrip& estop, const InputTrip& limits) {
  estop_trip_.store(pack(estop), std::memory_order_release);
  limit_trip_.store(pack(limits), std::memory_order_release);
}

void TickPlayer::arm_watch(const InputWatch& w, std::uint32_t bits_now) {
  watch_levels_.store(std::uint64_t{w.mask} << 32 | (w.levels & w.mask), std::memory_order_relaxed);
  watch_bits_now_.store(bits_now, std::memory_order_relaxed);
  watch_debounce_.store(w.debounce, std::memory_order_relaxed);
  watch_gen_.fetch_add(1, std::memory_order_release);
}

std::optional<InputEdge> TickPlayer::watch_fired() const {
  if (fired_gen_.load(std::memory_order_acquire) != watch_gen_.load(std::memory_order_acquire))
    return std::nullopt;
  return InputEdge{edge_tick_.load(std::memory_order_relaxed),
                   edge_bit_.load(std::memory_order_relaxed),
                   edge_bits_.load(std::memory_order_relaxed)};
}

void TickPlayer::sample_watch(std::uint64_t tick, std::uint32_t bits) {
  const unsigned gen = watch_gen_.load(std::memory_order_acquire);
  if (gen != armed_gen_) {
    armed_gen_ = gen;
    const std::uint64_t w = watch_levels_.load(std::memory_order_relaxed);
    detector_.arm({static_cast<std::uint32_t>(w >> 32), static_cast<std::uint32_t>(w), 0,
                   watch_debounce_.load(std::memory_order_relaxed)},
                  watch_bits_now_.load(std::memory_order_relaxed));
  }
  if (const std::optional<InputEdge> e = detector_.sample(bits, tick)) {
    edge_tick_.store(e->tick, std::memory_order_relaxed);
    edge_bit_.store(e->bit, std::memory_order_relaxed);
    edge_bits_.store(e->bits, std::memory_order_relaxed);
    fired_gen_.store(gen, std::memory_order_release);
  }
}

TickPlayer::TickPlayer(const GpioMap& map, GpioLines& lines, WordRing& ring)
    : lines_(lines),
      ring_(ring),
      map_(map),
      current_word_(map.initial_word),
      limit_rule_(map.limit_rule),
      trail_(map.cushion.pins, 2) {
  for (std::size_t i = 0; i < map.outputs.size() && i < 64; ++i) {
    lines_of_bit_[map.outputs[i].bit] |= std::uint64_t{1} << i;
    mapped_bits_ |= 1u << map.outputs[i].bit;
  }
  for (std::size_t i = 0; i < map.inputs.size() && i < 64; ++i)
    bit_of_input_[i] = map.inputs[i].bit;
  set_trips({map.estop_bits, map.estop_bits & ~map.active_low_bits},
            {map.limit_bits, map.limit_bits & ~map.active_low_bits});
  reset(map.pacer_hz);
}

void TickPlayer::reset(double pacer_hz) {
  sample_every_ = std::max<std::uint64_t>(1, std::llround(pacer_hz / map_.input_sample_hz));
  late_tolerance_ns_ = std::llround(map_.late_tolerance_ticks * 1e9 / pacer_hz);
  next_sample_tick_ = 0;
  limit_rule_.reset();
  tick_s_ = 1.0 / pacer_hz;
  trail_.reset(current_word_);
  cushioning_ = false;
  esc_request_.store(0, std::memory_order_relaxed);
  cushion_ready_.store(false, std::memory_order_release);
  ticks_played_.store(0, std::memory_order_release);
  line_tick_.store(0, std::memory_order_release);
  fault_.store(CardFault::None, std::memory_order_release);
  late_ticks_.store(0, std::memory_order_relaxed);
  worst_late_ns_.store(0, std::memory_order_relaxed);
  failed_operation_.store(0, std::memory_order_relaxed);
  failed_errno_.store(0, std::memory_order_relaxed);
}

void TickPlayer::begin_stream() {
  next_sample_tick_ = ticks_played_.load(std::memory_order_relaxed);
  last_sample_ = inputs_.load(std::memory_order_relaxed);
}

std::uint64_t TickPlayer::next_event_tick() const {
  if (cushioning_) {
    // The cushion's first word unlike the lines (runs of alike words are skipped whole),
    // or the next sample, or its end.
    CushionStream peek = cushion_;
    std::uint64_t tick = cushion_from_ + peek.given();
    while (!peek.done() && tick < next_sample_tick_) {
      const std::uint64_t n = peek.alike_ahead();
      if ((peek.next() ^ current_word_) & mapped_bits_) break;
      peek.skip(n - 1);
      tick += n;
    }
    return std::min(tick, next_sample_tick_);
  }
  if (esc_request_.load(std::memory_order_acquire) != 0)
    return ticks_played_.load(std::memory_order_relaxed);  // at once
  const std::uint64_t tick = ticks_played_.load(std::memory_order_relaxed);
  // The scan stops at the next sample tick, so it never reads more than sample_every_ words.
  const std::uint64_t horizon =
      std::min<std::uint64_t>(ring_.available(), next_sample_tick_ - tick);
  for (std::uint64_t i = 0; i < horizon; ++i)
    if ((ring_.peek(i) ^ current_word_) & mapped_bits_) return tick + i;
  return tick + horizon;
}

TickPlayer::Outcome TickPlayer::play_through(std::uint64_t tick, std::int64_t late_ns,
                                             bool stream_may_end) {
  if (cushioning_) return play_cushion(tick, late_ns);
  // The words before `tick` equal the current output on every mapped bit: nothing to drive.
  ring_.drop(tick - ticks_played_.load(std::memory_order_relaxed));
  ticks_played_.store(tick, std::memory_order_release);
  line_tick_.store(tick, std::memory_order_release);

  // The operator's E-stop with limits.esc_steps: the cushion from this tick on.
  if (const int steps = esc_request_.exchange(0, std::memory_order_acq_rel); steps > 0) {
    if (!begin_cushion(tick, steps, CardFault::None)) return Outcome::Stopped;
    return play_cushion(tick, late_ns);
  }

  // Inputs first: a tick that finds the E-stop active plays nothing more.
  if (tick == next_sample_tick_) {
    if (!read_inputs()) return Outcome::Faulted;
    next_sample_tick_ += sample_every_;
    const std::uint32_t bits = inputs_.load(std::memory_order_relaxed);
    sample_watch(tick, bits);
    if (unpack(estop_trip_.load(std::memory_order_acquire)).tripped(bits)) {
      fail(CardFault::EStop);
      return Outcome::Faulted;
    }
    // A limit switch trips as it becomes active (the tool that stopped on one can move off),
    // by the profile's rule: travel_only, debounce (LimitFilter, every card's).
    const InputTrip limits = unpack(limit_trip_.load(std::memory_order_acquire));
    const bool closed = limit_rule_.sample(limits, tick, last_sample_, bits);
    last_sample_ = bits;
    if (closed) {
      // limits.cushion_steps: the cushion first (the word at this tick is not played),
      // the fault once it has played.
      if (begin_cushion(tick, map_.cushion.limit_steps, CardFault::Limit))
        return play_cushion(tick, late_ns);
      fail(CardFault::Limit);
      return Outcome::Faulted;
    }
  }

  if (ring_.available() == 0) {
    if (stream_may_end) return Outcome::StreamEnded;
    fail(CardFault::Underrun);  // a word was due and the producer had not written it
    return Outcome::Faulted;
  }
  const std::uint32_t word = ring_.peek(0);
  limit_rule_.note_word(tick, current_word_, word);  // the steps, for travel_only
  trail_.note_word(tick, current_word_, word);       // and for a cushion's rates
  if (!write_word(word)) return Outcome::Faulted;
  ring_.drop(1);

  count_late(late_ns);
  ticks_played_.store(tick + 1, std::memory_order_release);
  return Outcome::Played;
}

void TickPlayer::count_late(std::int64_t late_ns) {
  worst_late_ns_.store(std::max(worst_late_ns_.load(std::memory_order_relaxed), late_ns),
                       std::memory_order_relaxed);
  if (late_ns > late_tolerance_ns_)
    late_ticks_.store(late_ticks_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}

// Each channel's rate from its last two steps played, decelerating from the word on the
// lines (docs/hardware.md, "Cushioned stop"). False when nothing moves: a dead stop.
bool TickPlayer::begin_cushion(std::uint64_t tick, int steps, CardFault fault) {
  if (steps <= 0) return false;
  std::array<ChannelMotion, kAxisCount> motion{};
  std::array<std::int64_t, kAxisCount> since{};
  trail_.motion_at(tick, tick_s_, motion, since);
  cushion_ = CushionStream(map_.cushion.pins, current_word_, motion, since, steps,
                           map_.cushion.pulse_ticks);
  if (cushion_.done()) return false;
  cushion_start_ = cushion_;
  cushion_from_ = tick;
  cushion_fault_ = fault;
  cushioning_ = true;
  ring_.drop(ring_.available());  // the words written are not played now
  return true;
}

TickPlayer::Outcome TickPlayer::play_cushion(std::uint64_t tick, std::int64_t late_ns) {
  // The words before `tick` are like the lines (next_event_tick): nothing to drive.
  const std::uint64_t at = tick - cushion_from_;
  while (cushion_.given() < at && !cushion_.done())
    cushion_.skip(std::min<std::uint64_t>(cushion_.alike_ahead(), at - cushion_.given()));
  ring_.drop(ring_.available());  // words written meanwhile are dropped, never played
  line_tick_.store(tick, std::memory_order_release);
  if (tick == next_sample_tick_) {  // the E-stop input still stops dead
    if (!read_inputs()) {
      end_cushion(tick, CardFault::Hardware);
      return Outcome::Faulted;
    }
    next_sample_tick_ += sample_every_;
    const std::uint32_t bits = inputs_.load(std::memory_order_relaxed);
    sample_watch(tick, bits);
    last_sample_ = bits;
    if (unpack(estop_trip_.load(std::memory_order_acquire)).tripped(bits)) {
      end_cushion(tick, CardFault::EStop);
      return Outcome::Faulted;
    }
  }
  if (!cushion_.done()) {
    const std::uint32_t word = cushion_.next();
    if (!write_word(word)) {
      end_cushion(tick, CardFault::Hardware);  // hardware_fault() has set the fault
      return Outcome::Faulted;
    }
    count_late(late_ns);
    if (!cushion_.done()) return Outcome::Played;
  }
  const CardFault fault = cushion_fault_;
  end_cushion(cushion_from_ + cushion_.given(), fault);
  return fault == CardFault::None ? Outcome::Stopped : Outcome::Faulted;
}

// The cushion's words up to `end_tick` played: published before the ticks, and both before
// the fault, so that whoever sees the fault finds where the tool is.
void TickPlayer::end_cushion(std::uint64_t end_tick, CardFault fault) {
  const std::uint64_t words = end_tick - cushion_from_;
  cushion_result_ = {cushion_from_,
                     words == cushion_.given() ? cushion_.steps() : cushion_start_.steps_in(words)};
  cushion_ready_.store(true, std::memory_order_release);
  cushioning_ = false;
  ticks_played_.store(end_tick, std::memory_order_release);
  if (fault != CardFault::None && this->fault() == CardFault::None) fail(fault);
}

void TickPlayer::leave_stream() {
  if (cushioning_) end_cushion(cushion_from_ + cushion_.given(), CardFault::None);
}

bool TickPlayer::sample_inputs() {
  return read_inputs();
}

bool TickPlayer::output(std::uint32_t word) {
  return write_word(word);
}

bool TickPlayer::write_word(std::uint32_t word) {
  const std::uint32_t changed_bits = (word ^ current_word_) & mapped_bits_;
  if (!changed_bits) {
    current_word_ = word;
    return true;
  }
  std::uint64_t changed_lines = 0, levels = 0;
  for_each_bit(changed_bits, [&](int b) { changed_lines |= lines_of_bit_[b]; });
  for_each_bit(word & mapped_bits_, [&](int b) { levels |= lines_of_bit_[b]; });
  if (!lines_.set_outputs(changed_lines, levels)) {
    hardware_fault(kWriteOperation);
    return false;
  }
  current_word_ = word;
  return true;
}

bool TickPlayer::read_inputs() {
  std::uint64_t levels = 0;
  if (!lines_.read_inputs(levels)) {
    hardware_fault(kReadOperation);
    return false;
  }
  std::uint32_t word = 0;
  for (std::size_t i = 0; i < map_.inputs.size() && i < 64; ++i)
    if ((levels >> i) & 1u) word |= 1u << bit_of_input_[i];
  inputs_.store(word, std::memory_order_release);
  return true;
}

void TickPlayer::hardware_fault(int operation) {
  failed_errno_.store(errno, std::memory_order_relaxed);
  failed_operation_.store(operation, std::memory_order_relaxed);
  fail(CardFault::Hardware);
}

const char* TickPlayer::failed_operation() const {
  switch (failed_operation_.load(std::memory_order_relaxed)) {
    case kWriteOperation:
      return "write";
    case kReadOperation:
      return "read";
  }
  return "";
}

}  // namespace gantry
