// Register semantics and virtual time of the emulated PCI-7200.
#include "pci7200/emulated_pci7200.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace gantry::pci7200 {
namespace {

constexpr std::uint32_t kCountMask = amcc::kMaxTransferBytes * 2 - 1;
constexpr std::uint32_t kMcsrControlBits = 0x0000ff00;  // transfer control; status is computed
constexpr std::uint32_t kIntcsrControlBits = 0xff00ffff;
constexpr std::uint32_t kIntcsrAsserted = 1u << 23;
constexpr std::uint64_t kDefaultPeriodCycles = 20;  // 200 kHz, when no pacer is programmed
constexpr auto kFeederTimeout = std::chrono::seconds(10);

std::uint64_t cycles_of(std::chrono::nanoseconds d) {
  return static_cast<std::uint64_t>(
      std::llround(static_cast<double>(d.count()) * i8254::kClockHz / 1e9));
}

}  // namespace

EmulatedPci7200::EmulatedPci7200(EmulatedPci7200Config config)
    : config_(config),
      poll_cycles_(std::max<std::uint64_t>(1, cycles_of(config.poll_interval))),
      host_memory_(config.dma_words),
      stepped_(config.stepped) {
  config_.fifo_words = std::max<std::size_t>(1, config_.fifo_words);
  wall_last_ = std::chrono::steady_clock::now();
}

// ---------------------------------------------------------------------------------------
// Registers.

std::uint32_t EmulatedPci7200::read32(Bar bar, std::uint32_t offset) {
  std::lock_guard lock(mutex_);
  if (lost_) return 0xffffffff;
  return bar == Bar::Amcc ? read_amcc(offset) : read_card(offset);
}

void EmulatedPci7200::write32(Bar bar, std::uint32_t offset, std::uint32_t value) {
  std::lock_guard lock(mutex_);
  if (lost_) return;
  if (bar == Bar::Amcc)
    write_amcc(offset, value);
  else
    write_card(offset, value);
}

std::uint32_t EmulatedPci7200::read_amcc(std::uint32_t offset) const {
  switch (offset) {
    case amcc::kMrar:
      return mrar_;
    case amcc::kMrtc:
      return mrtc_;
    case amcc::kIntcsr: {
      const bool asserted = (intcsr_status_ & amcc::kIntcsrReadComplete) &&
                            (intcsr_control_ & amcc::kIntcsrReadCompleteEnable);
      return intcsr_control_ | intcsr_status_ | (asserted ? kIntcsrAsserted : 0);
    }
    case amcc::kMcsr: {
      std::uint32_t status = 0;
      if (fifo_.size() >= config_.fifo_words) status |= amcc::kMcsrP2aFifoFull;
      if (fifo_.empty()) status |= amcc::kMcsrP2aFifoEmpty;
      if (mrtc_ == 0) status |= amcc::kMcsrP2aCountZero;
      return mcsr_control_ | status;
    }
    default:
      return 0;  // mailboxes and the FIFO port read nothing useful from this side
  }
}

std::uint32_t EmulatedPci7200::read_card(std::uint32_t offset) const {
  switch (offset) {
    case card::kDiPort:
      return inputs_;
    case card::kDoPort:
      return output_port_;
    case card::kDioCsr:
      return dio_csr_ | (underrun_flag_ ? card::kDioDoUnderrun : 0);
    case card::kIntCsr:
      return int_csr_;
    default:
      return 0;  // counter reads need a latch command; the driver never reads them
  }
}

void EmulatedPci7200::write_amcc(std::uint32_t offset, std::uint32_t value) {
  switch (offset) {
    case amcc::kFifo:
      // A PCI write into a full FIFO would be retried by the bridge; the driver checks first.
      if (fifo_.size() < config_.fifo_words) fifo_.push_back(value);
      return;
    case amcc::kMrar:
      mrar_ = value;
      return;
    case amcc::kMrtc:
      mrtc_ = value & kCountMask;
      dma_fill();
      return;
    case amcc::kIntcsr:
      intcsr_control_ = value & kIntcsrControlBits;
      intcsr_status_ &= ~(value & amcc::kIntcsrStatusBits);
      return;
    case amcc::kMcsr:
      if (value & amcc::kMcsrP2aFifoReset) fifo_.clear();
      mcsr_control_ = value & kMcsrControlBits;
      dma_fill();
      return;
    default:
      return;
  }
}

void EmulatedPci7200::write_card(std::uint32_t offset, std::uint32_t value) {
  switch (offset) {
    case card::kCounter0:
    case card::kCounter1:
    case card::kCounter2:
      write_count(static_cast<int>(offset / 4), value & 0xff);
      return;
    case card::kCounterControl:
      write_counter_control(value & 0xff);
      return;
    case card::kDoPort:
      // While paced, the latch takes its words from the FIFO only.
      if (!(dio_csr_ & card::kDioDoTimerPaced)) output_port_ = value;
      return;
    case card::kDioCsr:
      if (value & card::kDioDoClearFifo) fifo_.clear();
      if (value & card::kDioDoUnderrun) underrun_flag_ = false;
      dio_csr_ = value & ~(card::kDioDoClearFifo | card::kDioDoUnderrun);
      dma_fill();
      return;
    case card::kIntCsr:
      int_csr_ = value;
      return;
    default:
      return;
  }
}

