// G-code blocks: words, comments, parameter settings and expressions (docs/gcode.md).
// Spaces are allowed between a letter and its value; letters are read in either case.
#include <fmt/format.h>  // messages

#include <algorithm>  // equal
#include <cmath>      // math functions of expressions
#include <cstdint>    // uint64_t

#include "gantry/lang/gcode.hpp"
#include "gantry/lang/parser.hpp"  // LineParse, Statement
#include "gantry/lang/wincnc.hpp"  // evaluate_wincnc_braces
#include "gcode_oword.hpp"         // O-word lines
#include "number_literal.hpp"      // is_digit, plain_value
#include "scan.hpp"                // is_letter, upper

namespace gantry {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t';
}
using literal::is_digit;
using scan::is_letter;
using scan::upper;

// A number with spaces between its digits: LinuxCNC ignores them (`X 1 . 5` is X1.5).
size_t read_spaced(std::string_view s, size_t i, double* value) {
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
size_t read_unsigned(std::string_view s, size_t i, double* value) {
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

bool word_at(std::string_view s, size_t i, std::string_view word) {
  if (i + word.size() > s.size()) return false;
  for (size_t k = 0; k < word.size(); ++k)
    if (upper(s[i + k]) != word[k]) return false;
  return true;
}

constexpr std::string_view kFunctions[] = {"ABS", "ACOS", "ASIN", "ATAN",  "COS", "EXISTS", "EXP",
                                           "FIX", "FUP",  "LN",   "ROUND", "SIN", "SQRT",   "TAN"};

// The function named at s[i] (followed by `[`, spaces allowed), or empty.
std::string_view function_at(std::string_view s, size_t i) {
  for (std::string_view f : kFunctions) {
    if (!word_at(s, i, f)) continue;
    size_t j = i + f.size();
    while (j < s.size() && is_space(s[j])) ++j;
    if (j < s.size() && s[j] == '[') return f;
  }
  return {};
}

// ---- expressions ----------------------------------------------------------------------

// Brackets, signs, parameters and functions nested deeper than this are refused rather than
// risking the parser's stack (about 33,000 `[` overflowed it), as OpenSBP expressions are.
constexpr int kMaxNesting = 200;

class Expression {
 public:
  Expression(std::string_view s, const SourceLoc& at, const GcodeParameters* p)
      : s_(s), at_(at), params_(p) {}

  double whole() {
    const double v = value();
    skip();
    if (i_ < s_.size()) error(i_, "unexpected text after the value");
    return v;
  }

 private:
  [[noreturn]] void error(size_t i, const std::string& what) const {
    SourceLoc l = at_;
    l.column += static_cast<int>(i);
    fail(l, what);
  }
  SourceLoc loc(size_t i) const {
    SourceLoc l = at_;
    l.column += static_cast<int>(i);
    return l;
  }
  void skip() {
    while (i_ < s_.size() && is_space(s_[i_])) ++i_;
  }
  void expect(char c, const char* what) {
    skip();
    if (i_ >= s_.size() || s_[i_] != c) error(i_, fmt::format("expected '{}' {}", c, what));
    ++i_;
  }

  // A value: a number, [expression], #parameter, a function, each with an optional sign.
  // Every recursion passes through here, so one depth guard bounds the parser's stack.
  double value() {
    skip();
    if (i_ >= s_.size()) error(i_, "expected a value: a number, [expression] or #parameter");
    const Nest nest(*this);
    const char c = s_[i_];
    if (c == '-' || c == '+') {
      ++i_;
      const double v = value();
      return c == '-' ? -v : v;
    }
    if (c == '[') {
      ++i_;
      const double v = binary(0);
      expect(']', "to close the expression");
      return v;
    }
    if (c == '#') return parameter();
    double v = 0;
    if (const size_t e = read_unsigned(s_, i_, &v); e != i_) {
      i_ = e;
      return v;
    }
    if (const std::string_view f = function_at(s_, i_); !f.empty()) return function(f);
    error(i_, "expected a value: a number, [expression], #parameter or a function such as SIN[x]");
  }

  double parameter() {
    const size_t at = i_++;
    skip();
    if (i_ < s_.size() && s_[i_] == '<') {
      const std::string name = read_name();
      return params_ ? params_->named(name, loc(at)) : 0;
    }
    const double n = value();
    if (!params_) return 0;  // `#[#1 + 1]`: the number is known when the block runs
    if (n != std::round(n) || n < 1 || n > 5602)
      error(at, fmt::format("#{} is not a parameter: parameters are #1 to #5602", n));
    return params_->numbered(static_cast<int>(n), loc(at));
  }

  std::string read_name() {  // at '<'
    const size_t open = i_;
    const size_t close = s_.find('>', open);
    if (close == std::string_view::npos) error(open, "a parameter name opened with '<' needs '>'");
    std::string name;
    for (size_t k = open + 1; k < close; ++k)
      if (!is_space(s_[k]))
        name += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[k])));
    if (name.empty()) error(open, "the parameter name between < and > is empty");
    i_ = close + 1;
    return name;
  }

  double function(std::string_view f) {
    const size_t at = i_;
    i_ += f.size();
    if (f == "EXISTS") {
      expect('[', "after EXISTS");
      skip();
      if (i_ >= s_.size() || s_[i_] != '#')
        error(i_, "EXISTS takes a named parameter: EXISTS[#<name>]");
      ++i_;
      skip();
      if (i_ >= s_.size() || s_[i_] != '<')
        error(i_, "EXISTS takes a named parameter: EXISTS[#<name>]");
      const std::string name = read_name();
      expect(']', "to close EXISTS[...]");
      return params_ && params_->exists(name) ? 1 : 0;
    }
    expect('[', "after the function name");
    const double a = binary(0);
    expect(']', "to close the function's argument");
    constexpr double deg = M_PI / 180;
    auto domain = [&](bool ok) {
      // Without parameters (the load pass) every #n reads 0: only the syntax is checked.
      if (!ok && params_) error(at, fmt::format("{}[{}] is not defined", f, a));
    };
    if (f == "ATAN") {  // ATAN[y]/[x], in degrees
      expect('/', "in ATAN[y]/[x]");
      expect('[', "in ATAN[y]/[x]");
      const double b = binary(0);
      expect(']', "in ATAN[y]/[x]");
      return std::atan2(a, b) / deg;
    }
    if (f == "ABS") return std::abs(a);
    if (f == "ACOS") return domain(a >= -1 && a <= 1), std::acos(a) / deg;
    if (f == "ASIN") return domain(a >= -1 && a <= 1), std::asin(a) / deg;
    if (f == "COS") return std::cos(a * deg);
    if (f == "SIN") return std::sin(a * deg);
    if (f == "TAN") return std::tan(a * deg);
    if (f == "EXP") return std::exp(a);
    if (f == "FIX") return std::floor(a);
    if (f == "FUP") return std::ceil(a);
    if (f == "ROUND") return std::round(a);
    if (f == "LN") return domain(a > 0), std::log(a);
    return domain(a >= 0), std::sqrt(a);  // SQRT
  }

  // The binary operator at i_ and its precedence (higher binds tighter), or 0 when none.
  int op_at(std::string_view* op) {
    skip();
    if (i_ >= s_.size()) return 0;
    // Most values end at ']': no operator starts with any other character than these.
    if (std::string_view("*/+-MmEeNnGgLlAaOoXx").find(s_[i_]) == std::string_view::npos) return 0;
    struct Op {
      std::string_view text;
      int prec;
    };
    static constexpr Op ops[] = {{"**", 5}, {"*", 4},  {"/", 4},   {"MOD", 4}, {"+", 3},
                                 {"-", 3},  {"EQ", 2}, {"NE", 2},  {"GT", 2},  {"GE", 2},
                                 {"LT", 2}, {"LE", 2}, {"AND", 1}, {"OR", 1},  {"XOR", 1}};
    for (const Op& o : ops)
      if (word_at(s_, i_, o.text)) {
        *op = o.text;
        return o.prec;
      }
    return 0;
  }

  double binary(int min_prec) {
    double lhs = value();
    while (true) {
      std::string_view op;
      const int prec = op_at(&op);
      if (prec == 0 || prec < min_prec) return lhs;
      const size_t at = i_;
      i_ += op.size();
      const double rhs = binary(prec + 1);  // left-associative
      lhs = apply(op, lhs, rhs, at);
    }
  }

  double apply(std::string_view op, double a, double b, size_t at) const {
    if (op == "**") return std::pow(a, b);
    if (op == "*") return a * b;
    if (op == "/") {
      if (b == 0 && params_) error(at, "division by zero");
      return b == 0 ? 0 : a / b;
    }
    if (op == "MOD") {
      if (b == 0 && params_) error(at, "MOD by zero");
      if (b == 0) return 0;
      const double r = std::fmod(a, b);
      return r < 0 ? r + std::abs(b) : r;
    }
    if (op == "+") return a + b;
    if (op == "-") return a - b;
    // EQ and NE count values within 0.0001 as equal, as LinuxCNC does ([0.1 + 0.2 EQ 0.3] is 1);
    // GT, GE, LT and LE compare exactly there too.
    constexpr double kEqualWithin = 0.0001;
    if (op == "EQ") return std::abs(a - b) < kEqualWithin;
    if (op == "NE") return !(std::abs(a - b) < kEqualWithin);
    if (op == "GT") return a > b;
    if (op == "GE") return a >= b;
    if (op == "LT") return a < b;
    if (op == "LE") return a <= b;
    if (op == "AND") return a != 0 && b != 0;
    if (op == "OR") return a != 0 || b != 0;
    return (a != 0) != (b != 0);  // XOR
  }

  struct Nest {
    explicit Nest(Expression& e) : e_(e) {
      if (++e_.nesting_ > kMaxNesting)
        e_.error(e_.i_, fmt::format("this expression is nested more than {} deep; split it using "
                                    "parameters (#1 = [...])",
                                    kMaxNesting));
    }
    ~Nest() { --e_.nesting_; }
    Expression& e_;
  };

  std::string_view s_;
  size_t i_ = 0;
  int nesting_ = 0;
  SourceLoc at_;
  const GcodeParameters* params_;
};

