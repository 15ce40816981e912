// Where the player thread gets the time and sleeps until a deadline. Production uses the
// monotonic clock; tests use a virtual clock, so the thread logic runs without real time.
#pragma once

#include <cstdint>

namespace gantry {

class TickClock {
 public:
  virtual ~TickClock() = default;
  virtual std::int64_t now_ns() = 0;
  // Returns at `deadline_ns` or later (at once when it has passed), or early after
  // interrupt(). Called from the real-time thread: must not allocate.
  virtual void sleep_until_ns(std::int64_t deadline_ns) = 0;
  // Makes current and later sleeps return at once, until clear_interrupt(): how stop()
  // wakes the player.
  virtual void interrupt() = 0;
  virtual void clear_interrupt() = 0;
};

// CLOCK_MONOTONIC with absolute-deadline clock_nanosleep (TIMER_ABSTIME): no drift from
// wake-up latency, since each deadline is computed from the stream's start, not the last
// wake-up. Sleeps are at most one input-sample period, so interrupt() need not wake them.
class MonotonicClock : public TickClock {
 public:
  std::int64_t now_ns() override;
  void sleep_until_ns(std::int64_t deadline_ns) override;
  void interrupt() override {}
  void clear_interrupt() override {}
};

}  // namespace gantry