void EmulatedPci7200::write_counter_control(std::uint32_t value) {
  const int select = static_cast<int>(value >> 6) & 3;
  const int read_load = static_cast<int>(value >> 4) & 3;
  if (select == 3 || read_load == 0) return;  // read-back and latch commands change nothing
  Counter& c = counters_[select];
  c.mode = static_cast<int>(value >> 1) & 7;
  if (c.mode >= 6) c.mode -= 4;  // modes 6 and 7 are 2 and 3
  c.read_load = read_load;
  c.awaiting_msb = false;
  // A control word resets the counter: it waits for a new count.
  c.running = false;
}

void EmulatedPci7200::write_count(int index, std::uint32_t byte) {
  Counter& c = counters_[index];
  switch (c.read_load) {
    case 1:
      c.count = byte;
      break;
    case 2:
      c.count = byte << 8;
      break;
    default:
      if (!c.awaiting_msb) {
        c.pending_lsb = byte;
        c.awaiting_msb = true;
        return;
      }
      c.count = c.pending_lsb | byte << 8;
      c.awaiting_msb = false;
      break;
  }
  c.running = true;
  cycles_in_period_ = 0;
}

// ---------------------------------------------------------------------------------------
// Time.

std::uint64_t EmulatedPci7200::pacer_period_cycles() const {
  auto period = [](const Counter& c) -> std::uint64_t {
    if (!c.running || (c.mode != 2 && c.mode != 3)) return 0;  // only these repeat
    return c.count == 0 ? 65536 : c.count;
  };
  const std::uint64_t one = period(counters_[1]);
  if (!(int_csr_ & card::kIntT1T2Cascade)) return one;
  return one * period(counters_[2]);
}

std::uint64_t EmulatedPci7200::nominal_period_cycles() const {
  const std::uint64_t period = pacer_period_cycles();
  if (period > 0) return period;
  return counters_[1].count > 1 ? counters_[1].count : kDefaultPeriodCycles;
}

void EmulatedPci7200::run_cycles(std::uint64_t cycles) {
  const std::uint64_t period = pacer_period_cycles();
  if (period == 0) return;
  cycles_in_period_ += cycles;
  while (cycles_in_period_ >= period) {
    cycles_in_period_ -= period;
    tick();
  }
}

void EmulatedPci7200::tick() {
  if (!(dio_csr_ & card::kDioDoTimerPaced) || lost_) return;
  if (fifo_.empty()) {
    // The latch keeps its last word; the card flags the missed tick.
    underrun_flag_ = config_.flags_underrun;
    ++underrun_ticks_;
    return;
  }
  output_port_ = fifo_.front();
  fifo_.pop_front();
  played_.push_back(output_port_);
  dma_fill();
}

// The bus is far faster than any pacer, so the engine keeps the FIFO topped up at once.
void EmulatedPci7200::dma_fill() {
  while ((mcsr_control_ & amcc::kMcsrReadEnable) && mrtc_ >= 4 &&
         fifo_.size() < config_.fifo_words) {
    const std::uint64_t index = (std::uint64_t{mrar_} - config_.dma_bus_address) / 4;
    if (mrar_ < config_.dma_bus_address || mrar_ % 4 != 0 || index >= host_memory_.size()) {
      intcsr_status_ |= amcc::kIntcsrMasterAbort;  // nothing answers at that address
      mcsr_control_ &= ~amcc::kMcsrReadEnable;
      return;
    }
    fifo_.push_back(host_memory_[index]);
    mrar_ += 4;
    mrtc_ -= 4;
    if (mrtc_ == 0) {
      intcsr_status_ |= amcc::kIntcsrReadComplete;
      ++transfers_completed_;
    }
  }
}

DmaBuffer EmulatedPci7200::dma_buffer() {
  return {std::span<std::uint32_t>(host_memory_), config_.dma_bus_address};
}

void EmulatedPci7200::pause() {
  std::unique_lock lock(mutex_);
  ++pauses_;
  if (!stepped_ && config_.wall_clock) {
    lock.unlock();
    std::this_thread::sleep_for(config_.poll_interval);
    lock.lock();
    const auto now = std::chrono::steady_clock::now();
    // The card holds the FIFO and what the bridge has still to read of the transfer in
    // flight (it keeps the FIFO topped up): a late feeder slows the card down only past
    // what it holds, the reload deadline of a real card (not the FIFO alone: with the real
    // 8 words the card could hardly keep the wall clock's pace).
    const std::uint64_t held =
        fifo_.size() + ((mcsr_control_ & amcc::kMcsrReadEnable) ? mrtc_ / 4 : 0);
    const std::uint64_t most =
        (std::max<std::uint64_t>(config_.fifo_words, held) - 1) * nominal_period_cycles();
    run_cycles(std::min(most, cycles_of(now - wall_last_)));
    wall_last_ = now;
    return;
  }
  if (!stepped_) {
    run_cycles(poll_cycles_);
    lock.unlock();
    std::this_thread::yield();
    return;
  }
  parked_ = true;
  changed_.notify_all();
  changed_.wait(lock, [this] { return grants_ > 0 || !attached_; });
  if (grants_ > 0) --grants_;
  parked_ = false;
}

