// A step/direction card on Linux GPIO lines: a real-time thread plays one 32-bit word per
// pacer tick onto the mapped lines, timed in software (see drivers/gpiod/README.md).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>

#include "gantry/hal/card.hpp"
#include "gantry/hal/word_ring.hpp"
#include "gpiod/gpio_lines.hpp"
#include "gpiod/gpio_map.hpp"
#include "gpiod/pacer_schedule.hpp"
#include "gpiod/realtime.hpp"
#include "gpiod/tick_clock.hpp"
#include "gpiod/tick_player.hpp"

namespace gantry {

class GpiodCard : public Card {
 public:
  // `map` must be valid (validate_gpio_map); throws std::invalid_argument otherwise. The
  // lines are sampled once here, so inputs() is meaningful before start().
  GpiodCard(const GpioMap& map, std::unique_ptr<GpioLines> lines,
            std::unique_ptr<TickClock> clock = std::make_unique<MonotonicClock>());
  // Stops the player; the lines keep their last level (call stop() for the idle word).
  ~GpiodCard() override;
  GpiodCard(const GpiodCard&) = delete;
  GpiodCard& operator=(const GpiodCard&) = delete;

  // A rate above kGpiodMaxPacerHz is refused: the card faults (Hardware), error() says why
  // and every word is dropped. A stream starts playing once map.start_words are queued or
  // drain() is called; running dry after drain() ends it, running dry before is an underrun.
  void start(double pacer_hz) override;
  // Blocks while the queue is full. Words written before start() or after stop() or a fault
  // are dropped. May race stop() from another thread (an E-stop); not start().
  void write(std::span<const std::uint32_t> words) override;
  void drain() override;
  // The words written so far end at rest (Card::end_stream: a hold, the end of the motion):
  // running dry right after them ends the stream, as after drain(), and a stream shorter than
  // start_words starts. Never blocks.
  void end_stream() override;
  void stop(std::uint32_t idle_word) override;
  // limits.esc_steps: the player thread plays the cushion (CushionStream) from its next tick
  // (within one input sample, as it wakes at least that often), then this stops as stop()
  // does. A stream not playing stops at once.
  void stop_cushioned(std::uint32_t idle_word, int steps) override;
  std::optional<CushionPlayed> cushion_played() const override { return player_.cushion_played(); }
  std::uint64_t ticks_played() const override { return player_.ticks_played(); }
  std::uint32_t inputs() const override { return player_.inputs(); }
  CardFault fault() const override { return player_.fault(); }
  // The step generator bounds its lead over ticks_played(); a stream starts at
  // map.start_words, which the lead never goes below.
  bool queues_words() const override { return true; }
  std::uint64_t start_words() const override { return map_.start_words; }
  void set_trips(const InputTrip& estop, const InputTrip& limits) override {
    player_.set_trips(estop, limits);
  }
  // Compared at every input sample: an edge's tick is its sample's (not the next block's).
  void watch(const InputWatch& w) override { player_.arm_watch(w, player_.inputs()); }
  std::optional<InputEdge> watch_fired() override { return player_.watch_fired(); }

  // Ticks played more than map.late_tolerance_ticks after their deadline, and the worst
  // lateness of any played tick, since start().
  std::uint64_t late_ticks() const { return player_.late_ticks(); }
  std::int64_t worst_late_ns() const { return player_.worst_late_ns(); }
  std::size_t queued_words() const { return ring_.size(); }
  std::uint64_t line_tick() const { return player_.line_tick(); }  // TickPlayer::line_tick
  // Why start() refused or what failed on a Hardware fault; empty otherwise.
  std::string error() const;
  // What real-time set-up the player thread got (after start(), with map.realtime).
  RealtimeResult realtime() const;

 private:
  void run();          // the player thread
  bool play_stream();  // false when the card faulted or is stopping
  void halt_player();  // ends the thread; lines keep their level

  const GpioMap map_;
  std::unique_ptr<GpioLines> lines_;
  std::unique_ptr<TickClock> clock_;
  WordRing ring_;
  TickPlayer player_;
  double pacer_hz_ = 0;

  std::thread thread_;
  std::atomic<bool> running_{false};  // the thread exists (start() until stop())
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> drain_requested_{false};
  std::atomic<bool> pacing_{false};  // a stream is playing

  std::mutex producer_mutex_;  // write() against stop() clearing the queue
  bool accepting_ = false;     // guarded by producer_mutex_
  std::uint64_t written_ = 0;  // words queued since start(); guarded by producer_mutex_
  std::atomic<std::uint64_t> stream_end_{0};  // written_ at the last end_stream()

  mutable std::mutex status_mutex_;
  std::string refusal_;
  RealtimeResult realtime_;
  bool memory_locked_ = false;  // mlockall is process-wide: once is enough
  std::string memory_note_;
};

}  // namespace gantry
