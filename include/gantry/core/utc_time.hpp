// The time now as an ISO 8601 UTC stamp ("2026-11-27T02:55:25Z"), as saved files record it.
#pragma once

#include <chrono>
#include <ctime>
#include <string>

namespace gantry {

inline std::string utc_timestamp() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace gantry
