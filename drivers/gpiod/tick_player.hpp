// What happens at a tick, apart from when: the player takes words from the queue, drives the
// lines whose bits changed, samples the inputs every few ticks and decides when the card
// faults. The card's thread calls it at each tick's deadline; tests may call it directly.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <optional>

#include "gantry/hal/card.hpp"
#include "gantry/hal/word_ring.hpp"
#include "gpiod/gpio_lines.hpp"
#include "gpiod/gpio_map.hpp"

namespace gantry {

class TickPlayer {
 public:
  // Keeps references to `lines` and `ring`. The outputs start at map.initial_word.
  TickPlayer(const GpioMap& map, GpioLines& lines, WordRing& ring);

  // A new run at `pacer_hz` (start()): tick 0, no fault, no late ticks.
  void reset(double pacer_hz);
  // A stream of words begins at the current tick; its first tick samples the inputs.
  void begin_stream();

  // The first tick, from ticks_played() on, at which anything happens: a word changes a
  // mapped line, the inputs are due for a sample, or the queue holds no word for it. The
  // ticks before it repeat the current output, so the thread sleeps through them.
  std::uint64_t next_event_tick() const;

  // Stopped: a cushioned stop asked for by request_cushion() has played (or nothing moved);
  // the card stops as asked, without a fault.
  enum class Outcome { Played, StreamEnded, Faulted, Stopped };
  // Plays through `tick` (from next_event_tick()), `late_ns` after its deadline. With no
  // word for `tick`, the stream ends when `stream_may_end` (drain() was called) and the
  // card underruns otherwise. Real-time path: no allocation, no locks.
  // A limit trip with map.cushion.limit_steps, or a request_cushion(), plays the cushioned
  // stop's words (CushionStream) from that tick instead of the queue's; ticks_played() stays
  // at the cushion's first tick until it has played, then counts its words, cushion_played()
  // says what it was, and only then does a limit trip fault the card.
  Outcome play_through(std::uint64_t tick, std::int64_t late_ns, bool stream_may_end);
  // From any thread: the next tick played begins a cushion of `steps` (limits.esc_steps)
  // and the stream stops after it (Outcome::Stopped).
  void request_cushion(int steps) { esc_request_.store(steps, std::memory_order_release); }
  // The player leaves a stream before its end (the card stops it): a cushion under way
  // counts the words it played.
  void leave_stream();
  std::optional<CushionPlayed> cushion_played() const {
    if (!cushion_ready_.load(std::memory_order_acquire)) return std::nullopt;
    return cushion_result_;
  }

  // Outside a stream only (the thread idle, or stopped): read the inputs now; drive the
  // lines to `word` now. False (with a Hardware fault) on a device error.
  bool sample_inputs();
  bool output(std::uint32_t word);
  // Faults the card from outside (a refused start).
  void fail(CardFault fault) { fault_.store(fault, std::memory_order_release); }
  // The inputs that fault the card (the map's E-stop and limit bits until set), from any
  // thread: each trip is one atomic word, so the player never sees a mask without its levels.
  void set_trips(const InputTrip& estop, const InputTrip& limits);
  // The input watch (Card::watch), armed from any thread with the inputs as they are and
  // compared at every sample: an edge's tick is its sample's. Its `stop` bits are not acted
  // on here (the controller halts the motion as for any card).
  void arm_watch(const InputWatch& w, std::uint32_t bits_now);
  std::optional<InputEdge> watch_fired() const;

  std::uint64_t ticks_played() const { return ticks_played_.load(std::memory_order_acquire); }
  // The tick whose word the lines were last driven for: ticks_played()'s, and a cushion's
  // own ticks while ticks_played() waits at its start.
  std::uint64_t line_tick() const { return line_tick_.load(std::memory_order_acquire); }
  std::uint32_t inputs() const { return inputs_.load(std::memory_order_acquire); }
  CardFault fault() const { return fault_.load(std::memory_order_acquire); }
  std::uint64_t late_ticks() const { return late_ticks_.load(std::memory_order_relaxed); }
  std::int64_t worst_late_ns() const { return worst_late_ns_.load(std::memory_order_relaxed); }
  std::uint64_t sample_every_ticks() const { return sample_every_; }
  // After a Hardware fault: which operation failed ("write" or "read") and its errno.
  const char* failed_operation() const;
  int failed_errno() const { return failed_errno_.load(std::memory_order_relaxed); }

 private:
  bool write_word(std::uint32_t word);
  bool read_inputs();
  void hardware_fault(int operation);

  GpioLines& lines_;
  WordRing& ring_;
  const GpioMap& map_;

  std::array<std::uint64_t, 32> lines_of_bit_{};  // output lines each word bit drives
  std::uint32_t mapped_bits_ = 0;                 // bits that drive any line
  std::array<int, 64> bit_of_input_{};            // input-word bit of each input line

  std::uint64_t sample_every_ = 1;
  std::int64_t late_tolerance_ns_ = 0;
  std::uint32_t current_word_ = 0;  // the word the lines show
  std::uint64_t next_sample_tick_ = 0;
  std::uint32_t last_sample_ = 0;  // the inputs at the sample before
  LimitFilter limit_rule_;         // the map's: the player's own copy

  // The cushioned stop (the player's, but for the request and the published result).
  bool begin_cushion(std::uint64_t tick, int steps, CardFault fault);
  Outcome play_cushion(std::uint64_t tick, std::int64_t late_ns);
  void end_cushion(std::uint64_t end_tick, CardFault fault);
  void count_late(std::int64_t late_ns);
  StepTrail trail_;  // each channel's last two steps, from the words played
  double tick_s_ = 0;
  bool cushioning_ = false;
  CushionStream cushion_, cushion_start_;  // the words to come; as it began
  std::uint64_t cushion_from_ = 0;
  CardFault cushion_fault_ = CardFault::None;
  std::atomic<int> esc_request_{0};
  CushionPlayed cushion_result_;  // written before cushion_ready_
  std::atomic<bool> cushion_ready_{false};

  std::atomic<std::uint64_t> ticks_played_{0};
  std::atomic<std::uint64_t> line_tick_{0};
  std::atomic<std::uint32_t> inputs_{0};
  std::atomic<std::uint64_t> estop_trip_{0}, limit_trip_{0};  // mask << 32 | active_high
  void sample_watch(std::uint64_t tick, std::uint32_t bits);  // the player, at a sample
  // The watch: written by arm_watch, then watch_gen_ bumped; the player re-arms its
  // detector when it sees a new generation, and publishes an edge with that generation.
  std::atomic<std::uint64_t> watch_levels_{0};  // mask << 32 | levels
  std::atomic<std::uint32_t> watch_bits_now_{0};
  std::atomic<int> watch_debounce_{1};                   // InputWatch::debounce, in input samples
  std::atomic<unsigned> watch_gen_{0}, fired_gen_{~0u};  // none fired yet
  std::atomic<std::uint64_t> edge_tick_{0};
  std::atomic<std::uint32_t> edge_bits_{0};
  std::atomic<int> edge_bit_{0};
  unsigned armed_gen_ = 0;  // the player's
  EdgeDetector detector_;   // the player's
  std::atomic<CardFault> fault_{CardFault::None};
  std::atomic<std::uint64_t> late_ticks_{0};
  std::atomic<std::int64_t> worst_late_ns_{0};
  std::atomic<int> failed_operation_{0}, failed_errno_{0};
};

}  // namespace gantry
