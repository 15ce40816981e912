// A register-level emulation of the PCI-7200, so that the driver's init, pacer programming,
// FIFO/DMA refill, underrun and shutdown paths run in CI where no card exists. It models the
// AMCC S5933's P2A FIFO (8 words) and its bus-master read engine (MRAR/MRTC, count zero,
// aborts), the card's 8254 (control word, LSB/MSB latch, modes, T1-T2 cascade) with counter 1
// pacing the output, the paced output latch and its underrun flag, the input port, and
// virtual time. README.md ("The emulation") says what it leaves out.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "pci7200/pci7200_bus.hpp"        // Pci7200Bus
#include "pci7200/pci7200_registers.hpp"  // amcc::kFifoWords

namespace gantry::pci7200 {

struct EmulatedPci7200Config {
  std::size_t dma_words = 2 * 4096;  // host DMA buffer; 0: no DMA, programmed I/O only
  std::size_t fifo_words = amcc::kFifoWords;
  std::uint32_t dma_bus_address = 0x0010'0000;
  // Free-running time: how much virtual time passes each time the feeder pauses.
  std::chrono::nanoseconds poll_interval{10'000};
  // Stepped time: virtual time passes only in advance(), which runs the feeder in lockstep.
  bool stepped = false;
  // Wall-clock time (not stepped): each pause sleeps poll_interval and then plays the ticks
  // the wall clock has moved on, at most what the card holds (the FIFO and the transfer in
  // flight) less one, or a FIFO's worth less one (a descheduled feeder makes the emulated
  // card slow down rather than miss a DMA reload, which on a real card needs a PREEMPT_RT
  // kernel): the pace of a real card, for the hold-latency bench.
  bool wall_clock = false;
  // Whether the DIO register reads back the underrun flag (public sources do not settle it).
  bool flags_underrun = true;
};

class EmulatedPci7200 final : public Pci7200Bus {
 public:
  explicit EmulatedPci7200(EmulatedPci7200Config config = {});

  std::uint32_t read32(Bar bar, std::uint32_t offset) override;
  void write32(Bar bar, std::uint32_t offset, std::uint32_t value) override;
  bool failed() const override { return false; }
  DmaBuffer dma_buffer() override;
  void pause() override;
  void sleep_for(std::chrono::nanoseconds duration) override;
  void attach_feeder() override;
  void detach_feeder() override;
  std::string describe() const override;

  // Stepped time: plays `ticks` pacer periods, letting the feeder make one pass before every
  // `ticks_per_feeder_pass` ticks and once at the end. Throws if the feeder does not return.
  void advance(std::uint64_t ticks, std::uint64_t ticks_per_feeder_pass = 4);
  // Plays `ticks` periods while the feeder gets no pass (as if descheduled).
  void advance_without_feeder(std::uint64_t ticks);
  void set_inputs(std::uint32_t inputs);
  void inject_dma_abort();  // the bridge reports a master abort and stops reading
  void remove_device();     // from now on every register reads as all ones

  std::vector<std::uint32_t> played() const;  // every word the output latch took, in order
  std::uint64_t played_count() const;
  std::uint32_t output_port() const;
  bool pacer_running() const;  // counter 1 counting in a periodic mode
  std::uint32_t pacer_count() const;
  int pacer_mode() const;
  bool output_paced() const;  // the output is clocked by the pacer
  bool dma_reading() const;   // the bridge's bus-master read engine is enabled
  std::size_t fifo_fill() const;
  std::uint64_t underrun_ticks() const;  // paced ticks that found the FIFO empty
  std::uint64_t transfers_completed() const;
  std::uint64_t feeder_pauses() const;
  bool feeder_attached() const;

 private:
  struct Counter {
    int mode = 0;
    int read_load = 3;  // 1 LSB, 2 MSB, 3 LSB then MSB
    bool running = false;
    bool awaiting_msb = false;
    std::uint32_t count = 0;
    std::uint32_t pending_lsb = 0;
  };

  // All with mutex_ held.
  std::uint32_t read_amcc(std::uint32_t offset) const;
  std::uint32_t read_card(std::uint32_t offset) const;
  void write_amcc(std::uint32_t offset, std::uint32_t value);
  void write_card(std::uint32_t offset, std::uint32_t value);
  void write_counter_control(std::uint32_t value);
  void write_count(int index, std::uint32_t byte);
  std::uint64_t pacer_period_cycles() const;  // 0 when the pacer is not running
  std::uint64_t nominal_period_cycles() const;
  void run_cycles(std::uint64_t cycles);
  void tick();
  void dma_fill();
  void run_one_feeder_pass(std::unique_lock<std::mutex>& lock);

  EmulatedPci7200Config config_;
  std::uint64_t poll_cycles_;

  mutable std::mutex mutex_;
  std::condition_variable changed_;

  // The bridge.
  std::vector<std::uint32_t> host_memory_;
  std::deque<std::uint32_t> fifo_;
  std::uint32_t mrar_ = 0, mrtc_ = 0;
  std::uint32_t mcsr_control_ = 0;
  std::uint32_t intcsr_control_ = 0, intcsr_status_ = 0;
  std::uint64_t transfers_completed_ = 0;

  // The card.
  Counter counters_[3];
  std::uint32_t inputs_ = 0;
  std::uint32_t output_port_ = 0;
  std::uint32_t dio_csr_ = 0;
  std::uint32_t int_csr_ = 0;
  bool underrun_flag_ = false;
  bool lost_ = false;

  // Time and observations.
  std::uint64_t cycles_in_period_ = 0;
  std::vector<std::uint32_t> played_;
  std::uint64_t underrun_ticks_ = 0;

  std::chrono::steady_clock::time_point wall_last_;  // wall_clock: the last pause's time

  // Lockstep with the feeder.
  bool stepped_;
  bool attached_ = false;
  bool parked_ = false;
  std::uint64_t grants_ = 0;
  std::uint64_t pauses_ = 0;
};

}  // namespace gantry::pci7200
