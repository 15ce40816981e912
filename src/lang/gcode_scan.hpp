// The scanning G-code's block reader and expression compiler share (docs/gcode.md, "Blocks").
// Private to src/lang.
#pragma once

#include <cstdint>  // uint64_t
#include <string>
#include <string_view>

#include "gantry/lang/number_literal.hpp"  // is_digit, plain_value, kPow10
#include "gantry/lang/scan.hpp"            // upper

namespace gantry::gcode_scan {

inline bool is_space(char c) {
  return c == ' ' || c == '\t';
}
using literal::is_digit;
using scan::upper;

// A number with spaces between its digits: LinuxCNC ignores them (`X 1 . 5` is X1.5).
inline size_t read_spaced(std::string_view s, size_t i, double* value) {
  size_t end = i;  // past the last digit or point read
  bool point = false, digit = false, spaced = false;
  for (size_t j = i; j < s.size(); ++j) {
    const char c = s[j];
    if (is_space(c)) {
      if (end == i) break;  // the caller skips the spaces before a value
      continue;
    }
    if (!is_digit(c) && (c != '.' || point)) break;
    point |= c == '.';
    digit |= c != '.';
    spaced |= j != end;
    end = j + 1;
  }
  if (!digit) return i;
  if (!spaced) {
    *value = literal::plain_value(s.substr(i, end - i));
  } else {
    std::string packed;
    for (size_t k = i; k < end; ++k)
      if (!is_space(s[k])) packed += s[k];
    *value = literal::plain_value(packed);
  }
  return end;
}

// Reads `digits[.digits]` or `.digits` at s[i]; returns the end, or i when there is none.
// The hot path of every block: the digits are summed as they are scanned, and the value is
// the one plain_value gives (a mantissa of at most 15 digits over a power of ten, else the
// exact conversion).
inline size_t read_unsigned(std::string_view s, size_t i, double* value) {
  std::uint64_t m = 0;
  int digits = 0, decimals = -1;
  size_t j = i;
  for (; j < s.size(); ++j) {
    const char c = s[j];
    if (is_digit(c)) {
      m = m * 10 + static_cast<unsigned>(c - '0');  // wraps past 19 digits: not used then
      ++digits;
      decimals += decimals >= 0;
    } else if (c == '.' && decimals < 0) {
      decimals = 0;
    } else {
      break;
    }
  }
  if (digits == 0) return i;
  if (j < s.size() && is_space(s[j])) {  // more digits after spaces: the slow path
    size_t k = j;
    while (k < s.size() && is_space(s[k])) ++k;
    if (k < s.size() && (is_digit(s[k]) || (s[k] == '.' && decimals < 0)))
      return read_spaced(s, i, value);
  }
  *value = digits <= 15 && decimals <= 22
               ? static_cast<double>(m) / literal::kPow10[decimals < 0 ? 0 : decimals]
               : literal::plain_value(s.substr(i, j - i));
  return j;
}

inline bool word_at(std::string_view s, size_t i, std::string_view word) {
  if (i + word.size() > s.size()) return false;
  for (size_t k = 0; k < word.size(); ++k)
    if (upper(s[i + k]) != word[k]) return false;
  return true;
}

inline constexpr std::string_view kFunctions[] = {"ABS",    "ACOS", "ASIN", "ATAN", "COS",
                                                  "EXISTS", "EXP",  "FIX",  "FUP",  "LN",
                                                  "ROUND",  "SIN",  "SQRT", "TAN"};

// The function named at s[i] (followed by `[`, spaces allowed), or empty.
inline std::string_view function_at(std::string_view s, size_t i) {
  for (std::string_view f : kFunctions) {
    if (!word_at(s, i, f)) continue;
    size_t j = i + f.size();
    while (j < s.size() && is_space(s[j])) ++j;
    if (j < s.size() && s[j] == '[') return f;
  }
  return {};
}

}  // namespace gantry::gcode_scan
