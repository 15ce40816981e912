// The PCI-7200 as a gantry::Card. The card's 8254 counter 1 paces the output, one 32-bit word
// per tick, with no software jitter; a real-time feeder thread keeps the card's FIFO fed (a
// DMA double buffer, or programmed I/O) from a lock-free ring that write() fills.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <thread>

#include "gantry/hal/card.hpp"            // Card, CardFault
#include "gantry/hal/limit_filter.hpp"    // LimitFilter
#include "gantry/hal/word_ring.hpp"       // WordRing
#include "pci7200/charge_pump.hpp"        // ChargePump
#include "pci7200/output_feeder.hpp"      // OutputFeeder, WordSource
#include "pci7200/pci7200_bus.hpp"        // Pci7200Bus
#include "pci7200/pci7200_registers.hpp"  // i8254::kClockHz
#include "pci7200/pi_mutex.hpp"           // PiMutex
#include "pci7200/realtime_thread.hpp"    // RealtimeRequest

namespace gantry::pci7200 {

struct Pci7200Options {
  double clock_hz = i8254::kClockHz;
  std::size_t ring_words = std::size_t{1} << 18;  // write() to feeder: 1.3 s at 200 kHz
  std::size_t prime_words = 0;  // queued before output starts; 0: one DMA half (PIO: 64)
  int charge_pump_bit = -1;     // -1: no charge pump
  double charge_pump_hz = 12'500;
  std::uint32_t idle_word = 0;  // the output word when the card is opened and closed
  InputTrip estop;              // trips CardFault::EStop while any masked bit is active
  InputTrip limits;             // trips CardFault::Limit as any becomes active, by limit_rule
  // The profile's [limits] (travel_only, debounce in input samples: one a feeder pass), the
  // rule every card applies; default: any limit bit as it becomes active.
  LimitFilter limit_rule;
  // The cushioned stop (limits.cushion_steps after a limit trip; the pins and pulse width
  // for limits.esc_steps too); default: a dead stop.
  CushionRule cushion;
  RealtimeRequest realtime;  // for the feeder thread
};

class Pci7200Card : public Card, private WordSource {
 public:
  // Quiesces the card (pacer halted, transfers off, idle word out) and starts the feeder.
  Pci7200Card(std::shared_ptr<Pci7200Bus> bus, Pci7200Options options = {});
  ~Pci7200Card() override;
  Pci7200Card(const Pci7200Card&) = delete;
  Pci7200Card& operator=(const Pci7200Card&) = delete;

  // Throws std::invalid_argument when the pacer is not clock / N with N in 2..65535 (and
  // std::logic_error after close()). Output begins once `prime_words` are queued, or at
  // drain().
  void start(double pacer_hz) override;
  // Blocks while the ring is full; the feeder makes room as words play.
  void write(std::span<const std::uint32_t> words) override;
  void drain() override;
  // The words written so far end at rest (Card::end_stream: a hold, the end of the motion):
  // running dry right after them is no underrun, a stream shorter than prime_words starts,
  // and the next words start a new stretch of output, as after drain().
  void end_stream() override;
  // The words already inside the card's FIFO (at most 8) play out first, so that
  // ticks_played() is exact and no pulse is cut; then the pacer halts.
  void stop(std::uint32_t idle_word) override;
  // limits.esc_steps: the feeder's next pass stops taking the queue's words and feeds the
  // cushion (CushionStream) after the words already in the card; once it has played, this
  // stops as stop() does. Output not running stops at once.
  void stop_cushioned(std::uint32_t idle_word, int steps) override;
  std::optional<CushionPlayed> cushion_played() const override {
    if (!cushion_ready_.load(std::memory_order_acquire)) return std::nullopt;
    return cushion_result_;
  }
  // Exact once output has stopped (drained, stopped, underrun); while words play it may lag
  // by up to the FIFO depth.
  std::uint64_t ticks_played() const override { return ticks_.load(std::memory_order_acquire); }
  std::uint32_t inputs() const override { return inputs_.load(std::memory_order_acquire); }
  // The step generator bounds its lead over ticks_played(); output starts at prime_words
  // (Pci7200Options), which the lead never goes below.
  bool queues_words() const override { return true; }
  std::uint64_t start_words() const override {
    return prime_words_.load(std::memory_order_acquire);
  }
  CardFault fault() const override { return fault_.load(std::memory_order_acquire); }
  void set_trips(const InputTrip& estop, const InputTrip& limits) override;
  // The feeder compares every sample of the inputs (each pass, well under a millisecond):
  // the edge's tick is the sample's, and a `stop` bit halts the pacer in that pass.
  void watch(const InputWatch& w) override;
  std::optional<InputEdge> watch_fired() override;

