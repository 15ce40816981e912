// Friendly Motion's lexical rules and commands (docs/friendlymotion.md, "Reading a line").
// A line is cut at spaces into commands (quoted text may not hold spaces either, as the
// manual says; a prompt's `(text)` may), `!` outside quotes starts a comment, and each
// command is read by its code letter. Every error names its column.
#include <fmt/format.h>  // messages

#include <algorithm>  // min
#include <cctype>     // isdigit, toupper
#include <cstdlib>    // strtod
#include <optional>
#include <string>
#include <string_view>

#include "gantry/lang/fm.hpp"
#include "gantry/lang/parser.hpp"  // LineParse

namespace gantry {
namespace {

struct Fail {
  int column;
  std::string message;
};

// Reads expressions and commands out of one token. `up` is the token upper-cased outside
// quotes, `raw` as written; `col0` is the 1-based column of its first character.
class TokenReader {
 public:
  TokenReader(std::string_view up, std::string_view raw, int col0, FmLine& line)
      : up_(up), raw_(raw), col0_(col0), line_(line) {}

  size_t pos = 0;
  bool at_end() const { return pos >= up_.size(); }
  char peek(size_t k = 0) const { return pos + k < up_.size() ? up_[pos + k] : '\0'; }
  int column() const { return col0_ + static_cast<int>(pos); }
  std::string_view rest() const { return up_.substr(std::min(pos, up_.size())); }
  std::string_view raw_rest() const { return raw_.substr(std::min(pos, raw_.size())); }

  [[noreturn]] void fail(std::string message) const { throw Fail{column(), std::move(message)}; }

  // Digits only: a variable, string, code or sequence number.
  std::optional<long> digits() {
    const size_t b = pos;
    while (std::isdigit(static_cast<unsigned char>(peek())) && pos - b < 9) ++pos;
    if (pos == b) return std::nullopt;
    return std::stol(std::string(up_.substr(b, pos - b)));
  }

  // An expression: `allow_function` where the manual shows one (V assignments, G26), as the
  // first thing after `=`; it applies to the rest of the expression (V2=COS45+45 is cos 90).
  int expression(bool allow_function, std::string_view what) {
    FmExpr e;
    e.column = column();
    const size_t b = pos;
    parens_ = 0;
    if (at_end() || !starts_operand())
      fail(fmt::format("{} needs a number, a variable V0-V99 or an expression here", what));
    std::optional<FmStep::Op> fn;
    int fn_col = 0;
    if (allow_function) {
      fn_col = column();
      fn = function();
    }
    sum(e);
    if (fn) e.steps.push_back({*fn, 0, 0, fn_col});
    e.text = std::string(raw_.substr(b, pos - b));
    line_.exprs.push_back(std::move(e));
    return static_cast<int>(line_.exprs.size()) - 1;
  }