// ---- blocks ---------------------------------------------------------------------------

class BlockReader {
 public:
  BlockReader(std::string_view s, const std::shared_ptr<const std::string>& file, int line_no,
              GcodeBlock* out)
      : s_(s), file_(file), line_no_(line_no), out_(out) {}

  void read() {
    skip();
    if (i_ < s_.size() && s_[i_] == '%') return;  // a program marker: nothing else counts
    if (i_ < s_.size() && s_[i_] == '/') ++i_;    // block delete: the switch is off
    bool first = true;
    while (true) {
      skip();
      if (i_ >= s_.size()) return;
      const char c = s_[i_];
      if (c == '(') {
        comment();
      } else if (c == ';') {
        return;
      } else if (c == '[') {
        // WinCNC's comment: to the matching ']' or the end of the line.
        const size_t close = s_.find(']', i_);
        if (!out_->bracket) {
          std::string_view text = s_.substr(
              i_ + 1, close == std::string_view::npos ? std::string_view::npos : close - i_ - 1);
          while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
          while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
          out_->bracket = std::string(text);
        }
        if (close == std::string_view::npos) return;
        i_ = close + 1;
      } else if (c == '#') {
        assignment();
      } else if (is_letter(c)) {
        word(first);
        first = false;
      } else {
        error(i_, fmt::format("unexpected '{}': a block is made of words such as G1 or X2.5, "
                              "comments in ( ) and #n = value settings",
                              c));
      }
    }
  }

