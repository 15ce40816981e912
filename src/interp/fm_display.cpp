// G58 / G25's line (docs/friendlymotion.md, "Data files, scribed text and the display").
#include "gantry/interp/fm_display.hpp"

#include <fmt/format.h>

#include <cmath>

#include "gantry/core/text.hpp"  // ascii::upper

namespace gantry {

std::string fm_number_text(double v) {
  std::string s = fmt::format("{:.4f}", v);
  // -0.00001 prints as -0.0000: the manual's displays never show a signed zero.
  if (s == "-0.0000") s.erase(0, 1);
  return s;
}

// Upper case as the manual's examples show it (`"The"` is displayed `THE`): Friendly Motion
// reads its command line in capitals, so a string set from a command is upper case too.
std::string fm_display_line(std::span<const FmDisplayItem> items) {
  std::string out;
  bool first = true;
  for (const FmDisplayItem& item : items) {
    if (!first) out += ' ';
    first = false;
    if (item.kind == FmDisplayItem::Kind::Number)
      out += fm_number_text(item.number);
    else
      out += ascii::upper(item.text);
  }
  return out;
}

}  // namespace gantry