 private:
  bool starts_operand() const {
    const char c = peek();
    return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' ||
           c == '(' || c == 'V' || c == 'S' || c == 'C' || c == 'T' || c == 'A';
  }
  std::optional<FmStep::Op> function() {
    static constexpr std::pair<std::string_view, FmStep::Op> kFunctions[] = {
        {"ASIN", FmStep::Op::Asin}, {"ACOS", FmStep::Op::Acos}, {"ATAN", FmStep::Op::Atan},
        {"SIN", FmStep::Op::Sin},   {"COS", FmStep::Op::Cos},   {"TAN", FmStep::Op::Tan}};
    for (const auto& [name, op] : kFunctions)
      if (rest().starts_with(name)) {
        pos += name.size();
        return op;
      }
    return std::nullopt;
  }
  void sum(FmExpr& e) {
    term(e);
    while (peek() == '+' || peek() == '-') {
      const int col = column();
      const FmStep::Op op = peek() == '+' ? FmStep::Op::Add : FmStep::Op::Sub;
      ++pos;
      term(e);
      e.steps.push_back({op, 0, 0, col});
    }
  }
  void term(FmExpr& e) {
    unary(e);
    while (peek() == '*' || peek() == '/') {
      const int col = column();
      const FmStep::Op op = peek() == '*' ? FmStep::Op::Mul : FmStep::Op::Div;
      ++pos;
      unary(e);
      e.steps.push_back({op, 0, 0, col});
    }
  }
  // Unary minus binds looser than ^ (-2^2 is -4), as in Gantry's other languages.
  void unary(FmExpr& e) {
    if (peek() == '-' || peek() == '+') {
      const bool neg = peek() == '-';
      const int col = column();
      ++pos;
      unary(e);
      if (neg) e.steps.push_back({FmStep::Op::Neg, 0, 0, col});
      return;
    }
    power(e);
  }
  // ^ groups to the right (2^3^2 is 2^9): the manual does not say; mathematics does.
  void power(FmExpr& e) {
    primary(e);
    if (peek() == '^') {
      const int col = column();
      ++pos;
      unary(e);
      e.steps.push_back({FmStep::Op::Pow, 0, 0, col});
    }
  }
  void primary(FmExpr& e) {
    const char c = peek();
    const int col = column();
    if (c == '(') {
      if (++parens_ > 6)
        fail("more than six sets of parentheses in one expression; the manual allows six");
      ++pos;
      sum(e);
      if (peek() != ')') fail("')' expected: a parenthesis is not closed");
      ++pos;
      return;
    }
    if (c == 'V') {
      ++pos;
      const std::optional<long> n = digits();
      if (!n) fail("a variable is V followed by its number, V0 to V99");
      if (*n > 99) fail(fmt::format("V{} does not exist: the variables are V0 to V99", *n));
      e.steps.push_back({FmStep::Op::Var, static_cast<int>(*n), 0, col});
      return;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      const size_t b = pos;
      while (std::isdigit(static_cast<unsigned char>(peek()))) ++pos;
      if (peek() == '.') ++pos;
      while (std::isdigit(static_cast<unsigned char>(peek()))) ++pos;
      const std::string lit(up_.substr(b, pos - b));
      if (lit == ".") fail("a number needs a digit");
      e.steps.push_back({FmStep::Op::Number, 0, std::strtod(lit.c_str(), nullptr), col});
      return;
    }
    if (rest().starts_with("SIN") || rest().starts_with("COS") || rest().starts_with("TAN") ||
        rest().starts_with("ASIN") || rest().starts_with("ACOS") || rest().starts_with("ATAN"))
      fail(
          "a trigonometric function must come right after the '=' of a V assignment (or "
          "start a G26 value), and applies to the rest of it: V1=3+SIN45 is illegal, "
          "V1=SIN45+3 takes the sine of 48");
    if (c == '\0') fail("the expression ends here: a number or variable is missing");
    fail(fmt::format("'{}' cannot start a number, variable or expression", c));
  }