 private:
  SourceLoc loc(size_t i) const { return SourceLoc{file_, line_no_, static_cast<int>(i) + 1}; }
  [[noreturn]] void error(size_t i, std::string what) const { fail(loc(i), std::move(what)); }
  void skip() {
    while (i_ < s_.size() && is_space(s_[i_])) ++i_;
  }

  void comment() {
    const size_t open = i_;
    const size_t close = s_.find(')', open);
    if (close == std::string_view::npos)
      error(open, "this comment is not closed: add ')' at its end");
    std::string_view body = s_.substr(open + 1, close - open - 1);
    size_t b = 0;
    while (b < body.size() && is_space(body[b])) ++b;
    struct Key {
      std::string_view word;
      GcodeMessage kind;
    };
    static constexpr Key keys[] = {{"MSG", GcodeMessage::Msg},
                                   {"PRINT", GcodeMessage::Print},
                                   {"DEBUG", GcodeMessage::Debug},
                                   {"ABORT", GcodeMessage::Abort}};
    for (const Key& key : keys) {
      size_t k = b + key.word.size();
      if (!word_at(body, b, key.word)) continue;
      while (k < body.size() && is_space(body[k])) ++k;
      if (k < body.size() && body[k] == ',') {
        std::string_view text = body.substr(k + 1);
        while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
        out_->message = std::string(text);
        out_->message_kind = key.kind;
        out_->message_column = static_cast<int>(open) + 1;
      }
    }
    if (body.find('(') != std::string_view::npos)
      error(open + 1 + body.find('('), "a comment cannot hold another '('");
    i_ = close + 1;
  }

