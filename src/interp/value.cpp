// Conversions between the language's numbers and text.
#include "gantry/interp/value.hpp"

#include <fmt/format.h>  // number formatting and messages

#include <cmath>  // isfinite, trunc, fabs

#include "gantry/lang/number_literal.hpp"  // parse_number_literal
#include "gantry/core/any_bytes.hpp"   // echoed: long texts are cut in messages

namespace gantry {

namespace {

// Long texts are cut in messages so the error line stays readable.
std::string quoted_excerpt(std::string_view s) {
  return fmt::format("\"{}\"", echoed(s, 40));
}

}  // namespace

double Value::to_number(const SourceLoc& loc, std::string_view what) const {
  if (is_number()) return num();
  if (std::optional<double> d = parse_number_literal(str())) return *d;
  // A bare "value" reads badly in "value holds ..."; name the thing when we can.
  if (what == "value") {
    if (str().empty()) fail(loc, "expected a number but found an empty text");
    fail(loc, fmt::format("expected a number but found the text {}", quoted_excerpt(str())));
  }
  if (str().empty()) fail(loc, fmt::format("expected a number but {} is an empty text", what));
  fail(loc, fmt::format("expected a number but {} holds the text {}", what, quoted_excerpt(str())));
}

std::string Value::to_string() const {
  return is_number() ? format_number(num()) : str();
}

// The handbook says numbers are single precision, "7-8 digits" (002:L162); printing 7
// significant digits hides double-precision noise (0.1+0.2 prints 0.3) without showing more
// than the original controller could. Whole numbers below 1e15 print every digit so counters
// and integer ids never round. Fixed-point otherwise; scientific only for |v| >= 1e15 or
// |v| < 1e-7, where fixed-point would need more than 7 zeros.
std::string format_number(double d) {
  if (!std::isfinite(d)) return std::isnan(d) ? "nan" : (d > 0 ? "inf" : "-inf");
  if (d == 0) return "0";  // also -0
  const double a = std::fabs(d);
  if (a < 1e15 && d == std::trunc(d)) return fmt::format("{:.0f}", d);

  // Round to 7 significant digits first: rounding may carry into a new leading digit
  // (9.9999999 -> 10), so the exponent must come from the rounded text.
  const std::string sci = fmt::format("{:.6e}", a);  // d.dddddde[+-]XX
  std::string digits = sci.substr(0, 1) + sci.substr(2, 6);
  const size_t epos = sci.find('e');
  const int exp = std::stoi(sci.substr(epos + 1));
  while (digits.size() > 1 && digits.back() == '0') digits.pop_back();

  std::string out = d < 0 ? "-" : "";
  if (exp >= 15 || exp < -7) {
    out += digits[0];
    if (digits.size() > 1) out += "." + digits.substr(1);
    out += fmt::format("e{}{}", exp < 0 ? '-' : '+', std::abs(exp));
  } else if (exp >= 0) {
    const size_t whole = static_cast<size_t>(exp) + 1;
    if (digits.size() <= whole) {
      out += digits + std::string(whole - digits.size(), '0');
    } else {
      out += digits.substr(0, whole) + "." + digits.substr(whole);
    }
  } else {
    out += "0." + std::string(static_cast<size_t>(-exp - 1), '0') + digits;
  }
  return out;
}

}  // namespace gantry
