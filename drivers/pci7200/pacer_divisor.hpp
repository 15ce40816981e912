// The 8254 divisor that paces the output: pacer = clock / divisor, exactly, within the range
// the counter takes.
#pragma once

#include <string>

namespace gantry::pci7200 {

struct PacerDivisor {
  int divisor = 0;
  std::string error;  // empty when the pacer is possible
  bool ok() const { return error.empty(); }
};

// Rejects a pacer that is not the clock divided by a whole number in 2..65535.
PacerDivisor pacer_divisor(double clock_hz, double pacer_hz);

}  // namespace gantry::pci7200
