// A clock for tests: time moves only when the player sleeps (free-running) or when the test
// moves it (gated), so every run of a test sees the same ticks.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>

#include "gpiod/tick_clock.hpp"

namespace gantry {

class VirtualClock : public TickClock {
 public:
  // Free-running: a sleep jumps time to its deadline at once. Gated: a sleep blocks until
  // the test advances time to its deadline (advance_to) or the card interrupts it.
  enum class Mode { FreeRunning, Gated };
  explicit VirtualClock(Mode mode = Mode::FreeRunning) : mode_(mode) {}

  std::int64_t now_ns() override;
  void sleep_until_ns(std::int64_t deadline_ns) override;
  void interrupt() override;
  void clear_interrupt() override;

  // The next `count` wakes happen `late_ns` after their deadline.
  void make_late(std::int64_t late_ns, int count = 1);
  // Gated: waits (up to `limit` of real time) for a sleep that began after the last one
  // this returned; its deadline, or nullopt when the player did not sleep again.
  std::optional<std::int64_t> wait_for_sleeper(
      std::chrono::milliseconds limit = std::chrono::seconds(2));
  // Gated: moves time to `t_ns` (never backwards), waking a sleep whose deadline it reaches.
  void advance_to(std::int64_t t_ns);
  std::uint64_t sleeps() const;  // sleep_until_ns calls so far: the player's wake-ups

 private:
  const Mode mode_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::int64_t now_ = 0;
  bool interrupted_ = false;
  std::int64_t late_ns_ = 0;
  int late_count_ = 0;
  bool sleeping_ = false;
  std::int64_t sleep_deadline_ = 0;
  std::uint64_t sleep_count_ = 0, reported_sleep_ = 0;
};

}  // namespace gantry
