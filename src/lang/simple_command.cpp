// The line most part files are made of, read without the general parser: a two-letter command
// whose parameters are blank or plain numbers (`M3, 1.5, -2, .25`). A CAM file is almost all
// such lines, and the general parser (quotes, expressions, keywords) costs several times more.
// Anything else — a comment, a quote, a variable, an exponent, a keyword, a custom cut —
// is left to parse_line. The result equals parse_line's for every line accepted here; a
// differential fuzz target checks that.
#include "simple_command.hpp"

#include "gantry/lang/parser.hpp"

#include <cstdint>  // uint64_t
#include <cstring>  // memcpy

#include "gantry/lang/number_literal.hpp"  // literal::scan, literal::value
#include "gantry/lang/scan.hpp"            // is_space, is_word

namespace gantry {
namespace {

using scan::is_space;

using scan::is_letter;
using scan::upper;

// Walks the line; with `out` (kBuild) it also builds the statement, reusing the storage `out`
// holds; `code`, when given, receives the command's two letters (upper case). Each number's
// value is gathered while its digits are scanned (literal::plain_value's reading, without a
// second walk over the literal; longer literals still go to plain_value).
template <bool kBuild>
bool scan_line(std::string_view line, const std::shared_ptr<const std::string>* file, int line_no,
               Statement* out, char* code) {
  size_t b = 0, e = line.size();
  while (b < e && is_space(line[b])) ++b;
  while (e > b && is_space(line[e - 1])) --e;
  if (e - b < 2 || !is_letter(line[b])) return false;
  const char c0 = upper(line[b]), c1 = upper(line[b + 1]);
  if (!is_letter(c1) && !literal::is_digit(c1)) return false;
  if (c0 == 'C' && literal::is_digit(c1)) return false;                    // a custom cut
  if ((c0 == 'G' || c0 == 'N') && literal::is_digit(c1)) return false;     // G-code
  if ((c0 == 'I' && c1 == 'F') || (c0 == 'O' && c1 == 'N')) return false;  // statements
  size_t p = b + 2;
  if (p < e) {
    if (line[p] == ',') {
      ++p;
    } else if (is_space(line[p])) {
      while (p < e && is_space(line[p])) ++p;
    } else {
      return false;  // a longer word, a label, or an error for parse_line to explain
    }
  }
  if (code) {
    code[0] = c0;
    code[1] = c1;
  }
  CommandStmt* cmd = nullptr;
  if constexpr (kBuild) {
    if (out->loc.file != *file) out->loc.file = *file;
    out->loc.line = line_no;
    out->loc.column = static_cast<int>(b) + 1;
    cmd = std::get_if<CommandStmt>(&out->body);
    if (!cmd) cmd = &out->body.emplace<CommandStmt>();
    cmd->code.assign({c0, c1});
  }
  size_t n = 0;     // parameters so far, blanks included
  size_t kept = 0;  // parameters up to the last one written
  const bool has_params = p < e || line[p - 1] == ',';
  const char* s = line.data();
  for (size_t i = p; has_params; ++i) {  // one parameter: [spaces] [sign] literal [spaces]
    const size_t fb = i;
    while (i < e && is_space(s[i])) ++i;
    const size_t tb = i;
    if (i < e && (s[i] == '+' || s[i] == '-')) ++i;
    const size_t digits_at = i;
    std::uint64_t m = 0;  // the digits as an integer (wraps past 19 digits: then unused)
    while (i < e && literal::is_digit(s[i])) {
      if constexpr (kBuild) m = m * 10 + static_cast<unsigned>(s[i] - '0');
      ++i;
    }
    size_t point = 0;  // 1 when the literal has a '.'
    size_t frac_at = i;
    if (i < e && s[i] == '.') {
      point = 1;
      frac_at = ++i;
      while (i < e && literal::is_digit(s[i])) {
        if constexpr (kBuild) m = m * 10 + static_cast<unsigned>(s[i] - '0');
        ++i;
      }
    }
    const size_t te = i;
    const size_t lit_len = te - digits_at;
    if (te > tb && (lit_len == point || te - tb > 40)) return false;  // `-`, `.`, `+.`
    while (i < e && is_space(s[i])) ++i;
    if (i < e && s[i] != ',') return false;  // an expression, a word, an exponent...
    if constexpr (kBuild) {
      if (cmd->args.size() <= n) cmd->args.emplace_back();
      Arg& a = cmd->args[n];
      const size_t len = te - tb;
      // Within the kept capacity (a short literal fits the string itself) this is a length
      // store and a copy; assign() takes the general _M_replace path (callgrind: 590
      // instructions of a `gantry check` line's 4,400).
      a.text.resize(len);
      std::memcpy(a.text.data(), s + tb, len);
      if (a.loc.file != *file) a.loc.file = *file;
      a.loc.line = line_no;
      a.loc.column = static_cast<int>(len == 0 ? fb : tb) + 1;
      a.expr.reset();
      a.expr_error.reset();
      if (len == 0) {
        a.number.reset();
      } else {
        // literal::plain_value(lit): m / 10^decimals while the digits fit 15 (exact), else it.
        const size_t digits = lit_len - point;
        const double v = digits <= 15
                             ? static_cast<double>(m) / literal::kPow10[point ? te - frac_at : 0]
                             : literal::plain_value(line.substr(digits_at, lit_len));
        a.number = s[tb] == '-' ? -v : v;
      }
    }
    ++n;
    if (te > tb) kept = n;
    if (i == e) break;
  }
  if constexpr (kBuild) cmd->args.resize(kept);  // trailing blanks are dropped, as parse_line does
  return true;
}

}  // namespace

bool is_simple_command(std::string_view line) {
  return scan_line<false>(line, nullptr, 0, nullptr, nullptr);
}

bool simple_command_code(std::string_view line, char code[2]) {
  return scan_line<false>(line, nullptr, 0, nullptr, code);
}

bool parse_simple_command(std::string_view line, const std::shared_ptr<const std::string>& file,
                          int line_no, Statement* out) {
  return scan_line<true>(line, &file, line_no, out, nullptr);
}

}  // namespace gantry