  std::string_view up_, raw_;
  int col0_;
  FmLine& line_;
  int parens_ = 0;
};

// The G code at the start of the digits (longest match against the table): G68.1 is G68
// with `.1`, G192 is G19 with `2`, G4X1 is G4.
std::optional<int> longest_code(TokenReader& r, bool (*known)(int)) {
  size_t n = 0;
  while (std::isdigit(static_cast<unsigned char>(r.peek(n))) && n < 6) ++n;
  const std::string_view d = r.rest().substr(0, n);
  for (size_t len = n; len > 0; --len) {
    const int code = std::stoi(std::string(d.substr(0, len)));
    if (known(code)) {
      r.pos += len;
      return code;
    }
  }
  return std::nullopt;
}

// Quoted text ("..."); `closed_optional`: the token's end may close it (the manual's own
// G16"HELLO,_MARY).
std::string quoted(TokenReader& r, std::string_view raw_token, bool closed_optional,
                   std::string_view what) {
  if (r.peek() != '"') r.fail(fmt::format("{} must be in quotation marks", what));
  const size_t open = r.pos++;
  const size_t close = raw_token.find('"', r.pos);
  if (close == std::string_view::npos) {
    if (!closed_optional)
      r.fail(fmt::format("{} has no closing quotation mark (and may hold no spaces)", what));
    r.pos = raw_token.size();
    return std::string(raw_token.substr(open + 1));
  }
  r.pos = close + 1;
  return std::string(raw_token.substr(open + 1, close - open - 1));
}

void expect_end(const TokenReader& r, std::string_view what) {
  if (!r.at_end())
    r.fail(fmt::format("unexpected '{}' after {}; commands on one line are separated by spaces",
                       r.rest(), what));
}

// G58 / G25 elements: "text", Vxx, Ay or @y, in any order, no spaces.
void show_items(TokenReader& r, std::string_view raw_token, FmCommand& c) {
  if (r.at_end()) r.fail("G58 and G25 need what to show: \"text\", Vxx or @y elements");
  while (!r.at_end()) {
    FmShowItem item;
    const char ch = r.peek();
    if (ch == '"') {
      item.text = quoted(r, raw_token, false, "text");
    } else if (ch == 'V') {
      ++r.pos;
      const std::optional<long> n = r.digits();
      if (!n || *n > 99) r.fail("a variable is V0 to V99");
      item.kind = FmShowItem::Kind::Variable;
      item.index = static_cast<int>(*n);
    } else if (ch == 'A' || ch == '@') {
      ++r.pos;
      if (!std::isdigit(static_cast<unsigned char>(r.peek())))
        r.fail("a string is @0 to @9 (or A0 to A9)");
      item.kind = FmShowItem::Kind::String;
      item.index = r.peek() - '0';
      ++r.pos;
    } else {
      r.fail(fmt::format("'{}' is not a G58 element: \"text\", Vxx or @y", ch));
    }
    c.items.push_back(std::move(item));
  }
}

// G20, G21, G23: a file name, @n, or nothing (the operator names the file).
void file_name(TokenReader& r, std::string_view raw_token, FmCommand& c) {
  if (r.at_end()) return;
  if (r.peek() == '@') {
    ++r.pos;
    const std::optional<long> n = r.digits();
    if (!n || *n > 9) r.fail("@ names a string, @0 to @9");
    c.string_index = static_cast<int>(*n);
    expect_end(r, "the string");
    return;
  }
  c.text = r.peek() == '"' ? quoted(r, raw_token, false, "the file name")
                           : std::string(raw_token.substr(r.pos));
  r.pos = raw_token.size();
  c.has_text = true;
}

void g_tail(TokenReader& r, std::string_view raw_token, FmCommand& c) {
  switch (c.code) {
    case 0:
      if (r.peek() == 'R')
        r.fail(
            "G0R# (repeat the profile) is named in the manual but never described: how "
            "a downloaded profile is run again is not documented, so Gantry does not guess; "
            "repeat the moves with K and R instead");
      return expect_end(r, "G0");
    case 4:
      if (r.peek() != 'X') r.fail("G4 is written G4X# (the delay in seconds), e.g. G4X3.75");
      ++r.pos;
      c.expr = r.expression(false, "G4X");
      if (r.peek() == 'Q') {
        c.quick = true;
        ++r.pos;
      }
      return expect_end(r, "the delay");
    case 7:
      r.pos = 0;  // at the command
      r.fail(
          "G7 sends characters straight to U.S. Laser's motion controller, in that "
          "controller's own language; Gantry drives its own card and has no such "
          "controller to talk to");
    case 10:
      c.text = quoted(r, raw_token, false, "G10's font file name");
      c.has_text = true;
      return expect_end(r, "the font file name");
    case 16:
      if (r.at_end()) return;  // the operator types the text
      c.text = quoted(r, raw_token, true, "G16's text");
      c.has_text = true;
      return expect_end(r, "the text");
    case 19:
      if (r.at_end()) r.fail("G19 needs the character size factor: G19# (G19.5 halves it)");
      if (std::isalpha(static_cast<unsigned char>(r.peek())) && r.peek() != 'V')
        r.fail(
            "G19's ratio and direction forms are announced in the manual but their format "
            "is not given; only G19# (the size factor) is documented");
      c.expr = r.expression(false, "G19");
      return expect_end(r, "the size");
    case 20:
    case 21:
    case 23:
      return file_name(r, raw_token, c);
    case 25:
    case 58:
      return show_items(r, raw_token, c);
    case 26:
      for (;;) {
        c.list.push_back(r.expression(true, "G26"));
        if (r.peek() != ',') break;
        ++r.pos;
      }
      if (c.list.size() > 5) r.fail("G26 writes at most 5 values");
      return expect_end(r, "G26's values");
    case 27:
      if (r.peek() == 'R') {
        ++r.pos;
        c.record = r.expression(false, "G27's record R");
        if (r.at_end()) return;
        if (r.peek() != ',') r.fail("',' expected after the record number");
        ++r.pos;
      }
      if (r.at_end()) r.fail("G27 needs the variables to read into: G27V1,V2");
      for (;;) {
        if (r.peek() != 'V') r.fail("G27 reads into variables: V followed by the index");
        ++r.pos;
        c.list.push_back(r.expression(false, "the variable index"));
        if (r.peek() != ',') break;
        ++r.pos;
      }
      if (c.list.size() > 5) r.fail("G27 reads at most 5 values");
      return expect_end(r, "G27's variables");
    case 60:
      if (r.peek() != 'X' && r.peek() != 'A' && r.peek() != 'C')
        r.fail(
            "G60 is G60X (origin V81,V82 and +X point V83,V84), G60A (origin and angle V85) "
            "or G60C (machine coordinates)");
      c.axis = r.peek();
      ++r.pos;
      return expect_end(r, fmt::format("G60{}", c.axis));
    case 68:
      if (r.peek() == 'X' || r.peek() == 'Y') {
        c.axis = r.peek();
        ++r.pos;
      }
      c.expr = r.expression(false, "G68");
      return expect_end(r, "the scale");
    default:
      return expect_end(r, fmt::format("G{}", c.code));
  }
}

void read_move(TokenReader& r, FmCommand& c) {
  c.op = FmOp::Move;
  std::string seen;
  while (!r.at_end()) {
    const char l = r.peek();
    const std::string_view letters = "XYZABCIJR";
    if (letters.find(l) == std::string_view::npos)
      r.fail(
          fmt::format("'{}' cannot follow in a move; a move is X#Y# (interpolated), X#Y#I#J# "
                      "(an arc) and commands are separated by spaces",
                      l));
    if (seen.find(l) != std::string::npos) r.fail(fmt::format("{} is given twice in one move", l));
    seen += l;
    ++r.pos;
    const int e = r.expression(false, std::string(1, l));
    if (l == 'I')
      c.i = e;
    else if (l == 'J')
      c.j = e;
    else if (l == 'R')
      c.repeat = e;
    else
      c.axes[std::string_view("XYZABC").find(l)] = e;
  }
  const bool arc = c.i >= 0 || c.j >= 0;
  if (arc && (c.i < 0 || c.j < 0 || c.axes[0] < 0 || c.axes[1] < 0))
    throw Fail{c.column,
               "an arc is written X#Y#I#J# with all four: the end point and the centre (the "
               "manual gives no form with some of them left out)"};
  if (arc && (c.axes[2] >= 0 || c.axes[3] >= 0 || c.axes[4] >= 0 || c.axes[5] >= 0))
    throw Fail{c.column, "an arc moves X and Y only; move the other axes before or after it"};
  if (c.repeat >= 0 && !arc)
    throw Fail{c.column,
               "R repeats only circles (X#Y#I#J#R#), subroutine calls (KN#R#) and profiles; "
               "the manual implements it for nothing else"};
}

// One command: the token `up` (upper case outside quotes), `raw` as written.
FmCommand read_command(std::string_view up, std::string_view raw, int col, bool first,
                       FmLine& line) {
  FmCommand c;
  c.column = col;
  TokenReader r(up, raw, col, line);
  const char letter = r.peek();
  ++r.pos;
  switch (letter) {
    case 'N': {
      const std::optional<long> n = r.digits();
      if (!n || *n < 1 || *n > 99999) r.fail("a sequence number is N1 to N99999");
      expect_end(r, "the sequence number");
      if (!first) throw Fail{col, "N must be the first command on its line"};
      c.op = FmOp::Sequence;
      c.code = static_cast<int>(*n);
      line.sequence = c.code;
      return c;
    }
    case 'A':
      if (std::isdigit(static_cast<unsigned char>(r.peek())) && r.peek(1) == '=') {
        c.op = FmOp::SetString;
        c.code = r.peek() - '0';
        r.pos += 2;
        if (r.peek() == '?' && r.pos + 1 == up.size()) {
          c.op = FmOp::Prompt;
          c.axis = '@';
          return c;
        }
        c.text = std::string(r.raw_rest());
        return c;
      }
      if (std::isdigit(static_cast<unsigned char>(r.peek())) && up.size() == 2)
        r.fail(fmt::format(
            "A{0} is ambiguous: the manual's A command shows string A{0}, and A is also the "
            "A axis; write @{0} to show the string, or A{0}.0 to move the A axis",
            r.peek()));
      --r.pos;
      read_move(r, c);
      return c;
    case 'X':
    case 'Y':
    case 'Z':
    case 'B':
    case 'C':
      --r.pos;
      read_move(r, c);
      return c;
    case 'I':
      --r.pos;  // at the command
      r.fail("I and J give an arc's centre after its end point: X#Y#I#J#");
    case 'F':
      c.op = FmOp::Feed;
      if (r.peek() == 'X' || r.peek() == 'Y' || r.peek() == 'C') c.axis = r.peek(), ++r.pos;
      c.expr = r.expression(false, "F");
      expect_end(r, "the feed rate");
      return c;
    case 'G': {
      c.op = FmOp::G;
      const std::optional<int> code = longest_code(r, fm_is_g_code);
      if (!code) {
        --r.pos;
        r.fail(fmt::format("{} is not a Friendly Motion G code (`gantry help fm` lists them)",
                           up.substr(0, 1 + std::min<size_t>(up.size() - 1, 3))));
      }
      c.code = *code;
      g_tail(r, raw, c);
      return c;
    }
    case 'M': {
      c.op = FmOp::M;
      if (r.peek() == 'V') {  // MVnn: the M-function whose number V nn holds
        c.expr = r.expression(false, "M");
        expect_end(r, "the M-function's variable");
        return c;
      }
      const std::optional<int> code = longest_code(r, fm_is_m_code);
      if (!code) {
        --r.pos;
        r.fail(fmt::format("{} is not a Friendly Motion M code (`gantry help fm` lists them)", up));
      }
      c.code = *code;
      if ((c.code == 98 || c.code == 99) && (r.peek() == 'X' || r.peek() == 'Y'))
        c.axis = r.peek(), ++r.pos;
      expect_end(r, fmt::format("M{}", c.code));
      return c;
    }
    case 'J':
    case 'K': {
      c.op = letter == 'J' ? FmOp::Jump : FmOp::Call;
      if (r.peek() == 'M' || r.peek() == 'V') {
        c.axis = r.peek();
        ++r.pos;
        const std::optional<long> n = r.digits();
        if (!n) r.fail(fmt::format("{}{} needs the number tested", letter, c.axis));
        if (c.axis == 'M' && (*n < 200 || *n > 231))
          r.fail(fmt::format("M{} is not an input M-function; inputs are M200 to M231", *n));
        if (c.axis == 'V' && (*n < 1 || *n > 99))
          r.fail(fmt::format("V{} cannot be tested; the manual allows V1 to V99", *n));
        c.cond = static_cast<int>(*n);
      }
      if (r.peek() != 'N')
        r.fail(fmt::format("{} needs its target sequence number: {}N#", letter, letter));
      ++r.pos;
      const std::optional<long> n = r.digits();
      if (!n || *n < 1 || *n > 99999) r.fail("a sequence number is N1 to N99999");
      c.target = static_cast<int>(*n);
      if (r.peek() == 'R') {
        if (letter == 'J') r.fail("R repeats subroutine calls (K), not jumps");
        ++r.pos;
        c.repeat = r.expression(false, "R");
      }
      expect_end(r, "the sequence number");
      return c;
    }
    case 'V': {
      const std::optional<long> n = r.digits();
      if (!n || *n > 99) r.fail("a variable is V0 to V99");
      c.code = static_cast<int>(*n);
      if (r.at_end()) {
        c.op = FmOp::ShowVariable;
        return c;
      }
      if (r.peek() != '=') r.fail(fmt::format("'=' expected after V{}", c.code));
      ++r.pos;
      if (r.peek() == '?') {
        c.op = FmOp::Prompt;
        c.axis = 'V';
        ++r.pos;
        if (r.peek() == '(') {
          const std::string_view t = r.raw_rest();
          if (t.back() != ')') r.fail("the prompt's text ends with ')': V1=?(Text)");
          c.text = std::string(t.substr(1, t.size() - 2));
          c.has_text = true;
          r.pos = up.size();
        }
        expect_end(r, "the prompt");
        return c;
      }
      c.op = FmOp::Assign;
      c.expr = r.expression(true, fmt::format("V{}=", c.code));
      expect_end(r, "the expression");
      return c;
    }
    case '@': {
      if (!std::isdigit(static_cast<unsigned char>(r.peek()))) r.fail("a string is @0 to @9");
      c.code = r.peek() - '0';
      ++r.pos;
      if (r.at_end()) {
        c.op = FmOp::ShowString;
        return c;
      }
      if (r.peek() != '=') r.fail(fmt::format("'=' expected after @{}", c.code));
      ++r.pos;
      if (r.peek() == '?' && r.pos + 1 == up.size()) {
        c.op = FmOp::Prompt;
        c.axis = '@';
        return c;
      }
      c.op = FmOp::SetString;
      c.text = std::string(r.raw_rest());
      return c;
    }
    case 'P':  // the relay matrix: whether the profile wires one is the executor's question
      c.op = FmOp::Relay;
      if (r.peek() != 'A' && r.peek() != 'B' && r.peek() != 'D')
        r.fail("P is PA# or PB# (connect test probe # to bus A or B) or PD (disconnect all)");
      c.axis = r.peek();
      ++r.pos;
      if (c.axis != 'D') c.expr = r.expression(false, fmt::format("P{}", c.axis));
      expect_end(r, c.axis == 'D' ? "PD" : "the probe number");
      return c;
    case 'S':
      c.op = FmOp::Analog;
      if (r.peek() != 'F' && r.peek() != 'C')
        r.fail(
            "S is Sf# (Q-switch frequency, kHz) or SC# (lamp current); the manual documents "
            "no other analog form");
      c.axis = r.peek();
      ++r.pos;
      c.expr = r.expression(false, c.axis == 'F' ? "Sf" : "SC");
      expect_end(r, "the value");
      return c;
    case 'T':
      --r.pos;  // at the command
      r.fail(
          "T (resistor trim) cannot run: the manual gives the Trim window's fields but "
          "not the text of a T line, and the trim measures with a DMM board Gantry does "
          "not have");
    case 'L':
      --r.pos;  // at the command
      r.fail(
          "L is listed as a code letter in the manual but never described; Gantry does "
          "not guess what it does");
    case 'R':
      --r.pos;  // at the command
      r.fail("R repeats the command it is appended to, with no space: KN100R6, X#Y#I#J#R#");
    case '"':
      --r.pos;  // at the command
      r.fail("quoted text belongs to a command (G10, G16, G58, G25); none is written here");
    default:
      --r.pos;
      r.fail(fmt::format("'{}' is not a Friendly Motion command letter", letter));
  }
}

}  // namespace

bool parse_fm_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                   int line_no, FmLine* out, Diagnostic* error) {
  out->commands.clear();
  out->exprs.clear();
  out->sequence.reset();
  // The manual's typography: curly quotes stand for ".
  std::string raw;
  raw.reserve(line.size());
  for (size_t k = 0; k < line.size(); ++k) {
    if (line.substr(k, 3) == "\xE2\x80\x9C" || line.substr(k, 3) == "\xE2\x80\x9D") {
      raw += '"';
      k += 2;
    } else {
      raw += line[k];
    }
  }
  std::string up = raw;
  bool in_quote = false;
  for (char& ch : up) {
    if (ch == '"') in_quote = !in_quote;
    if (!in_quote) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  }
  size_t p = 0;
  const size_t n = raw.size();
  int m6_column = 0;
  try {
    while (p < n) {
      while (p < n && (raw[p] == ' ' || raw[p] == '\t')) ++p;
      if (p >= n || raw[p] == '!') break;
      const size_t b = p;
      bool quote = false;
      while (p < n) {
        const char ch = raw[p];
        if (ch == '"') quote = !quote;
        if (!quote && (ch == ' ' || ch == '\t' || ch == '!')) {
          // A prompt's (text) may hold spaces: V1=?(enter size on square).
          const std::string_view so_far = std::string_view(up).substr(b, p - b);
          const size_t open = so_far.find("=?(");
          if (open != std::string_view::npos && so_far.find(')', open) == std::string_view::npos &&
              ch != '!') {
            ++p;
            continue;
          }
          break;
        }
        ++p;
      }
      const int col = static_cast<int>(b) + 1;
      FmCommand c =
          read_command(std::string_view(up).substr(b, p - b),
                       std::string_view(raw).substr(b, p - b), col, out->commands.empty(), *out);
      if (c.op == FmOp::M && c.expr < 0 && c.code == 6) m6_column = col;
      out->commands.push_back(std::move(c));
    }
    if (m6_column && out->commands.size() > 1)
      throw Fail{m6_column, "M6 (return from subroutine) must be on a line by itself"};
  } catch (const Fail& f) {
    *error = Diagnostic({file, line_no, f.column}, Severity::Error, f.message);
    out->commands.clear();
    return false;
  }
  return true;
}

LineParse parse_fm(std::string_view line, const std::shared_ptr<const std::string>& file,
                   int line_no) {
  LineParse out;
  FmStmt st;
  Diagnostic error;
  if (!parse_fm_line(line, file, line_no, &st.line, &error)) {
    out.error = std::move(error);
    return out;
  }
  if (st.line.commands.empty()) return out;
  Statement s;
  s.loc = {file, line_no, st.line.commands.front().column};
  s.body = std::move(st);
  out.statement = std::move(s);
  return out;
}

}  // namespace gantry
