// G-code blocks: words, comments, parameter settings and expressions (docs/gcode.md).
// Spaces are allowed between a letter and its value; letters are read in either case.
#include <fmt/format.h>  // messages

#include <cmath>  // abs, round

#include "gantry/lang/gcode.hpp"
#include "gantry/lang/parser.hpp"  // LineParse, Statement
#include "gantry/lang/scan.hpp"    // is_letter
#include "gcode_oword.hpp"         // O-word lines
#include "gcode_scan.hpp"          // numbers, function names

namespace gantry {
namespace {

using gcode_scan::function_at;
using gcode_scan::is_digit;
using gcode_scan::is_space;
using gcode_scan::read_unsigned;
using gcode_scan::upper;
using gcode_scan::word_at;
using scan::is_letter;

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
      } else if (c == '"') {
        error(i_,
              "a quoted text is WinCNC's G5 message box (G5 T# M\"text\"), which Gantry does not "
              "show: write (MSG, text) and M0 to stop with a message");
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

  // Whether the block so far holds the plain word `letter``number` (G41, M37).
  bool has_code(char letter, double number) const {
    for (const GcodeWord& w : out_->words)
      if (w.letter == letter && w.expr < 0 && w.number == number) return true;
    return false;
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

  // A value at i_: a plain number goes into *number; anything else is an expression, compiled
  // here (returns its index). -1 and *bare when there is no value.
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
      i_ = close + 1;
      return add_gcode_expression(out_, s_.substr(b, close + 1 - b), loc(b));
    }
    const size_t e = value_end(b);
    if (e == b) {
      *bare = true;
      return -1;
    }
    i_ = e;
    return add_gcode_expression(out_, s_.substr(b, e - b), loc(b));
  }

  void word(bool first) {
    const size_t at = i_;
    const char letter = upper(s_[i_]);
    // A function's name has two letters or more; a word's letter is followed by its value.
    if (i_ + 1 < s_.size() && is_letter(s_[i_ + 1]) && !function_at(s_, i_).empty())
      error(at, "a function is a value: write it after a word's letter, as in X[SIN[30]]");
    // WinCNC's O word: M37's offset (read as a word), G41/G42's compensation amount (not read).
    const bool m37_offset = letter == 'O' && has_code('M', 37);
    if (letter == 'O' && !m37_offset) {
      if (has_code('G', 41) || has_code('G', 42))
        error(at,
              "O is WinCNC's compensation amount of G41/G42 (G41 O#), which Gantry does not "
              "read: give the tool's diameter with G41.1 D#, or its tool number with G41 D# and "
              "the tool table");
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
                        : "a line number N must come first in the block (WinCNC's L1 N# V# "
                          "stores an H register, which Gantry does not have: use #parameters)");
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
    // W is read as a word: the executor moves the axis the profile names W (display.w_axis)
    // or says there is none.
    if (letter == 'U' || letter == 'V')
      error(at, fmt::format("{} is not a G-code word letter: in WinCNC it is the axis of {} "
                            "vertical head; Gantry drives Z and a W head at most: program the "
                            "cut on Z",
                            letter, letter == 'U' ? "a third" : "a fourth"));
    if (letter == 'E')
      error(at,
            "E is not a G-code word letter: in WinCNC it is L10's (a cut array), which Gantry "
            "does not run: repeat the cut in the CAM program, or with FP from an OpenSBP file");
    if (!m37_offset &&
        std::string_view("ABCDFGHIJKLMPQRSTWXYZ").find(letter) == std::string_view::npos)
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
      a.param = static_cast<int>(n);
      a.target = std::to_string(a.param);  // `#1 0 = 5` sets #10
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
