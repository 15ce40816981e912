// Axis naming and the integer step position (the real-valued Vec6 is in core/vec6.hpp).
#pragma once

#include <array>
#include <cstdint>

namespace gantry {

inline constexpr int kAxisCount = 6;

enum class Axis : int { X = 0, Y, Z, A, B, C };

// A position or displacement in motor steps, as the card counts them.
using Steps6 = std::array<std::int64_t, kAxisCount>;

inline constexpr std::array<char, kAxisCount> kAxisLetters{'x', 'y', 'z', 'a', 'b', 'c'};

constexpr int index(Axis a) {
  return static_cast<int>(a);
}

}  // namespace gantry
