// The statements hand-written part files are made of, read without the general parser:
// `&name = expression`, `IF test THEN action` (the action a GOTO, GOSUB, RETURN or such an
// assignment), `GOTO label`, `GOSUB label`, `RETURN` and `LABEL:`. The general parser builds
// and moves a LineParse and its Statement several times a line and copies the file name's
// pointer at every location; here the statement is written into storage the caller reuses.
// The expressions are parsed by the one expression parser, so they are exactly its trees.
// Anything else (a quote, a comment, a colon inside the line, `$` or `:=` targets, a label
// with spaces, an expression that is not one) is left to parse_line. The result equals
// parse_line's for every line accepted here; a differential unit test and the language fuzz
// target check that.
#include <cstring>  // memchr
#include <memory>

#include "gantry/lang/gcode.hpp"           // is_gcode_line: `N10:` is G-code, not a label
#include "gantry/lang/number_literal.hpp"  // parse_number_literal
#include "gantry/lang/parser.hpp"
#include "gantry/lang/scan.hpp"  // is_space, is_word, find_keyword

namespace gantry {
namespace {

using scan::is_space;
using scan::upper;

// scan::is_word without a call for ASCII (isalnum's answer for it in every locale).
inline bool is_word(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x80) return scan::is_word(c);
  return (u >= '0' && u <= '9') || ((u | 0x20) >= 'a' && (u | 0x20) <= 'z') || u == '_';
}

bool is_name_start(char c) {  // the expression lexer's (expression.cpp)
  return scan::is_letter(c) || c == '_';
}
bool is_name_char(char c) {
  return is_name_start(c) || (c >= '0' && c <= '9');
}

class Reader {
 public:
  Reader(std::string_view line, const std::shared_ptr<const std::string>& file, int line_no)
      : line_(line), file_(file), line_no_(line_no), at_{file, line_no, 0} {}

  // [b, e) is the trimmed line.
  bool line(size_t b, size_t e, Statement* out) {
    if (line_[e - 1] == ':') return label(b, e - 1, out);
    return statement(b, e, out, false);
  }

 private:
  void set_loc(SourceLoc& l, size_t col0) const {
    if (l.file != file_) l.file = file_;
    l.line = line_no_;
    l.column = static_cast<int>(col0) + 1;
  }
  size_t skip_space(size_t i, size_t e) const {
    while (i < e && is_space(line_[i])) ++i;
    return i;
  }
  // Whether [b, w) is `kw` (upper case) in any case.
  bool is(size_t b, size_t w, std::string_view kw) const {
    if (w - b != kw.size()) return false;
    for (size_t i = 0; i < kw.size(); ++i)
      if (upper(line_[b + i]) != kw[i]) return false;
    return true;
  }
  // `s` upper-cased into `to`, reusing its storage.
  static void assign_upper(std::string& to, std::string_view s) {
    to.resize(s.size());
    for (size_t i = 0; i < s.size(); ++i) to[i] = upper(s[i]);
  }

  // LineParser::expression without its errors: false where it would throw.
  bool expression(size_t b, size_t e, bool bare_words, Expr* out) {
    b = skip_space(b, e);
    while (e > b && is_space(line_[e - 1])) --e;
    if (b == e) return false;
    at_.column = static_cast<int>(b) + 1;
    ExprParse p = parse_expression(line_.substr(b, e - b), at_, bare_words);
    if (!p.expr) return false;
    *out = std::move(*p.expr);
    return true;
  }

  // A label: [b, e) is its name, word characters only (LineParser::label_name also takes
  // inner spaces; those lines go to the general parser).
  bool label(size_t b, size_t e, Statement* out) const {
    if (b == e) return false;
    for (size_t i = b; i < e; ++i)
      if (!is_word(line_[i])) return false;
    if (is_gcode_line(line_.substr(b, e + 1 - b))) return false;
    set_loc(out->loc, b);
    auto* l = std::get_if<LabelStmt>(&out->body);
    if (!l) l = &out->body.emplace<LabelStmt>();
    assign_upper(l->name, line_.substr(b, e - b));
    return true;
  }

  // LineParser::statement for the shapes read here; `action`: an IF's.
  bool statement(size_t b, size_t e, Statement* out, bool action) {
    if (line_[b] == '&') return assignment(b, e, out);
    size_t w = b;
    while (w < e && is_word(line_[w])) ++w;
    switch (w - b) {
      case 2:
        return !action && is(b, w, "IF") && if_statement(b, w, e, out);
      case 4:
        return is(b, w, "GOTO") && jump(false, b, w, e, out);
      case 5:
        return is(b, w, "GOSUB") && jump(true, b, w, e, out);
      case 6:
        if (!is(b, w, "RETURN") || skip_space(w, e) != e) return false;
        set_loc(out->loc, b);
        if (!std::holds_alternative<ReturnStmt>(out->body)) out->body.emplace<ReturnStmt>();
        return true;
      default:
        return false;
    }
  }

