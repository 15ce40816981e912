// O-word lines: `o<name> sub`, `o100 if [expr]`, `o<name> call [a] [b]`, Fanuc's `O1234`.
// LinuxCNC writes every value of an O-word in brackets (`1 2` would read as the number 12),
// and a line with an O-word holds nothing else but comments.
#include "gcode_oword.hpp"

#include <fmt/format.h>  // messages

#include <cctype>  // tolower

#include "gantry/lang/number_literal.hpp"  // is_digit
#include "gantry/lang/scan.hpp"            // is_letter

namespace gantry {

const char* oword_keyword(OwordKind kind) {
  switch (kind) {
    case OwordKind::Sub:
      return "sub";
    case OwordKind::Endsub:
      return "endsub";
    case OwordKind::Call:
      return "call";
    case OwordKind::Return:
      return "return";
    case OwordKind::If:
      return "if";
    case OwordKind::Elseif:
      return "elseif";
    case OwordKind::Else:
      return "else";
    case OwordKind::Endif:
      return "endif";
    case OwordKind::While:
      return "while";
    case OwordKind::Endwhile:
      return "endwhile";
    case OwordKind::Do:
      return "do";
    case OwordKind::Repeat:
      return "repeat";
    case OwordKind::Endrepeat:
      return "endrepeat";
    case OwordKind::Break:
      return "break";
    case OwordKind::Continue:
      return "continue";
    case OwordKind::Program:
    case OwordKind::None:
      break;
  }
  return "";
}

namespace gcode_oword {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t';
}

struct Keyword {
  std::string_view text;
  OwordKind kind;
  int min_args, max_args;  // bracketed values it takes
};
constexpr Keyword kKeywords[] = {
    {"sub", OwordKind::Sub, 0, 0},
    {"endsub", OwordKind::Endsub, 0, 1},
    {"call", OwordKind::Call, 0, 30},
    {"return", OwordKind::Return, 0, 1},
    {"if", OwordKind::If, 1, 1},
    {"elseif", OwordKind::Elseif, 1, 1},
    {"else", OwordKind::Else, 0, 0},
    {"endif", OwordKind::Endif, 0, 0},
    {"while", OwordKind::While, 1, 1},
    {"endwhile", OwordKind::Endwhile, 0, 0},
    {"do", OwordKind::Do, 0, 0},
    {"repeat", OwordKind::Repeat, 1, 1},
    {"endrepeat", OwordKind::Endrepeat, 0, 0},
    {"break", OwordKind::Break, 0, 0},
    {"continue", OwordKind::Continue, 0, 0},
};

class Reader {
 public:
  Reader(std::string_view s, size_t at, const SourceLoc& loc, GcodeBlock* out)
      : s_(s), i_(at), loc_(loc), out_(out) {}

