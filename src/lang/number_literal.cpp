// Text to number, as the language reads a value that is text (docs/language.md).
#include "gantry/lang/number_literal.hpp"

namespace gantry {
namespace {

bool is_space(char c) {  // a value read from a file or an answer may end its line
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

}  // namespace

std::optional<double> parse_number_literal(std::string_view text) {
  size_t b = 0, e = text.size();
  while (b < e && is_space(text[b])) ++b;
  while (e > b && is_space(text[e - 1])) --e;
  text = text.substr(b, e - b);
  bool negative = false;
  if (!text.empty() && (text[0] == '+' || text[0] == '-')) {
    negative = text[0] == '-';
    text.remove_prefix(1);
  }
  if (text.empty() || literal::scan(text, 0) != text.size()) return std::nullopt;
  // Without an exponent, the fast exact reading (plain_value: the same double as value());
  // it gives infinity only for a literal value() finds too large.
  std::optional<double> d;
  if (text.find_first_of("eE") == std::string_view::npos) {
    if (const double v = literal::plain_value(text); v != HUGE_VAL) d = v;
  } else {
    d = literal::value(text);
  }
  if (d && negative) *d = -*d;
  return d;
}

}  // namespace gantry
