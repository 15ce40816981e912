// The number-literal grammar, shared by the expression lexer and text-to-number conversion.
#pragma once

#include <charconv>  // from_chars: locale-independent, unlike strtod
#include <cmath>     // HUGE_VAL
#include <cstddef>
#include <cstdint>
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

// Ten to the k, exactly, for k <= 22 (every such power is a double).
inline constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                    1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                    1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

inline std::optional<double> value(std::string_view lit);

// The value of `digits[.digits]` or `.digits` (no sign, no exponent; the caller scanned it).
// When the digits form an integer m < 2^53 and there are k <= 22 decimals, m and 10^k are
// both exact doubles and one IEEE division rounds m / 10^k correctly: the same double
// from_chars gives (Clinger's fast path). Longer literals go through value(); one too large
// for a double is infinite.
inline double plain_value(std::string_view t) {
  std::uint64_t m = 0;
  int digits = 0, decimals = -1;
  for (char c : t) {
    if (c == '.') {
      decimals = 0;
      continue;
    }
    m = m * 10 + static_cast<unsigned>(c - '0');
    ++digits;
    if (decimals >= 0) ++decimals;
  }
  if (digits <= 15 && decimals <= 22)  // 15 digits: m < 10^15 < 2^53
    return static_cast<double>(m) / kPow10[decimals < 0 ? 0 : decimals];
  return value(t).value_or(HUGE_VAL);
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

namespace gantry {

// Parses a whole trimmed string as a number literal with an optional sign; nullopt if it is
// not one.
std::optional<double> parse_number_literal(std::string_view text);

}  // namespace gantry
