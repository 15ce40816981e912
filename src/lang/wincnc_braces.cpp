// WinCNC's `{}` substitution (manual, "Braces"): `G0Z{TH1+2}` moves Z to tool height 1 plus 2.
#include <fmt/format.h>  // messages

#include <cctype>  // isalpha, isalnum
#include <string>
#include <vector>

#include "gantry/lang/wincnc.hpp"

namespace gantry {
namespace {

class Braces {
 public:
  Braces(std::string_view s, const SourceLoc& at, const WinCncVariable* lookup)
      : s_(s), at_(at), lookup_(lookup) {}

  double whole() {
    i_ = 1;  // past '{'
    double sum = 0;
    double term = operand(true);
    char pending = '+';
    int numbers = 0;
    while (true) {
      skip();
      if (i_ >= s_.size()) error(i_, "this '{' is never closed with '}'");
      const char c = s_[i_];
      if (c == '}') break;
      if (c != '+' && c != '-' && c != '*' && c != '/')
        error(i_, fmt::format("unexpected '{}' in braces: WinCNC's braces join a value and "
                              "numbers with + - * /, as in {{TH1+2}}",
                              c));
      const size_t op_at = i_++;
      const double n = operand(false);
      ++numbers;
      if (c == '*') {
        term *= n;
      } else if (c == '/') {
        if (n == 0 && lookup_) error(op_at, "division by zero in braces");
        term = n == 0 ? 0 : term / n;
      } else {
        sum = pending == '+' ? sum + term : sum - term;
        term = n;
        pending = c;
      }
    }
    if (numbers == 0)
      error(0,
            "WinCNC's braces need a value and a number, as {TH1+2} (manual, \"Braces\": "
            "the second one must be a number); write {TH1+0} for the value alone");
    if (i_ + 1 != s_.size()) error(i_ + 1, "unexpected text after '}'");
    return pending == '+' ? sum + term : sum - term;
  }

 private:
  [[noreturn]] void error(size_t i, const std::string& what) const {
    SourceLoc l = at_;
    l.column += static_cast<int>(i);
    fail(l, what);
  }
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
  }
  // A number (signed, with an optional point) or, first only, a variable name.
  double operand(bool first) {
    skip();
    const size_t b = i_;
    if (i_ < s_.size() && std::isalpha(static_cast<unsigned char>(s_[i_]))) {
      if (!first)
        error(b, "after the first value WinCNC's braces take numbers only (manual, \"Braces\")");
      std::string name;
      while (i_ < s_.size() && std::isalnum(static_cast<unsigned char>(s_[i_])))
        name += static_cast<char>(std::toupper(static_cast<unsigned char>(s_[i_++])));
      if (!lookup_) return 0;
      SourceLoc l = at_;
      l.column += static_cast<int>(b);
      return (*lookup_)(name, l);
    }
    size_t j = i_;
    if (j < s_.size() && (s_[j] == '-' || s_[j] == '+')) ++j;
    const size_t digits = j;
    bool point = false;
    while (j < s_.size() &&
           (std::isdigit(static_cast<unsigned char>(s_[j])) || (s_[j] == '.' && !point))) {
      point |= s_[j] == '.';
      ++j;
    }
    if (j == digits || (j == digits + 1 && point))
      error(b, first ? "expected a variable (such as TH1, LZ0, X) or a number in braces"
                     : "expected a number in braces");
    i_ = j;
    return std::stod(std::string(s_.substr(b, j - b)));
  }

  std::string_view s_;
  size_t i_ = 0;
  SourceLoc at_;
  const WinCncVariable* lookup_;
};

}  // namespace

double evaluate_wincnc_braces(std::string_view text, const SourceLoc& at,
                              const WinCncVariable* lookup) {
  return Braces(text, at, lookup).whole();
}

}  // namespace gantry
