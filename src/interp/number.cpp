// Numeric parameters. Issue 3's expression evaluator replaces this with full expressions.
#include <fmt/format.h>  // messages

#include <cctype>   // isdigit
#include <cstdlib>  // strtod

#include "gantry/interp/interpreter.hpp"

namespace gantry {

double evaluate_number(const Param& p, std::string_view what) {
  const std::string& t = p.text;
  // Accept: [+-] digits [. digits] | [+-] . digits, then an optional exponent.
  size_t i = 0;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  size_t digits = 0;
  while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i, ++digits;
  if (i < t.size() && t[i] == '.') {
    ++i;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i, ++digits;
  }
  if (digits > 0 && i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    size_t j = i + 1;
    if (j < t.size() && (t[j] == '+' || t[j] == '-')) ++j;
    size_t exp_digits = 0;
    while (j < t.size() && std::isdigit(static_cast<unsigned char>(t[j]))) ++j, ++exp_digits;
    if (exp_digits > 0) i = j;
  }
  if (digits == 0 || i != t.size())
    fail(p.loc, fmt::format("expected a number for {}, found '{}'", what, t));
  return std::strtod(t.c_str(), nullptr);
}

}  // namespace gantry
