// Line classification and the parsing of commands, labels, assignments and control flow.
// The other program statements are parsed in statement_parser.cpp.
#include "gantry/lang/parser.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // count
#include <cmath>      // floor

#include "gantry/core/any_bytes.hpp"  // echoed: quoted source text is capped
#include "gantry/lang/check_only.hpp"      // check_line
#include "gantry/lang/number_literal.hpp"  // parse_number_literal
#include "line_parser.hpp"          // LineParser
#include "gantry/lang/scan.hpp"                 // character helpers

namespace gantry {

using namespace scan;

SourceLoc LineParser::loc(size_t col0) const {
  return SourceLoc{file_, line_no_, static_cast<int>(col0) + 1};
}

[[noreturn]] void LineParser::error(size_t col0, std::string message) const {
  fail(loc(col0), std::move(message));
}

size_t LineParser::skip_space(size_t i, size_t end) const {
  while (i < end && is_space(line_[i])) ++i;
  return i;
}

Arg LineParser::arg(size_t b, size_t e, bool whole_quotes) const {
  const size_t start = b;
  while (b < e && is_space(line_[b])) ++b;
  while (e > b && is_space(line_[e - 1])) --e;
  const size_t quote = line_.substr(b, e - b).find('"');
  if (whole_quotes && quote != std::string_view::npos &&
      std::count(line_.begin() + b, line_.begin() + e, '"') % 2 == 1)
    error(b + line_.substr(b, e - b).rfind('"'),
          "this parameter opens a quote (\") that is never closed");
  Arg a;
  a.text = std::string(line_.substr(b, e - b));
  a.loc = loc(b == e ? start : b);
  if (!a.text.empty()) {
    // Most parameters are plain numbers: no tree for them (the parse costs more than a line).
    if ((a.number = parse_number_literal(a.text))) return a;
    ExprParse p = parse_expression(a.text, a.loc);
    a.expr = std::move(p.expr);
    a.expr_error = std::move(p.error);
  }
  return a;
}

Expr LineParser::expression(size_t b, size_t e, std::string_view what, bool bare_words) const {
  b = skip_space(b, e);
  while (e > b && is_space(line_[e - 1])) --e;
  if (b == e) error(b, fmt::format("expected {}", what));
  ExprParse p = parse_expression(line_.substr(b, e - b), loc(b), bare_words);
  if (!p.expr) throw GantryError(*p.error);
  return *p.expr;
}

namespace {

// The expression lexer's name characters (expression.cpp).
bool is_name_start(char c) {
  return is_letter(c) || c == '_';
}
bool is_name_char(char c) {
  return is_name_start(c) || (c >= '0' && c <= '9');
}

}  // namespace

LValue LineParser::lvalue(size_t b, size_t e) const {
  b = skip_space(b, e);
  while (e > b && is_space(line_[e - 1])) --e;
  // The common target, `&name`, read here: exactly what parse_lvalue gives for it, without
  // its lexer (a tenth of an assignment's parse).
  if (e - b >= 2 && line_[b] == '&' && is_name_start(line_[b + 1])) {
    size_t i = b + 2;
    while (i < e && is_name_char(line_[i])) ++i;
    if (i == e) {
      LValue v;
      v.name = upper(line_.substr(b + 1, e - b - 1));
      v.loc = loc(b);
      return v;
    }
  }
  std::optional<Diagnostic> err;
  std::optional<LValue> v = parse_lvalue(line_.substr(b, e - b), loc(b), &err);
  if (!v) {
    if (err) throw GantryError(*err);
    error(b, "expected a variable such as &name");
  }
  return *v;
}

std::vector<std::pair<size_t, size_t>> LineParser::split_commas(size_t b, size_t e) const {
  std::vector<std::pair<size_t, size_t>> out;
  const std::string_view s = line_.substr(0, e);
  while (true) {
    size_t c = find_top_level(s, ',', b);
    if (c == std::string_view::npos) c = e;
    out.emplace_back(b, c);
    if (c == e) break;
    b = c + 1;
  }
  return out;
}

std::string LineParser::label_name(size_t b, size_t e, bool* ok) const {
  std::string name;
  *ok = b < e;
  for (size_t i = b; i < e && *ok; ++i) {
    const char c = line_[i];
    if (is_word(c)) {
      name += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    } else if (is_space(c)) {
      if (!name.empty() && name.back() != ' ') name += ' ';
    } else {
      *ok = false;
    }
  }
  while (!name.empty() && name.back() == ' ') name.pop_back();
  *ok = *ok && !name.empty();
  return name;
}

// Classifies [b, e) (comment removed, trimmed) and parses it as one statement.
Statement LineParser::statement(size_t b, size_t e) const {
  const SourceLoc at = loc(b);
  const char first = line_[b];
  if (line_[e - 1] == ':') {  // a label stands alone: words (and spaces) then a colon
    bool ok = false;
    std::string name = label_name(b, e - 1, &ok);
    // `GOTO DONE:` or `IF 1 THEN GOTO DONE:` is a jump written with a colon, not a label.
    const std::string first_word = name.substr(0, name.find(' '));
    if (ok && name.find(' ') != std::string::npos &&
        (first_word == "GOTO" || first_word == "GOSUB" || first_word == "IF" || first_word == "ON"))
      error(e - 1, "write the label after GOTO or GOSUB without its colon");
    if (ok) return {at, LabelStmt{std::move(name)}};
  }
  if (first == '&' || first == '$') return assignment(b, e);
  if (first == '%') error(b, "system variables %(n) are read-only; assign to a &variable instead");
  size_t w = b;
  while (w < e && is_word(line_[w])) ++w;
  if (w == b)
    error(b, fmt::format("unexpected '{}' at the start of a statement; a line starts with a "
                         "command, a statement, a label or a comment",
                         first));
  const std::string word = upper(line_.substr(b, w - b));
  if (const size_t p = skip_space(w, e); p + 1 < e && line_[p] == ':' && line_[p + 1] != '=')
    error(skip_space(p + 1, e),
          "unexpected text after the label; put the next statement on its "
          "own line");
  if (std::optional<Statement> st = program_statement(word, b, w, e)) return std::move(*st);
  if (word.size() >= 2 && word.size() <= kMaxCustomCutDigits + 1 && word[0] == 'C' &&
      word.find_first_not_of("0123456789", 1) == std::string::npos)
    return custom_cut(word, b, w, e);
  if (word == "C" && w < e && line_[w] == '#') return computed_custom_cut(b, w + 1, e);
  return command(word, b, w, e);
}

Statement LineParser::assignment(size_t b, size_t e) const {
  const std::string_view s = line_.substr(0, e);
  const size_t eq = find_top_level(s, '=', b);
  if (eq == std::string_view::npos)
    error(b, "expected '=' after the variable: write &name = value");
  const bool weak = eq > b && line_[eq - 1] == ':';
  AssignStmt st;
  st.target = lvalue(b, weak ? eq - 1 : eq);
  st.weak = weak;
  st.value = arg(eq + 1, e);
  // A bare word stays text (`&s = Material Surface`), but text that can only be meant as an
  // expression must be one: `&x = &y +` or `&x = SQR(1, 2)` is an error, not a string.
  if (!st.value.is_expression() && looks_like_expression(st.value.text, false) &&
      st.value.expr_error)
    throw GantryError(*st.value.expr_error);
  return {loc(b), std::move(st)};
}

Statement LineParser::command(const std::string& word, size_t b, size_t w, size_t e) const {
  const bool letters_only = word.find_first_of("0123456789") == std::string::npos;
  if (word.size() > 2 && letters_only)
    error(b, fmt::format("unknown statement '{}'; commands are two characters, such as MX or "
                         "J3, and statements are words such as IF, GOTO or PAUSE",
                         echoed(line_.substr(b, w - b))));
  if (!std::isalpha(static_cast<unsigned char>(word[0])) || word.size() < 2)
    error(b, fmt::format("unknown statement '{}'", echoed(line_.substr(b, w - b))));
  CommandStmt cmd{word.substr(0, 2), {}};
  size_t p = b + 2;  // just after the two-letter code
  // The handbook's rule: one comma, or a run of spaces, separates the code from its first
  // parameter; `M2 , 4.2` therefore leaves X blank.
  if (p < e) {
    if (line_[p] == ',') {
      ++p;
    } else if (is_space(line_[p])) {
      p = skip_space(p, e);
    } else {
      std::string_view rest = line_.substr(p, e - p);
      rest = trim(rest.substr(0, rest.find(',')));
      error(p, fmt::format("expected a space or a comma after the command {}; write `{}, {}`",
                           cmd.code, cmd.code, rest));
    }
    if (p < e || line_[p - 1] == ',')
      for (auto [fb, fe] : split_commas(p, e)) cmd.args.push_back(arg(fb, fe));
  }
  while (!cmd.args.empty() && cmd.args.back().blank()) cmd.args.pop_back();
  return {loc(b), std::move(cmd)};
}

Statement LineParser::custom_cut(const std::string& word, size_t b, size_t w, size_t e) const {
  CustomCutStmt st;
  st.number = std::stoi(word.substr(1));
  size_t p = w;
  if (p < e && line_[p] == ',') ++p;
  p = skip_space(p, e);
  if (p < e)
    for (auto [fb, fe] : split_commas(p, e)) st.args.push_back(arg(fb, fe));
  while (!st.args.empty() && st.args.back().blank()) st.args.pop_back();
  return {loc(b), std::move(st)};
}

// `C#, n [, params]`: ShopBot's spelling of `C<n>`, the number being the first parameter (a
// number or an expression, evaluated when the line runs). `p` is just after the `#`.
Statement LineParser::computed_custom_cut(size_t b, size_t p, size_t e) const {
  if (p < e && line_[p] == ',') ++p;  // FabMo also takes `C# 90` and `C#90`
  const auto fields = split_commas(skip_space(p, e), e);
  Arg number = arg(fields[0].first, fields[0].second);
  if (number.blank())
    error(number.loc.column - 1,
          "C# needs the number of the custom cut: write `C#, 90` to run custom cut 90");
  CustomCutStmt st;
  if (number.number) {
    const double n = *number.number;
    if (n < 0 || n != std::floor(n) || n > kMaxCustomCut)
      error(number.loc.column - 1, fmt::format("custom cuts are numbered 0 to {}; C# was given {}",
                                               kMaxCustomCut, number.text));
    st.number = static_cast<int>(n);
  } else if (number.expr) {
    st.computed = std::move(number);
  } else if (looks_like_expression(number.text, true)) {
    throw GantryError(*number.expr_error);  // `C#, &n +`: say where it breaks
  } else {
    error(number.loc.column - 1,
          fmt::format("C# needs a number or a variable, not '{}': write `C#, 90` or `C#, &n`",
                      echoed(number.text)));
  }
  for (size_t i = 1; i < fields.size(); ++i)
    st.args.push_back(arg(fields[i].first, fields[i].second));
  while (!st.args.empty() && st.args.back().blank()) st.args.pop_back();
  return {loc(b), std::move(st)};
}

Statement LineParser::jump(bool gosub, size_t b, size_t w, size_t e) const {
  const size_t lb = skip_space(w, e);
  bool ok = false;
  JumpStmt st;
  st.label = label_name(lb, e, &ok);
  if (!ok)
    error(lb, fmt::format("{} needs a label name (letters, digits, _ and spaces), written "
                          "without its colon",
                          gosub ? "GOSUB" : "GOTO"));
  st.gosub = gosub;
  st.label_loc = loc(lb);
  return {loc(b), std::move(st)};
}

Statement LineParser::if_statement(size_t b, size_t w, size_t e) const {
  const std::string_view s = line_.substr(0, e);
  const size_t then = find_keyword(s, "THEN", w);
  if (then == std::string_view::npos) error(b, "IF needs THEN: write IF test THEN statement");
  IfStmt st;
  st.test = expression(w, then, "a test after IF", /*bare_words=*/true);
  const size_t ab = skip_space(then + 4, e);
  if (ab == e) error(then, "THEN needs a statement after it");
  st.action = action(ab, e, "IF ... THEN");
  return {loc(b), std::move(st)};
}

StatementPtr LineParser::action(size_t b, size_t e, std::string_view owner) const {
  Statement st = statement(b, e);
  if (std::holds_alternative<IfStmt>(st.body) || std::holds_alternative<OnInputStmt>(st.body) ||
      std::holds_alternative<LabelStmt>(st.body))
    error(b, fmt::format("{} takes one plain statement: not IF, ON INPUT or a label", owner));
  return std::make_shared<const Statement>(std::move(st));
}

Statement LineParser::on_input(size_t b, size_t w, size_t e) const {
  const std::string_view s = line_.substr(0, e);
  size_t p = skip_space(w, e);
  // ShopBot's files often abbreviate INPUT to INP, as FabMo accepts.
  const size_t keyword = find_keyword(s, "INPUT", p) == p ? 5
                         : find_keyword(s, "INP", p) == p ? 3
                                                          : 0;
  if (keyword == 0) error(p, "expected INPUT after ON: ON INPUT(switch, state)");
  p = skip_space(p + keyword, e);
  if (p >= e || line_[p] != '(') error(p, "expected '(' after ON INPUT");
  const size_t close = find_top_level(s, ')', p + 1);
  const size_t comma = find_top_level(s, ',', p + 1);
  if (close == std::string_view::npos || comma == std::string_view::npos || comma > close)
    error(p, "ON INPUT needs (switch, state), e.g. ON INPUT(2, 1) GOTO STOPPED");
  OnInputStmt st;
  st.input = expression(p + 1, comma, "an input switch number");
  st.condition = expression(comma + 1, close, "a state: 0, 1, 2 or 3");
  const size_t ab = skip_space(close + 1, e);
  if (ab < e) st.action = action(ab, e, "ON INPUT");
  return {loc(b), std::move(st)};
}

LineParse parse_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                     int line_no) {
  LineParse out;
  const std::string_view t = trim(line);
  if (t.empty()) return out;
  if (t.front() == '\'') {
    out.comment = std::string(trim(t.substr(1)));
    return out;
  }
  if (t.size() >= 3 && upper(t.substr(0, 3)) == "REM" && (t.size() == 3 || is_space(t[3]))) {
    out.comment = std::string(trim(t.substr(3)));
    return out;
  }
  if (is_gcode_line(t)) return parse_gcode_line(line, file, line_no);  // G-code in OpenSBP
  size_t e = std::min(line.size(), scan::comment_start(line));
  while (e > 0 && is_space(line[e - 1])) --e;
  size_t b = 0;
  while (b < e && is_space(line[b])) ++b;
  try {
    out.statement = LineParser(line, file, line_no).statement(b, e);
  } catch (const GantryError& err) {
    out.error = err.diagnostic();
  }
  return out;
}

LineParse check_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                     int line_no) {
  const ExprCheckOnly check;
  return parse_line(line, file, line_no);
}

}  // namespace gantry