  void read() {
    GcodeOword& o = out_->oword;
    o.column = static_cast<int>(i_) + 1;
    o.args.clear();
    o.name.clear();
    ++i_;  // the O
    skip();
    if (i_ < s_.size() && s_[i_] == '<') {
      const size_t close = s_.find('>', i_);
      if (close == std::string_view::npos) error(i_, "an O-word name opened with '<' needs '>'");
      for (size_t k = i_ + 1; k < close; ++k)
        if (!is_space(s_[k]))
          o.name += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[k])));
      if (o.name.empty()) error(i_, "the O-word name between < and > is empty");
      i_ = close + 1;
    } else if (i_ < s_.size() && literal::is_digit(s_[i_])) {
      const size_t b = i_;
      while (i_ < s_.size() && literal::is_digit(s_[i_])) ++i_;
      std::string_view digits = s_.substr(b, i_ - b);
      while (digits.size() > 1 && digits.front() == '0') digits.remove_prefix(1);
      o.name = std::string(digits);
      if (i_ < s_.size() && s_[i_] == '.') error(b, "an O number is a whole number, as in o100");
    } else if (i_ < s_.size() && (s_[i_] == '[' || s_[i_] == '#')) {
      error(i_,
            "computed O numbers (o[#1] call) are not supported: name the subroutine, as in "
            "o<name> call or o100 call");
    } else {
      error(i_, "O needs a number or a <name>, as in o100 if [#1 GT 0] or o<name> call");
    }
    skip();
    const size_t kw = i_;
    while (i_ < s_.size() && scan::is_letter(s_[i_])) ++i_;
    std::string word;
    for (size_t k = kw; k < i_; ++k)
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[k])));
    o.keyword_column = static_cast<int>(kw) + 1;
    if (word.empty()) {
      // Fanuc's program number: `O1234` alone, maybe with a comment (its title).
      if (o.name.empty() || !literal::is_digit(o.name[0]))
        error(kw, fmt::format("o<{}> needs a keyword: sub, endsub, call, return, if, while, "
                              "do, repeat...",
                              o.name));
      o.kind = OwordKind::Program;
      o.keyword_column = o.column;
      rest_is_comments();
      return;
    }
    const Keyword* k = nullptr;
    for (const Keyword& c : kKeywords)
      if (c.text == word) k = &c;
    if (!k)
      error(kw, fmt::format("'{}' is not an O-word keyword; they are sub endsub call return if "
                            "elseif else endif while endwhile do repeat endrepeat break continue",
                            word));
    o.kind = k->kind;
    while (true) {
      skip();
      if (i_ >= s_.size() || s_[i_] != '[') break;
      if (static_cast<int>(o.args.size()) == k->max_args)
        error(i_, k->max_args == 0 ? fmt::format("'{}' takes no value", k->text)
                                   : fmt::format("'{}' takes at most {} value{}", k->text,
                                                 k->max_args, k->max_args == 1 ? "" : "s"));
      const size_t b = i_;
      const size_t e = bracket_end(b);
      const std::string_view text = s_.substr(b, e - b);
      SourceLoc at = loc_;
      at.column = static_cast<int>(b) + 1;
      o.args.push_back(add_gcode_expression(out_, text, at));
      i_ = e;
    }
    if (static_cast<int>(o.args.size()) < k->min_args)
      error(i_, fmt::format("'{}' needs its value in brackets, as in o100 {} [#1 LT 10]", k->text,
                            k->text));
    rest_is_comments();
  }

 private:
  [[noreturn]] void error(size_t i, std::string what) const {
    SourceLoc l = loc_;
    l.column = static_cast<int>(i) + 1;
    fail(l, std::move(what));
  }
  void skip() {
    while (i_ < s_.size() && is_space(s_[i_])) ++i_;
  }
  size_t bracket_end(size_t open) const {
    int depth = 0;
    for (size_t j = open; j < s_.size(); ++j) {
      if (s_[j] == '[') ++depth;
      if (s_[j] == ']' && --depth == 0) return j + 1;
    }
    error(open, "this '[' is never closed with ']'");
  }
  void rest_is_comments() {
    while (true) {
      skip();
      if (i_ >= s_.size() || s_[i_] == ';') return;
      if (s_[i_] == '(') {
        const size_t close = s_.find(')', i_);
        if (close == std::string_view::npos)
          error(i_, "this comment is not closed: add ')' at its end");
        i_ = close + 1;
        continue;
      }
      const GcodeOword& o = out_->oword;
      error(i_, o.kind == OwordKind::Call || o.kind == OwordKind::Return ||
                        o.kind == OwordKind::Endsub || o.kind == OwordKind::If ||
                        o.kind == OwordKind::Elseif || o.kind == OwordKind::While ||
                        o.kind == OwordKind::Repeat
                    ? "an O-word's values are written in brackets, as in o<name> call [1] [#2]; "
                      "other words go on a line of their own"
                    : "an O-word line holds only the O-word (and comments): put other words on a "
                      "line of their own");
    }
  }

  std::string_view s_;
  size_t i_;
  SourceLoc loc_;
  GcodeBlock* out_;
};

}  // namespace

void read(std::string_view line, size_t at, const SourceLoc& line_loc, GcodeBlock* out) {
  Reader(line, at, line_loc, out).read();
}

bool file_name_at(std::string_view s, size_t i, size_t* end) {
  while (i < s.size() && is_space(s[i])) ++i;
  size_t e = i;
  while (e < s.size() && !is_space(s[e]) && s[e] != '(' && s[e] != '[' && s[e] != ';') ++e;
  if (e == i || !scan::is_letter(s[i])) return false;
  const std::string_view token = s.substr(i, e - i);
  // `P100`, `P#1`, `L-2`: a word. `Texas.tap`, `SPIN.MAC`, `x1.tap`, `start`: a file name.
  bool name = token.size() > 1 && scan::is_letter(token[1]);
  const size_t dot = token.find('.');
  if (dot != std::string_view::npos && dot + 1 < token.size() && scan::is_letter(token[dot + 1]))
    name = true;
  if (name) *end = e;
  return name;
}

}  // namespace gcode_oword
}  // namespace gantry