  // The end of the value starting at i (spaces skipped), or i when there is none there.
  size_t value_end(size_t i) const {
    if (i < s_.size() && (s_[i] == '-' || s_[i] == '+')) {
      size_t j = i + 1;
      while (j < s_.size() && is_space(s_[j])) ++j;
      const size_t e = value_end(j);
      return e == j ? i : e;
    }
    if (i >= s_.size()) return i;
    if (s_[i] == '[') return bracket_end(i);
    if (s_[i] == '#') {
      size_t j = i + 1;
      while (j < s_.size() && is_space(s_[j])) ++j;
      if (j < s_.size() && s_[j] == '<') {
        const size_t close = s_.find('>', j);
        return close == std::string_view::npos ? s_.size() : close + 1;
      }
      const size_t e = value_end(j);
      return e == j ? j : e;  // `#` alone: the expression reports it
    }
    double v = 0;
    if (const size_t e = read_unsigned(s_, i, &v); e != i) return e;
    if (const std::string_view f = function_at(s_, i); !f.empty()) {
      size_t e = bracket_end(s_.find('[', i));
      if (f == "ATAN") {  // ATAN[y]/[x]
        size_t j = e;
        while (j < s_.size() && is_space(s_[j])) ++j;
        if (j < s_.size() && s_[j] == '/') {
          ++j;
          while (j < s_.size() && is_space(s_[j])) ++j;
          if (j < s_.size() && s_[j] == '[') e = bracket_end(j);
        }
      }
      return e;
    }
    return i;
  }

  size_t bracket_end(size_t open) const {  // past the ']' matching s_[open]
    int depth = 0;
    for (size_t j = open; j < s_.size(); ++j) {
      if (s_[j] == '[') ++depth;
      if (s_[j] == ']' && --depth == 0) return j + 1;
    }
    error(open, "this '[' is never closed with ']'");
  }

  // A value at i_: a plain number goes into *number; anything else is an expression, checked
  // here and kept as text (returns its index). -1 and *bare when there is no value.
  int value(double* number, bool* bare) {
    skip();
    const size_t b = i_;
    // The common case, a plain signed number, without the expression machinery.
    size_t j = b;
    const bool negative = j < s_.size() && s_[j] == '-';
    if (j < s_.size() && (s_[j] == '-' || s_[j] == '+'))
      while (++j < s_.size() && is_space(s_[j])) {
      }
    if (const size_t e = read_unsigned(s_, j, number); e != j) {
      if (negative) *number = -*number;
      i_ = e;
      return -1;
    }
    if (b < s_.size() && s_[b] == '{') {  // WinCNC's substitution, kept whole: {TH1+2}
      const size_t close = s_.find('}', b);
      if (close == std::string_view::npos) error(b, "this '{' is never closed with '}'");
      const std::string_view text = s_.substr(b, close + 1 - b);
      evaluate_wincnc_braces(text, loc(b), nullptr);  // its syntax, now
      out_->exprs.emplace_back(text);
      out_->exprs_column.push_back(static_cast<int>(b) + 1);
      i_ = close + 1;
      return static_cast<int>(out_->exprs.size()) - 1;
    }
    const size_t e = value_end(b);
    if (e == b) {
      *bare = true;
      return -1;
    }
    const std::string_view text = s_.substr(b, e - b);
    evaluate_gcode_expression(text, loc(b), nullptr);  // its syntax, now
    out_->exprs.emplace_back(text);
    out_->exprs_column.push_back(static_cast<int>(b) + 1);
    i_ = e;
    return static_cast<int>(out_->exprs.size()) - 1;
  }