  // `&name = value` (LineParser::assignment, lvalue and arg).
  bool assignment(size_t b, size_t e, Statement* out) {
    size_t i = b + 1;
    if (i >= e || !is_name_start(line_[i])) return false;
    while (i < e && is_name_char(line_[i])) ++i;
    const size_t name_end = i;
    i = skip_space(i, e);
    if (i >= e || line_[i] != '=') return false;
    const size_t start = i + 1;
    const size_t vb = skip_space(start, e);
    if (vb == e) return false;  // a blank value: the general parser's
    const std::string_view text = line_.substr(vb, e - vb);
    std::optional<double> number = parse_number_literal(text);
    Expr expr;
    if (!number) {
      at_.column = static_cast<int>(vb) + 1;
      ExprParse p = parse_expression(text, at_);
      if (!p.expr) return false;  // text, or an error: the general parser's
      expr = std::move(*p.expr);
    }
    set_loc(out->loc, b);
    auto* a = std::get_if<AssignStmt>(&out->body);
    if (!a) a = &out->body.emplace<AssignStmt>();
    a->target.persistent = false;
    assign_upper(a->target.name, line_.substr(b + 1, name_end - b - 1));
    a->target.path.clear();
    set_loc(a->target.loc, b);
    a->weak = false;
    Arg& v = a->value;
    v.text.assign(text);
    set_loc(v.loc, vb);
    v.number = number;
    if (number)
      v.expr.reset();
    else
      v.expr = std::move(expr);
    v.expr_error.reset();
    return true;
  }

  // `GOTO label` / `GOSUB label`, the label of word characters only.
  bool jump(bool gosub, size_t b, size_t w, size_t e, Statement* out) const {
    const size_t lb = skip_space(w, e);
    if (lb == e) return false;
    for (size_t i = lb; i < e; ++i)
      if (!is_word(line_[i])) return false;
    set_loc(out->loc, b);
    auto* j = std::get_if<JumpStmt>(&out->body);
    if (!j) j = &out->body.emplace<JumpStmt>();
    assign_upper(j->label, line_.substr(lb, e - lb));
    j->gosub = gosub;
    set_loc(j->label_loc, lb);
    return true;
  }

  // scan::find_keyword(line_.substr(0, e), "THEN", from) for a line without quotes.
  size_t find_then(size_t from, size_t e) const {
    int depth = 0;
    for (size_t i = from; i + 4 <= e; ++i) {
      const char c = line_[i];
      if (c == '(' || c == '[') ++depth;
      if ((c == ')' || c == ']') && depth > 0) --depth;
      if (depth != 0 || (c | 0x20) != 't') continue;  // only `t` and `T` start THEN
      if (i > 0 && (is_word(line_[i - 1]) || line_[i - 1] == '&' || line_[i - 1] == '$')) continue;
      if (i + 4 < e && is_word(line_[i + 4])) continue;
      if ((line_[i + 1] | 0x20) == 'h' && (line_[i + 2] | 0x20) == 'e' &&
          (line_[i + 3] | 0x20) == 'n')
        return i;
    }
    return std::string_view::npos;
  }

  // `IF test THEN action` (LineParser::if_statement).
  bool if_statement(size_t b, size_t w, size_t e, Statement* out) {
    const size_t then = find_then(w, e);
    if (then == std::string_view::npos) return false;
    Expr test;
    if (!expression(w, then, /*bare_words=*/true, &test)) return false;
    const size_t ab = skip_space(then + 4, e);
    if (ab == e) return false;
    auto* s = std::get_if<IfStmt>(&out->body);
    if (!s) s = &out->body.emplace<IfStmt>();
    // The action's storage is reused when no one else holds it (the script's parse cache
    // may share a copy); this reader made it, as a mutable Statement.
    if (!s->action || s->action.use_count() != 1) s->action = std::make_shared<Statement>();
    if (!statement(ab, e, const_cast<Statement*>(s->action.get()), true)) return false;
    set_loc(out->loc, b);
    s->test = std::move(test);
    return true;
  }

  std::string_view line_;
  const std::shared_ptr<const std::string>& file_;
  int line_no_;
  SourceLoc at_;  // the expressions' location: the file and line, the column set per use
};

}  // namespace

bool parse_common_statement(std::string_view line, const std::shared_ptr<const std::string>& file,
                            int line_no, Statement* out) {
  size_t b = 0, e = line.size();
  while (b < e && is_space(line[b])) ++b;
  while (e > b && is_space(line[e - 1])) --e;
  if (e - b < 2) return false;
  // Quotes and comments are the general parser's; so is a colon anywhere but a label's end
  // (`GOTO X:`, `X: MX, 1`, `&a := 1`).
  const char* d = line.data();
  if (std::memchr(d, '\'', line.size()) || std::memchr(d, '"', line.size())) return false;
  if (const void* colon = std::memchr(d, ':', line.size()); colon && colon != d + e - 1)
    return false;  // the first colon is the last character: there is no other
  // No shape here starts as a REM comment does (`REM` and a blank), nor as G-code does but a
  // label, which label() leaves to the general parser.
  return Reader(line, file, line_no).line(b, e, out);
}

}  // namespace gantry
