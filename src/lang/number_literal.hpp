// The number-literal grammar, shared by the expression lexer and text-to-number conversion.
#pragma once

#include <charconv>  // from_chars: locale-independent, unlike strtod
#include <cstddef>
#include <optional>
#include <string_view>
#include <system_error>  // errc

namespace gantry::literal {

inline bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// The end of the literal `digits ["." [digits]] | "." digits` plus an optional exponent
// `[eE][+-]?digits` starting at s[i], or i when none starts there. An `e` not followed by
// digits is not part of the literal (`5e` is 5 followed by `e`). No sign: a sign is an
// operator in expressions and is handled by the caller for text.
inline size_t scan(std::string_view s, size_t i) {
  const size_t n = s.size();
  size_t j = i;
  size_t digits = 0;
  while (j < n && is_digit(s[j])) ++j, ++digits;
  if (j < n && s[j] == '.') {
    ++j;
    while (j < n && is_digit(s[j])) ++j, ++digits;
  }
  if (digits == 0) return i;
  if (j < n && (s[j] == 'e' || s[j] == 'E')) {
    size_t k = j + 1;
    if (k < n && (s[k] == '+' || s[k] == '-')) ++k;
    if (k < n && is_digit(s[k])) {
      while (k < n && is_digit(s[k])) ++k;
      j = k;
    }
  }
  return j;
}

// The value of a whole literal as scan() accepts it; nullopt when it is too large for a
// double. Literals too small for a double are 0.
inline std::optional<double> value(std::string_view lit) {
  double d = 0;
  const auto r = std::from_chars(lit.data(), lit.data() + lit.size(), d);
  if (r.ec == std::errc::result_out_of_range) {
    // Underflow needs a negative exponent or, without one, a value below 1 (`0.000…1`);
    // anything else that is out of range is too large.
    const size_t e = lit.find_first_of("eE");
    bool tiny;
    if (e != std::string_view::npos) {
      tiny = e + 1 < lit.size() && lit[e + 1] == '-';
    } else {
      const std::string_view whole = lit.substr(0, lit.find('.'));
      tiny = whole.find_first_not_of('0') == std::string_view::npos;
    }
    if (!tiny) return std::nullopt;
    return 0.0;
  }
  return d;
}

}  // namespace gantry::literal
