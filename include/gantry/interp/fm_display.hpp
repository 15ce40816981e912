// Friendly Motion's G58 display line (and G25's, which writes the same line to the output
// file): quoted text, variables' values and strings, one space apart, in upper case
// (docs/friendlymotion.md, "Data files, scribed text and the display"). Pure: the caller looks
// the values up; nothing here reads the executor's state.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace gantry {

// One element of a G58 / G25 command, its value already looked up.
struct FmDisplayItem {
  enum class Kind { Text, Number, String };
  Kind kind = Kind::Text;
  std::string text;   // Text: the quoted text (without its quotes); String: @n's contents
  double number = 0;  // Number: the variable's value

  static FmDisplayItem quoted(std::string_view t) { return {Kind::Text, std::string(t), 0}; }
  static FmDisplayItem value(double v) { return {Kind::Number, "", v}; }
  static FmDisplayItem string(std::string_view s) { return {Kind::String, std::string(s), 0}; }
};

// A number as G58 shows it and G26 writes it: four decimals, `3.0000`; a value that rounds to
// zero shows as 0.0000, never -0.0000.
std::string fm_number_text(double v);

// The line G58 shows (and G25 writes, before its CR/LF): each element in turn, one space
// between two elements, quoted text and strings in upper case. `G58"The""value""of""V1""is"V1`
// with V1 = 3 is `THE VALUE OF V1 IS 3.0000`.
std::string fm_display_line(std::span<const FmDisplayItem> items);

}  // namespace gantry
