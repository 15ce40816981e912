// A number as Gantry writes it into a part file or an exported G-code program: fixed
// decimals, no trailing zeros, never "-0". The tools, the converters and export share it.
#pragma once

#include <fmt/format.h>  // the digits

#include <string>

namespace gantry {

// At most `decimals` (at least 1) decimals: part files take 4, exported G-code 8.
inline std::string part_number(double v, int decimals = 4) {
  std::string s = fmt::format("{:.{}f}", v, decimals);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

}  // namespace gantry
