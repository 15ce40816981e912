// The absolute deadline of every tick of a stream, exact in integer nanoseconds.
#pragma once

#include <cmath>
#include <cstdint>

namespace gantry {

// Tick n of a stream is due at start + floor(n * 1e9 / pacer_hz) ns, with the rate taken to
// the millihertz. Computing each deadline from the stream's start (never by adding periods)
// keeps rounding and wake-up latency from accumulating into drift.
class PacerSchedule {
 public:
  PacerSchedule() = default;
  PacerSchedule(double pacer_hz, std::int64_t start_ns)
      : rate_mhz_(static_cast<std::uint64_t>(std::llround(pacer_hz * 1000))),
        whole_ns_(kPicosPerSecond / rate_mhz_),
        rest_(kPicosPerSecond % rate_mhz_),
        start_ns_(start_ns) {}

  // n * 1e12 / rate_mhz, split so that nothing overflows for 2^64 / rate_mhz ticks (84
  // days at 50 kHz).
  std::int64_t deadline(std::uint64_t n) const {
    return start_ns_ + static_cast<std::int64_t>(n * whole_ns_ + n * rest_ / rate_mhz_);
  }
  std::int64_t period_ns() const { return static_cast<std::int64_t>(whole_ns_); }

 private:
  static constexpr std::uint64_t kPicosPerSecond = 1'000'000'000'000;  // 1e9 ns x 1000 mHz
  std::uint64_t rate_mhz_ = 1000;
  std::uint64_t whole_ns_ = 0, rest_ = 0;
  std::int64_t start_ns_ = 0;
};

}  // namespace gantry