void EmulatedPci7200::sleep_for(std::chrono::nanoseconds duration) {
  std::lock_guard lock(mutex_);
  run_cycles(cycles_of(duration));
}

void EmulatedPci7200::attach_feeder() {
  std::lock_guard lock(mutex_);
  attached_ = true;
}

void EmulatedPci7200::detach_feeder() {
  std::lock_guard lock(mutex_);
  attached_ = false;
  changed_.notify_all();
}

void EmulatedPci7200::run_one_feeder_pass(std::unique_lock<std::mutex>& lock) {
  const auto deadline = std::chrono::steady_clock::now() + kFeederTimeout;
  if (!changed_.wait_until(lock, deadline, [this] { return parked_ || !attached_; }))
    throw std::runtime_error("emulated PCI-7200: the feeder never paused");
  if (!attached_) return;
  ++grants_;
  changed_.notify_all();
  if (!changed_.wait_until(lock, deadline,
                           [this] { return (parked_ && grants_ == 0) || !attached_; }))
    throw std::runtime_error("emulated PCI-7200: the feeder did not finish its pass");
}

void EmulatedPci7200::advance(std::uint64_t ticks, std::uint64_t ticks_per_feeder_pass) {
  std::unique_lock lock(mutex_);
  const std::uint64_t step = std::max<std::uint64_t>(1, ticks_per_feeder_pass);
  while (ticks > 0) {
    if (stepped_) run_one_feeder_pass(lock);
    const std::uint64_t n = std::min(step, ticks);
    run_cycles(n * nominal_period_cycles());
    ticks -= n;
  }
  if (stepped_) run_one_feeder_pass(lock);
}

void EmulatedPci7200::advance_without_feeder(std::uint64_t ticks) {
  std::lock_guard lock(mutex_);
  run_cycles(ticks * nominal_period_cycles());
}

// ---------------------------------------------------------------------------------------
// Test controls and observations.

void EmulatedPci7200::set_inputs(std::uint32_t inputs) {
  std::lock_guard lock(mutex_);
  inputs_ = inputs;
}

void EmulatedPci7200::inject_dma_abort() {
  std::lock_guard lock(mutex_);
  intcsr_status_ |= amcc::kIntcsrMasterAbort;
  mcsr_control_ &= ~amcc::kMcsrReadEnable;
}

void EmulatedPci7200::remove_device() {
  std::lock_guard lock(mutex_);
  lost_ = true;
}

std::string EmulatedPci7200::describe() const {
  if (config_.dma_words == 0) return "emulated PCI-7200 (programmed I/O)";
  return fmt::format("emulated PCI-7200 (DMA, {}-word buffer)", config_.dma_words);
}

std::vector<std::uint32_t> EmulatedPci7200::played() const {
  std::lock_guard lock(mutex_);
  return played_;
}

std::uint64_t EmulatedPci7200::played_count() const {
  std::lock_guard lock(mutex_);
  return played_.size();
}

std::uint32_t EmulatedPci7200::output_port() const {
  std::lock_guard lock(mutex_);
  return output_port_;
}

bool EmulatedPci7200::pacer_running() const {
  std::lock_guard lock(mutex_);
  return pacer_period_cycles() > 0;
}

std::uint32_t EmulatedPci7200::pacer_count() const {
  std::lock_guard lock(mutex_);
  return counters_[1].count;
}

int EmulatedPci7200::pacer_mode() const {
  std::lock_guard lock(mutex_);
  return counters_[1].mode;
}

bool EmulatedPci7200::output_paced() const {
  std::lock_guard lock(mutex_);
  return (dio_csr_ & card::kDioDoTimerPaced) != 0;
}

bool EmulatedPci7200::dma_reading() const {
  std::lock_guard lock(mutex_);
  return (mcsr_control_ & amcc::kMcsrReadEnable) != 0;
}

std::size_t EmulatedPci7200::fifo_fill() const {
  std::lock_guard lock(mutex_);
  return fifo_.size();
}

std::uint64_t EmulatedPci7200::underrun_ticks() const {
  std::lock_guard lock(mutex_);
  return underrun_ticks_;
}

std::uint64_t EmulatedPci7200::transfers_completed() const {
  std::lock_guard lock(mutex_);
  return transfers_completed_;
}

std::uint64_t EmulatedPci7200::feeder_pauses() const {
  std::lock_guard lock(mutex_);
  return pauses_;
}

bool EmulatedPci7200::feeder_attached() const {
  std::lock_guard lock(mutex_);
  return attached_;
}

}  // namespace gantry::pci7200