  void word(bool first) {
    const size_t at = i_;
    const char letter = upper(s_[i_]);
    // A function's name has two letters or more; a word's letter is followed by its value.
    if (i_ + 1 < s_.size() && is_letter(s_[i_ + 1]) && !function_at(s_, i_).empty())
      error(at, "a function is a value: write it after a word's letter, as in X[SIN[30]]");
    if (letter == 'O') {
      if (!out_->words.empty() || !out_->assigns.empty() || out_->message)
        error(at, "an O-word comes first on its line: put the other words on a line of their own");
      gcode_oword::read(s_, at, loc(at), out_);
      i_ = s_.size();
      return;
    }
    ++i_;
    GcodeWord w;
    w.letter = letter;
    w.column = static_cast<int>(at) + 1;
    w.expr = value(&w.number, &w.bare);
    if (letter == 'N') {
      if (!first || w.bare || w.expr >= 0)
        error(at, first ? "N needs a line number, as in N10"
                        : "a line number N must come first in the block");
      return;
    }
    if (letter == 'M' && w.expr < 0 && (w.number == 98 || w.number == 99))
      out_->flow_m = static_cast<std::uint8_t>(w.number);
    // WinCNC's `M98 file.tap` (M98.1 too): the rest of the word is a file name.
    if (letter == 'M' && w.expr < 0 && (w.number == 98 || std::abs(w.number - 98.1) < 1e-9)) {
      size_t end = 0;
      if (gcode_oword::file_name_at(s_, i_, &end)) {
        size_t b = i_;
        while (is_space(s_[b])) ++b;
        out_->call_file = std::string(s_.substr(b, end - b));
        out_->call_file_column = static_cast<int>(b) + 1;
        i_ = end;
      }
    }
    if (std::string_view("ABCDFGHIJKLMPQRSTXYZ").find(letter) == std::string_view::npos)
      error(at,
            fmt::format("'{}' is not a G-code word letter; the letters are A B C D F G H I J K L "
                        "M N P Q R S T X Y Z",
                        letter));
    out_->words.push_back(w);
  }

  void assignment() {
    const size_t at = i_++;
    skip();
    GcodeAssign a;
    a.column = static_cast<int>(at) + 1;
    if (i_ < s_.size() && s_[i_] == '<') {
      const size_t close = s_.find('>', i_);
      if (close == std::string_view::npos) error(i_, "a parameter name opened with '<' needs '>'");
      a.target = "<";
      for (size_t k = i_ + 1; k < close; ++k)
        if (!is_space(s_[k]))
          a.target += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[k])));
      a.target += '>';
      if (a.target == "<>") error(i_, "the parameter name between < and > is empty");
      i_ = close + 1;
    } else if (i_ < s_.size() && s_[i_] == '[') {
      // `#[#1 + 2] = v`: the number is known when the block runs (the executor checks it).
      const size_t b = i_;
      double unused = 0;
      bool bare = false;
      a.target_expr = value(&unused, &bare);
      a.target = std::string(s_.substr(b, i_ - b));
    } else {
      double n = 0;
      const size_t e = read_unsigned(s_, i_, &n);
      if (e == i_ || n != std::round(n) || n < 1 || n > 5602)
        error(at, "expected a parameter number from 1 to 5602 or a <name> after '#'");
      if (n > 5000)
        error(at, fmt::format("#{} is read-only: it holds the machine's state; set #1 to #5000 or "
                              "a named #<parameter>",
                              n));
      a.target = std::to_string(static_cast<int>(n));  // `#1 0 = 5` sets #10
      i_ = e;
    }
    skip();
    if (i_ >= s_.size() || s_[i_] != '=')
      error(i_,
            "expected '=' after the parameter: a parameter is read inside a word's value, "
            "as in X#1, and set as #1 = 2.5");
    ++i_;
    bool bare = false;
    a.expr = value(&a.number, &bare);
    if (bare) error(i_, "expected a value after '='");
    out_->assigns.push_back(std::move(a));
  }

  std::string_view s_;
  size_t i_ = 0;
  const std::shared_ptr<const std::string>& file_;
  int line_no_;
  GcodeBlock* out_;
};

}  // namespace

