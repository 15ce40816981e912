// A sleep on the monotonic clock, as the real buses' waits use: clock_nanosleep is what
// PREEMPT_RT wakes precisely, and it is unaffected by wall-clock changes.
#pragma once

#include <time.h>

#include <chrono>

namespace gantry::pci7200 {

inline void sleep_monotonic(std::chrono::nanoseconds duration) {
  if (duration.count() <= 0) return;
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(duration.count() / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(duration.count() % 1'000'000'000);
  clock_nanosleep(CLOCK_MONOTONIC, 0, &ts, nullptr);
}

}  // namespace gantry::pci7200