  double pacer_hz() const { return pacer_hz_.load(std::memory_order_acquire); }
  bool uses_dma() const { return output_.uses_dma(); }
  bool feeder_running() const { return feeder_running_.load(std::memory_order_acquire); }
  // What the feeder thread was granted (scheduling, CPU, locked memory).
  const std::string& realtime_report() const { return realtime_report_; }
  std::string describe() const { return bus_->describe(); }

  // Halts output, writes the idle word and joins the feeder. Idempotent.
  void close();

 private:
  enum class Phase { Idle, Armed, Running, Starved, Drained, Faulted };

  std::size_t take(std::span<std::uint32_t> out) override;  // WordSource, for the feeder
  void feeder_loop();
  void pass();
  void run_output(Phase phase, std::uint32_t inputs, bool limit_closed, std::uint64_t drain_request,
                  bool drain_pending, std::uint64_t stream_end);
  void begin_output();
  void halt_output(bool play_out);
  void trip(CardFault fault, bool play_out);
  // The cushioned stop, in the feeder's pass: begun after the words already in the card
  // (false, and nothing changed, when nothing moves), fed as the stream's words were, and
  // counted when output halts (halt_output).
  bool begin_cushion(int steps, CardFault fault);
  void run_cushion(const FeederSnapshot& s);
  void end_cushion(std::uint64_t ticks);
  bool active() const;
  void acknowledge_drain(std::uint64_t request);

  std::shared_ptr<Pci7200Bus> bus_;
  Pci7200Options options_;
  WordRing ring_;
  OutputFeeder output_;

  PiMutex hardware_;  // held by a feeder pass and by start, stop and close
  // Under hardware_:
  ChargePump pump_;
  std::uint64_t stream_position_ = 0;  // words taken from the ring since start()
  std::uint32_t last_inputs_ = 0;      // the sample before: limit switches trip on closing
  std::uint32_t last_taken_ = 0;       // the last word taken from the ring (steps, travel_only)
  EdgeDetector watcher_;
  std::optional<InputEdge> fired_;
  StepTrail trail_;  // the steps taken, deep enough for the words not yet played
  bool cushioning_ = false;
  CushionStream cushion_, cushion_start_;  // the words to come; as it began
  std::uint64_t cushion_from_ = 0;
  CardFault cushion_fault_ = CardFault::None;
  CushionPlayed cushion_result_;  // written before cushion_ready_
  std::atomic<bool> cushion_ready_{false};
  std::atomic<int> esc_request_{0};    // stop_cushioned's steps, for the next pass
  std::atomic<bool> esc_busy_{false};  // until its cushion has played (or none could)
  std::atomic<std::size_t> prime_words_{0};
  double tick_seconds_ = 0;

  std::atomic<Phase> phase_{Phase::Idle};
  std::atomic<CardFault> fault_{CardFault::None};
  std::atomic<std::uint64_t> ticks_{0};
  std::atomic<std::uint32_t> inputs_{0};
  std::atomic<double> pacer_hz_{0};
  std::atomic<std::uint64_t> drains_requested_{0};
  std::atomic<std::uint64_t> drains_done_{0};
  std::uint64_t written_ = 0;                 // the producer's: words written since start()
  std::atomic<std::uint64_t> stream_end_{0};  // written_ at the last end_stream()
  std::atomic<bool> exit_{false};
  std::atomic<bool> feeder_ready_{false};
  std::atomic<bool> feeder_running_{false};
  std::string realtime_report_;  // written by the feeder before feeder_ready_
  std::thread feeder_thread_;
  bool closed_ = false;
};

}  // namespace gantry::pci7200
