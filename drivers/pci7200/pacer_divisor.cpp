// Divisor arithmetic for the output pacer.
#include "pci7200/pacer_divisor.hpp"

#include <fmt/format.h>

#include <cmath>

#include "pci7200/pci7200_registers.hpp"

namespace gantry::pci7200 {

PacerDivisor pacer_divisor(double clock_hz, double pacer_hz) {
  if (!std::isfinite(clock_hz) || !std::isfinite(pacer_hz) || clock_hz <= 0 || pacer_hz <= 0)
    return {0,
            fmt::format("pacer {} Hz from clock {} Hz: both must be positive", pacer_hz, clock_hz)};
  const double exact = clock_hz / pacer_hz;
  const double rounded = std::round(exact);
  // The card plays one word per period of the divided clock; a pacer that is not an exact
  // division would silently run at another rate.
  if (std::abs(exact - rounded) > 1e-9 * exact)
    return {0, fmt::format("pacer {} Hz is not {} Hz divided by a whole number (it would need "
                           "{:.4f}); choose clock / N",
                           pacer_hz, clock_hz, exact)};
  if (rounded < i8254::kMinDivisor || rounded > i8254::kMaxDivisor)
    return {0, fmt::format("pacer {} Hz needs divisor {:.0f}; the PCI-7200's 8254 takes {}..{} "
                           "({} Hz down to {:.2f} Hz)",
                           pacer_hz, rounded, i8254::kMinDivisor, i8254::kMaxDivisor,
                           clock_hz / i8254::kMinDivisor, clock_hz / i8254::kMaxDivisor)};
  return {static_cast<int>(rounded), {}};
}

}  // namespace gantry::pci7200
