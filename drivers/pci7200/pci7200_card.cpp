// The PCI-7200 card: pacer programming, the feeder thread's state machine, faults and stop.
#include "pci7200/pci7200_card.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "pci7200/pacer_divisor.hpp"

namespace gantry::pci7200 {
namespace {

constexpr auto kProducerWait = std::chrono::microseconds(50);
constexpr std::size_t kPioPrimeWords = 64;

}  // namespace

Pci7200Card::Pci7200Card(std::shared_ptr<Pci7200Bus> bus, Pci7200Options options)
    : bus_(std::move(bus)), options_(options), ring_(options.ring_words), output_(*bus_) {
  // The feeder takes words up to two DMA halves (PIO: the FIFO) before they play: the trail
  // keeps a step of every two words of that, so a cushion finds the steps before its start.
  trail_ = StepTrail(options_.cushion.pins,
                     (output_.uses_dma() ? output_.half_words() : amcc::kFifoWords) + 8,
                     options_.charge_pump_bit >= 0 && options_.charge_pump_bit < 32
                         ? 1u << options_.charge_pump_bit
                         : 0u);
  {
    // Whatever the card was doing (a previous run that crashed), it stops here.
    std::lock_guard lock(hardware_);
    bus_->write32(Bar::Card, card::kCounterControl,
                  i8254::control_word(i8254::kPacerCounter, i8254::kPacerMode));
    output_.reset();
    bus_->write32(Bar::Card, card::kDioCsr, card::kDioDoClearFifo | card::kDioDoUnderrun);
    bus_->write32(Bar::Card, card::kDioCsr, 0);
    bus_->write32(Bar::Card, card::kDoPort, options_.idle_word);
    last_inputs_ = bus_->read32(Bar::Card, card::kDiPort);
    inputs_.store(last_inputs_, std::memory_order_release);
  }
  bus_->attach_feeder();
  feeder_thread_ = std::thread(&Pci7200Card::feeder_loop, this);
  while (!feeder_ready_.load(std::memory_order_acquire)) std::this_thread::yield();
}

Pci7200Card::~Pci7200Card() {
  close();
}

void Pci7200Card::close() {
  if (closed_) return;
  closed_ = true;
  {
    std::lock_guard lock(hardware_);
    const Phase phase = phase_.load(std::memory_order_acquire);
    if (active()) halt_output(true);
    output_.reset();
    if (phase != Phase::Idle) bus_->write32(Bar::Card, card::kDoPort, options_.idle_word);
    phase_.store(Phase::Idle, std::memory_order_release);
  }
  exit_.store(true, std::memory_order_release);
  bus_->detach_feeder();
  if (feeder_thread_.joinable()) feeder_thread_.join();
}

void Pci7200Card::start(double pacer_hz) {
  if (closed_) throw std::logic_error("PCI-7200: start() after close()");
  const PacerDivisor divisor = pacer_divisor(options_.clock_hz, pacer_hz);
  if (!divisor.ok()) throw std::invalid_argument(divisor.error);

  std::lock_guard lock(hardware_);
  if (active()) halt_output(false);
  output_.reset();
  ring_.clear();
  bus_->write32(Bar::Card, card::kDioCsr, card::kDioDoClearFifo | card::kDioDoUnderrun);
  bus_->write32(Bar::Card, card::kDioCsr, 0);
  // Counter 1 alone sets the rate: pacer = clock / divisor.
  const std::uint32_t int_csr = bus_->read32(Bar::Card, card::kIntCsr);
  bus_->write32(Bar::Card, card::kIntCsr, int_csr & ~card::kIntT1T2Cascade);
  const auto count = static_cast<std::uint32_t>(divisor.divisor);
  const std::uint32_t counter = i8254::counter_offset(i8254::kPacerCounter);
  bus_->write32(Bar::Card, card::kCounterControl,
                i8254::control_word(i8254::kPacerCounter, i8254::kPacerMode));
  bus_->write32(Bar::Card, counter, count & 0xff);
  bus_->write32(Bar::Card, counter, count >> 8);

  tick_seconds_ = divisor.divisor / options_.clock_hz;
  pacer_hz_.store(options_.clock_hz / divisor.divisor, std::memory_order_release);
  pump_ = ChargePump();
  if (options_.charge_pump_bit >= 0 && options_.charge_pump_bit < 32) {
    const double half = std::round(pacer_hz / (2 * options_.charge_pump_hz));
    pump_ = ChargePump(options_.charge_pump_bit, static_cast<std::uint32_t>(std::max(1.0, half)));
  }
  stream_position_ = 0;
  options_.limit_rule.reset();
  trail_.reset(last_taken_);
  cushioning_ = false;
  esc_request_.store(0, std::memory_order_relaxed);
  esc_busy_.store(false, std::memory_order_relaxed);
  cushion_ready_.store(false, std::memory_order_release);
  const std::size_t prime = options_.prime_words > 0 ? options_.prime_words
                            : output_.uses_dma()     ? output_.half_words()
                                                     : kPioPrimeWords;
  prime_words_.store(std::min(prime, ring_.capacity()), std::memory_order_release);
  ticks_.store(0, std::memory_order_release);
  written_ = 0;
  stream_end_.store(0, std::memory_order_release);
  fault_.store(CardFault::None, std::memory_order_release);
  drains_done_.store(drains_requested_.load(std::memory_order_acquire), std::memory_order_release);
  phase_.store(Phase::Armed, std::memory_order_release);
}

void Pci7200Card::write(std::span<const std::uint32_t> words) {
  while (!words.empty()) {
    const Phase phase = phase_.load(std::memory_order_acquire);
    if (phase == Phase::Idle || phase == Phase::Faulted) return;  // dropped
    const std::size_t n = ring_.push(words);
    written_ += n;
    words = words.subspan(n);
    if (n == 0) std::this_thread::sleep_for(kProducerWait);
  }
}

void Pci7200Card::drain() {
  const std::uint64_t mine = drains_requested_.fetch_add(1, std::memory_order_acq_rel) + 1;
  for (;;) {
    const Phase phase = phase_.load(std::memory_order_acquire);
    if (phase == Phase::Idle || phase == Phase::Faulted) return;
    if (drains_done_.load(std::memory_order_acquire) >= mine) return;
    std::this_thread::sleep_for(kProducerWait);
  }
}

void Pci7200Card::end_stream() {
  stream_end_.store(written_, std::memory_order_release);
}

void Pci7200Card::stop(std::uint32_t idle_word) {
  std::lock_guard lock(hardware_);
  if (active()) halt_output(true);
  bus_->write32(Bar::Card, card::kDoPort, pump_.idle(idle_word));
  ring_.clear();
  phase_.store(Phase::Idle, std::memory_order_release);
}

void Pci7200Card::stop_cushioned(std::uint32_t idle_word, int steps) {
  if (steps > 0 && phase_.load(std::memory_order_acquire) == Phase::Running) {
    esc_busy_.store(true, std::memory_order_release);
    esc_request_.store(steps, std::memory_order_release);
    while (esc_busy_.load(std::memory_order_acquire) && active())
      std::this_thread::sleep_for(kProducerWait);
  }
  stop(idle_word);
}

std::size_t Pci7200Card::take(std::span<std::uint32_t> out) {
  if (cushioning_) {  // the cushion's words, in place of the queue's
    std::size_t n = 0;
    while (n < out.size() && !cushion_.done()) out[n++] = cushion_.next();
    pump_.stamp(out.first(n), stream_position_);
    stream_position_ += n;
    return n;
  }
  const std::size_t n = ring_.pop(out);
  pump_.stamp(out.first(n), stream_position_);
  for (std::size_t i = 0; i < n; ++i) {  // the steps, for limits.travel_only: at their ticks
    if (out[i] != last_taken_) {
      options_.limit_rule.note_word(stream_position_ + i, last_taken_, out[i]);
      trail_.note_word(stream_position_ + i, last_taken_, out[i]);  // a cushion's rates
    }
    last_taken_ = out[i];
  }
  stream_position_ += n;
  return n;
}

void Pci7200Card::set_trips(const InputTrip& estop, const InputTrip& limits) {
  std::lock_guard lock(hardware_);  // the feeder reads them in its pass
  options_.estop = estop;
  options_.limits = limits;
}

void Pci7200Card::watch(const InputWatch& w) {
  std::lock_guard lock(hardware_);
  watcher_.arm(w, inputs_.load(std::memory_order_acquire));
  fired_.reset();
}

std::optional<InputEdge> Pci7200Card::watch_fired() {
  std::lock_guard lock(hardware_);
  return fired_;
}

void Pci7200Card::feeder_loop() {
  realtime_report_ = make_current_thread_realtime(options_.realtime);
  feeder_running_.store(true, std::memory_order_release);
  feeder_ready_.store(true, std::memory_order_release);
  for (;;) {
    bus_->pause();
    if (exit_.load(std::memory_order_acquire)) break;
    std::lock_guard lock(hardware_);
    pass();
  }
  feeder_running_.store(false, std::memory_order_release);
}

// One look at the card: sample the inputs, then move the state machine on. Allocation-free.
void Pci7200Card::pass() {
  // The drain request is read before the ring: the producer queues its words before it asks,
  // so a request seen here comes with all the words it covers.
  const std::uint64_t drain_request = drains_requested_.load(std::memory_order_acquire);
  const bool drain_pending = drain_request > drains_done_.load(std::memory_order_acquire);
  // Read before the ring too: an end marked here comes with its words.
  const std::uint64_t stream_end = stream_end_.load(std::memory_order_acquire);
  const std::uint32_t inputs = bus_->read32(Bar::Card, card::kDiPort);
  inputs_.store(inputs, std::memory_order_release);
  // A limit switch trips as it becomes active (the E-stop while it is): the tool that stopped
  // on one must be able to move off it.
  const bool limit_closed = options_.limit_rule.sample(
      options_.limits, ticks_.load(std::memory_order_acquire), last_inputs_, inputs);
  last_inputs_ = inputs;
  if (!fired_)
    if (const std::optional<InputEdge> e =
            watcher_.sample(inputs, ticks_.load(std::memory_order_acquire))) {
      fired_ = e;
      if ((watcher_.watch().stop >> e->bit & 1u) && active()) {  // an instant stop, no fault
        halt_output(true);
        ring_.clear();
        phase_.store(Phase::Idle, std::memory_order_release);
        return;
      }
    }
  const Phase phase = phase_.load(std::memory_order_acquire);
  // The operator's E-stop with limits.esc_steps: a cushion, or (nothing moving, output not
  // running) nothing, and the caller stops the card. A limit's cushion under way plays out
  // first, and its fault stands; the caller waits for it.
  if (const int steps = esc_request_.exchange(0, std::memory_order_acq_rel);
      steps > 0 && !cushioning_) {
    if (phase != Phase::Running || !begin_cushion(steps, CardFault::None))
      esc_busy_.store(false, std::memory_order_release);
    else
      output_.feed(*this);
    return;
  }
  switch (phase) {
    case Phase::Idle:
    case Phase::Faulted:
      ring_.clear();  // late writes are dropped, never played
      return;
    case Phase::Armed: {
      if (bus_->failed()) return trip(CardFault::Hardware, false);
      if (options_.estop.tripped(inputs)) return trip(CardFault::EStop, false);
      if (limit_closed) return trip(CardFault::Limit, false);
      const std::size_t queued = ring_.available();
      if (queued == 0) {
        if (drain_pending) acknowledge_drain(drain_request);
        return;
      }
      if (queued >= prime_words_.load(std::memory_order_relaxed) || drain_pending ||
          stream_end > stream_position_)
        begin_output();
      return;
    }
    case Phase::Running:
    case Phase::Starved:
    case Phase::Drained:
      return run_output(phase, inputs, limit_closed, drain_request, drain_pending, stream_end);
  }
}

void Pci7200Card::run_output(Phase phase, std::uint32_t inputs, bool limit_closed,
                             std::uint64_t drain_request, bool drain_pending,
                             std::uint64_t stream_end) {
  const FeederSnapshot s = output_.poll();
  const std::uint64_t into_card = output_.words_into_card();
  if (s.device_lost || s.dma_error) return trip(CardFault::Hardware, false);
  if (options_.estop.tripped(inputs)) return trip(CardFault::EStop, true);  // even a cushion
  if (cushioning_) return run_cushion(s);
  if (limit_closed) {
    // limits.cushion_steps: the cushion first, the fault once it has played.
    if (phase == Phase::Running && begin_cushion(options_.cushion.limit_steps, CardFault::Limit))
      return output_.feed(*this);
    return trip(CardFault::Limit, true);
  }

  // The card flags a pacer tick that found its FIFO empty.
  const bool underran = (bus_->read32(Bar::Card, card::kDioCsr) & card::kDioDoUnderrun) != 0;
  const std::size_t queued = ring_.available();
  const bool words_waiting = s.words_staged || queued > 0;  // not yet handed to the card
  const bool words_due = s.in_flight || words_waiting;
  const bool all_played = s.fifo_empty && !words_due;
  // An empty FIFO with words still waiting is the reload deadline missed: counted as an
  // underrun even if the next tick has not come yet, so detection does not rest on the
  // card's flag alone.
  const bool ran_dry = s.fifo_empty && !s.in_flight && words_waiting;

  switch (phase) {
    case Phase::Running:
      // Played out to the end of a stream that ended at rest (end_stream), nothing after it
      // taken: no underrun, however long the pacer has ticked on the empty FIFO since; what
      // was written since starts a new stretch. (Issue 26: a hold on this card ended in an
      // underrun, at once or at the resume's first word.)
      if (s.fifo_empty && !s.in_flight && !s.words_staged && stream_position_ == stream_end) {
        ticks_.store(into_card, std::memory_order_release);
        if (drain_pending && queued == 0) acknowledge_drain(drain_request);
        phase_.store(Phase::Drained, std::memory_order_release);
        return;
      }
      if ((underran && words_due) || ran_dry) return trip(CardFault::Underrun, true);
      if (all_played) {
        ticks_.store(into_card, std::memory_order_release);
        if (drain_pending) {
          acknowledge_drain(drain_request);
          phase_.store(Phase::Drained, std::memory_order_release);
        } else if (underran) {
          // Ran out with nothing asked for: a word written from now on is late.
          phase_.store(Phase::Starved, std::memory_order_release);
        }
        return;
      }
      output_.feed(*this);
      if (s.fifo_empty) {
        ticks_.store(into_card, std::memory_order_release);
      } else {
        // Up to a FIFO's worth has entered but not yet played.
        const std::uint64_t lower =
            into_card - std::min<std::uint64_t>(into_card, amcc::kFifoWords);
        if (lower > ticks_.load(std::memory_order_relaxed))
          ticks_.store(lower, std::memory_order_release);
      }
      return;
    case Phase::Starved:
      if (queued > 0) return trip(CardFault::Underrun, false);
      if (drain_pending) {
        acknowledge_drain(drain_request);
        phase_.store(Phase::Drained, std::memory_order_release);
      }
      return;
    case Phase::Drained:
      // After a drain the next words start a new stretch of output, as at start().
      if (queued > 0 && (queued >= prime_words_.load(std::memory_order_relaxed) || drain_pending ||
                         stream_end > stream_position_))
        return begin_output();
      if (queued == 0 && drain_pending) acknowledge_drain(drain_request);
      return;
    default:
      return;
  }
}

void Pci7200Card::begin_output() {
  output_.feed(*this);
  // The FIFO is filled first, so the first paced tick already has a word.
  bus_->write32(Bar::Card, card::kDioCsr, card::kDioDoTimerPaced | card::kDioDoUnderrun);
  phase_.store(Phase::Running, std::memory_order_release);
}

void Pci7200Card::halt_output(bool play_out) {
  output_.stop_transfers();
  bool empty = output_.fifo_empty();
  if (play_out) {
    const auto tick =
        std::chrono::nanoseconds(static_cast<std::int64_t>(std::ceil(tick_seconds_ * 1e9)));
    for (std::uint32_t i = 0; !empty && i <= amcc::kFifoWords; ++i) {
      bus_->sleep_for(tick);
      empty = output_.fifo_empty();
    }
  }
  // A control word alone stops the counter until a new count is written.
  bus_->write32(Bar::Card, card::kCounterControl,
                i8254::control_word(i8254::kPacerCounter, i8254::kPacerMode));
  bus_->write32(Bar::Card, card::kDioCsr, card::kDioDoUnderrun);
  const std::uint64_t into_card = output_.words_into_card();
  std::uint64_t ticks = into_card;
  if (!empty) {
    const std::uint64_t lower = into_card - std::min<std::uint64_t>(into_card, amcc::kFifoWords);
    ticks = std::max(lower, ticks_.load(std::memory_order_relaxed));
  }
  if (cushioning_) end_cushion(ticks);  // counted before the ticks (and any fault) show
  ticks_.store(ticks, std::memory_order_release);
  bus_->write32(Bar::Amcc, amcc::kMcsr, amcc::kMcsrP2aFifoReset | amcc::kMcsrReadPriority);
  bus_->write32(Bar::Amcc, amcc::kMcsr, amcc::kMcsrReadPriority);
}

void Pci7200Card::trip(CardFault fault, bool play_out) {
  halt_output(play_out);
  ring_.clear();
  fault_.store(fault, std::memory_order_release);
  phase_.store(Phase::Faulted, std::memory_order_release);
}

// The words already in the card play first; the cushion decelerates from the last of them,
// each channel's rate from its last two steps before it (the trail).
bool Pci7200Card::begin_cushion(int steps, CardFault fault) {
  if (steps <= 0) return false;
  auto plan = [&](std::uint64_t from) {
    std::array<ChannelMotion, kAxisCount> motion{};
    std::array<std::int64_t, kAxisCount> since{};
    trail_.motion_at(from, tick_seconds_, motion, since);
    cushion_ = CushionStream(options_.cushion.pins, trail_.word_before(from), motion, since, steps,
                             options_.cushion.pulse_ticks);
    return !cushion_.done();
  };
  if (!plan(output_.words_into_card())) return false;  // nothing moves: transfers untouched
  output_.stop_transfers();                            // no more of the queue's words
  const std::uint64_t from = output_.words_into_card();
  if (!plan(from)) {  // came to rest meanwhile: the stream's end plays out as a dead stop
    ring_.clear();
    return false;
  }
  cushion_start_ = cushion_;
  cushion_from_ = from;
  cushion_fault_ = fault;
  cushioning_ = true;
  stream_position_ = from;  // the charge pump's phase goes on from the words played
  ring_.clear();
  return true;
}

// While the cushion plays: a pacer tick that finds the FIFO empty only holds the lines a
// tick longer (the words and their steps are the same), so underruns are not faults here.
void Pci7200Card::run_cushion(const FeederSnapshot& s) {
  ring_.clear();  // words written meanwhile are dropped, never played
  if (s.fifo_empty && !s.in_flight && !s.words_staged && cushion_.done()) {
    if (cushion_fault_ != CardFault::None) return trip(cushion_fault_, false);
    halt_output(false);
    phase_.store(Phase::Idle, std::memory_order_release);
    esc_busy_.store(false, std::memory_order_release);
    return;
  }
  output_.feed(*this);
}

void Pci7200Card::end_cushion(std::uint64_t ticks) {
  const std::uint64_t words = ticks > cushion_from_ ? ticks - cushion_from_ : 0;
  cushion_result_ = {cushion_from_,
                     words == cushion_.given() ? cushion_.steps() : cushion_start_.steps_in(words)};
  cushion_ready_.store(true, std::memory_order_release);
  cushioning_ = false;
}

bool Pci7200Card::active() const {
  const Phase phase = phase_.load(std::memory_order_acquire);
  return phase != Phase::Idle && phase != Phase::Faulted;
}

void Pci7200Card::acknowledge_drain(std::uint64_t request) {
  drains_done_.store(request, std::memory_order_release);
}

}  // namespace gantry::pci7200
