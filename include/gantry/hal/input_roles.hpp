// What the machine does with each bit of the card's input word: the profile's wiring
// ([inputs]) and VN's limit switch and input modes, in one place for the cards and the
// controller.
#pragma once

#include <cstdint>

namespace gantry {

struct Settings;

// Input bits at whose active level something must happen: bit b is active when it reads
// (active_high >> b) & 1.
struct InputTrip {
  std::uint32_t mask = 0;         // 0: nothing
  std::uint32_t active_high = 0;  // per masked bit: 1 active when high, 0 when low
  std::uint32_t active(std::uint32_t bits) const { return ~(bits ^ active_high) & mask; }
  bool tripped(std::uint32_t bits) const { return active(bits) != 0; }
  InputTrip without(std::uint32_t bits) const { return {mask & ~bits, active_high & ~bits}; }
};

// E-stop and limit switches stop the card by itself (its driver latches them); a stop
// switch is the operator's pause, from outside (the controller watches it).
struct InputRoles {
  InputTrip estop;   // [inputs] estop_bit: the pulses stop at once
  InputTrip limits;  // [inputs] min_bit, max_bit and VN's limit inputs; none with VN 1 = 0
  InputTrip stops;   // VN's stop inputs, and input 4 when it is not the E-stop
};

InputRoles input_roles(const Settings& s);

}  // namespace gantry
