// The bounds a part file's numbers are held to, and the one checked way a double becomes a
// whole tick or step count (docs/reliability.md, "What is bounded").
#pragma once

#include <cmath>    // abs, llround
#include <cstddef>  // size_t
#include <cstdint>  // int64_t
#include <optional>

namespace gantry {

// No move may reach further than this from the table base (units, or degrees on a rotary
// axis), whether soft limits are checked or not: 25 km in inches, 1 km in millimetres,
// 2,777 turns. Past it a position is a mistake, and its step count nears a double's precision.
inline constexpr double kMaxCoordinate = 1e6;

// The longest text a value may hold (a join beyond it is a located error), bytes.
inline constexpr std::size_t kMaxTextBytes = std::size_t{1} << 20;

// Every whole number up to 2^53 is exact in a double, and a sum of a few such counts cannot
// overflow an int64: the most ticks or steps a conversion gives (at 200 kHz, 1,400 years).
inline constexpr double kMaxWholeCount = 9007199254740992.0;  // 2^53

// `x` rounded to the nearest whole number, or nullopt when it is not finite or beyond
// kMaxWholeCount (where std::llround's result is unspecified: it garbled the steps).
inline std::optional<std::int64_t> checked_llround(double x) {
  if (!(std::abs(x) <= kMaxWholeCount)) return std::nullopt;  // NaN fails this too
  return std::llround(x);
}

}  // namespace gantry