bool parse_gcode_block(std::string_view line, const std::shared_ptr<const std::string>& file,
                       int line_no, GcodeBlock* out, Diagnostic* error) {
  out->clear();
  try {
    BlockReader(line, file, line_no, out).read();
  } catch (const GantryError& e) {
    *error = e.diagnostic();
    return false;
  }
  return true;
}

LineParse parse_gcode_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                           int line_no) {
  LineParse out;
  GcodeStmt st;
  Diagnostic error;
  if (!parse_gcode_block(line, file, line_no, &st.block, &error)) {
    out.error = std::move(error);
  } else if (!st.block.empty()) {
    size_t b = 0;
    while (b < line.size() && is_space(line[b])) ++b;
    out.statement = Statement{SourceLoc{file, line_no, static_cast<int>(b) + 1}, std::move(st)};
  }
  return out;
}

bool parse_gcode_statement(std::string_view line, const std::shared_ptr<const std::string>& file,
                           int line_no, Statement* out) {
  auto* st = std::get_if<GcodeStmt>(&out->body);
  if (!st) st = &out->body.emplace<GcodeStmt>();
  Diagnostic error;
  if (!parse_gcode_block(line, file, line_no, &st->block, &error) || st->block.empty())
    return false;
  size_t b = 0;
  while (b < line.size() && is_space(line[b])) ++b;
  if (out->loc.file != file) out->loc.file = file;
  out->loc.line = line_no;
  out->loc.column = static_cast<int>(b) + 1;
  return true;
}

double evaluate_gcode_expression(std::string_view text, const SourceLoc& at,
                                 const GcodeParameters* params) {
  return Expression(text, at, params).whole();
}

bool is_gcode_line(std::string_view line) {
  size_t i = 0;
  while (i < line.size() && is_space(line[i])) ++i;
  if (i + 1 >= line.size() || !is_digit(line[i + 1])) return false;
  const char c = upper(line[i]);
  if (c == 'G' || c == 'N') return true;
  // OpenSBP's parameters are separated by commas (`M23, 3` is a mistyped M2, not G-code).
  if (c != 'M' || line.find(',') != std::string_view::npos) return false;
  size_t j = i + 1;
  while (j < line.size() && is_digit(line[j])) ++j;
  if (j - i > 2) return true;  // M30, M62: OpenSBP's codes are two characters
  if (j < line.size() && line[j] == '.') return true;
  while (j < line.size() && is_space(line[j])) ++j;
  return j < line.size() && (is_letter(line[j]) || line[j] == '(' || line[j] == ';');
}

bool is_gcode_file(std::string_view path, std::string_view first_text) {
  const size_t dot = path.rfind('.');
  const size_t slash = path.find_last_of("/\\");
  std::string ext;
  if (dot != std::string_view::npos && (slash == std::string_view::npos || dot > slash))
    for (char c : path.substr(dot + 1))
      ext += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "nc" || ext == "tap" || ext == "gcode" || ext == "ngc") return true;
  if (ext == "sbp") return false;
  // Any other name: the first line that is not blank decides.
  size_t b = 0;
  while (b < first_text.size()) {
    size_t e = first_text.find_first_of("\r\n", b);
    if (e == std::string_view::npos) e = first_text.size();
    std::string_view l = first_text.substr(b, e - b);
    while (!l.empty() && is_space(l.front())) l.remove_prefix(1);
    if (!l.empty())
      return l.front() == '%' || l.front() == '(' || l.front() == ';' || is_gcode_line(l);
    b = e + 1;
  }
  return false;
}

}  // namespace gantry
