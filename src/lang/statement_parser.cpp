// The keyword statements: PAUSE, PRINT/WRITE, INPUT, MSGBOX, DIALOG, FAIL, files, SHELL,
// PLAY, WARNING OFF and the registry statements.
#include <fmt/format.h>  // messages

#include "line_parser.hpp"  // LineParser
#include "gantry/lang/scan.hpp"             // character helpers
#include "gantry/lang/statement_table.hpp"  // the keywords

namespace gantry {

using namespace scan;

std::optional<Statement> LineParser::program_statement(const std::string& word, size_t b, size_t w,
                                                       size_t e) const {
  // Most lines are two-letter commands; of the keywords only IF and ON are that short.
  if (word.size() < 2) return std::nullopt;
  if (word.size() == 2 && !(word[0] == 'I' && word[1] == 'F') &&
      !(word[0] == 'O' && word[1] == 'N'))
    return std::nullopt;
  const SourceLoc at = loc(b);
  auto nothing_after = [&](std::string_view what) {
    const size_t p = skip_space(w, e);
    if (p < e) error(p, fmt::format("{} takes no parameters", what));
  };
  const StatementSpec* spec = find_statement(word);
  if (!spec) return std::nullopt;
  switch (spec->keyword) {  // every Keyword has its case: the table and the parser agree
    case Keyword::Goto:
    case Keyword::Gosub:
      return jump(spec->keyword == Keyword::Gosub, b, w, e);
    case Keyword::Return:
      return nothing_after("RETURN"), Statement{at, ReturnStmt{}};
    case Keyword::End: {
      EndStmt st{EndStmt::Scope::File, std::nullopt};
      if (skip_space(w, e) < e) {  // FabMo: END "message" says why the file ended
        st.message = arg(w, e);
        const char first = st.message->text[0];
        if (!st.message->is_expression() || (first != '"' && first != '&' && first != '$'))
          error(skip_space(w, e), "END takes no parameters, or a message in quotes");
      }
      return Statement{at, std::move(st)};
    }
    case Keyword::EndAll:
      return nothing_after("ENDALL"), Statement{at, EndStmt{EndStmt::Scope::All, std::nullopt}};
    case Keyword::Exit: {
      const size_t p = skip_space(w, e);
      if (upper(line_.substr(p, e - p)) != "SHOPBOT") error(p, "write EXIT SHOPBOT");
      return Statement{at, EndStmt{EndStmt::Scope::Exit, std::nullopt}};
    }
    case Keyword::If:
      return if_statement(b, w, e);
    case Keyword::On:
      return on_input(b, w, e);
    case Keyword::Pause:
      return pause(b, w, e);
    case Keyword::Print:
    case Keyword::Write:
      return print(b, w, e, spec->keyword == Keyword::Write);
    case Keyword::Input:
      return input(b, w, e);
    case Keyword::Msgbox:
      return msgbox(b, w, e);
    case Keyword::Dialog:
      return dialog(b, w, e);
    case Keyword::Fail:
      return Statement{at, FailStmt{arg(w, e)}};
    case Keyword::Open:
      return open(b, w, e);
    case Keyword::Close: {
      CloseStmt st;
      size_t p = skip_space(w, e);
      if (p < e) st.number = file_number(&p, e);
      if (skip_space(p, e) < e) error(p, "CLOSE takes at most one file number, like CLOSE #1");
      return Statement{at, std::move(st)};
    }
    case Keyword::Shell: {
      size_t p = w;
      if (p < e && line_[p] == ',') ++p;
      auto fields = split_commas(p, e);
      ShellStmt st;
      st.command = arg(fields[0].first, fields[0].second);
      for (size_t i = 1; i < fields.size(); ++i)
        st.options.push_back(arg(fields[i].first, fields[i].second));
      if (st.command.blank()) error(p, "SHELL needs a command line in quotes");
      return Statement{at, std::move(st)};
    }
    case Keyword::Warning: {
      const size_t p = skip_space(w, e);
      if (upper(line_.substr(p, e - p)) != "OFF") error(p, "write WARNING OFF");
      return Statement{at, WarningOffStmt{}};
    }
    case Keyword::Play: {
      Arg path = arg(w, e);
      if (path.blank()) error(w, "PLAY needs the path of a sound file");
      return Statement{at, PlayStmt{std::move(path)}};
    }
    case Keyword::Registry:
      return registry(word, b, w, e);
    case Keyword::DataSend:
      error(b,
            "DATA_SEND is a FabMo statement that sends data to its web dashboard; Gantry has "
            "no dashboard: use PRINT or WRITE #n to record values");
  }
  return std::nullopt;
}

// PAUSE | PAUSE UNTIL sw, state | PAUSE value [, &var]. The value's type decides at run time:
// a number waits that many seconds, a string is a message for the operator.
Statement LineParser::pause(size_t b, size_t w, size_t e) const {
  PauseStmt st;
  const size_t p = skip_space(w, e);
  const std::string_view s = line_.substr(0, e);
  if (p == e) return {loc(b), std::move(st)};
  if (find_keyword(s, "UNTIL", p) == p) {
    const size_t comma = find_top_level(s, ',', p + 5);
    if (comma == std::string_view::npos)
      error(p, "PAUSE UNTIL needs an input and a state, e.g. PAUSE UNTIL 5, 1");
    st.kind = PauseStmt::Kind::Until;
    st.input = expression(p + 5, comma, "an input switch number");
    st.state = expression(comma + 1, e, "a state, 0 (open) or 1 (closed)");
    return {loc(b), std::move(st)};
  }
  auto fields = split_commas(p, e);
  st.kind = PauseStmt::Kind::Timed;
  st.value = arg(fields[0].first, fields[0].second);
  if (!st.value->is_expression() && looks_like_expression(st.value->text, false) &&
      st.value->expr_error)
    throw GantryError(*st.value->expr_error);  // `PAUSE SQR(4`, `PAUSE time(sec)`
  for (size_t i = 1; i < fields.size(); ++i) {
    const auto [fb, fe] = fields[i];
    const size_t eq = find_top_level(line_.substr(0, fe), '=', fb);
    const size_t first = skip_space(fb, fe);
    if (eq != std::string_view::npos && first < fe &&
        std::isalpha(static_cast<unsigned char>(line_[first]))) {
      st.options.emplace_back(upper(trim(line_.substr(fb, eq - fb))), arg(eq + 1, fe));
    } else if (i == 1) {
      st.into = lvalue(fb, fe);
    } else {
      error(fb, "PAUSE takes a time or message, a variable, and options written NAME = value");
    }
  }
  return {loc(b), std::move(st)};
}

Expr LineParser::file_number(size_t* p, size_t e) const {
  if (*p >= e || line_[*p] != '#') error(*p, "expected a file number such as #1");
  size_t q = *p + 1;
  size_t end = q;
  if (q < e && line_[q] == '(') {
    end = find_top_level(line_.substr(0, e), ')', q + 1);
    if (end == std::string_view::npos) error(q, "missing ')' after the file number");
    Expr n = expression(q + 1, end, "a file number 1 to 9");
    *p = end + 1;
    return n;
  }
  while (end < e &&
         (is_word(line_[end]) || line_[end] == '&' || line_[end] == '$' || is_space(line_[end])))
    ++end;
  Expr n = expression(q, end, "a file number 1 to 9");
  *p = end;
  return n;
}

// Splits on top-level separators `sep`, as PRINT and WRITE items; in comma mode every comma
// splits (the handbook's rule: quotes do not protect commas there).
Statement LineParser::print(size_t b, size_t w, size_t e, bool is_write) const {
  PrintStmt st;
  size_t p = skip_space(w, e);
  if (p < e && line_[p] == '#') {
    st.file = file_number(&p, e);
    p = skip_space(p, e);
    if (p >= e || (line_[p] != ',' && line_[p] != ';'))
      error(p, "expected ',' or ';' after the file number");
  } else if (is_write) {
    error(p, "WRITE needs a file number: WRITE #1, items");
  }
  if (p == e) return {loc(b), std::move(st)};
  // The first separator outside quotes decides the mode.
  size_t first = std::string_view::npos;
  for (size_t i = p, q = 0; i < e; ++i) {
    if (line_[i] == '"') q ^= 1;
    if (!q && (line_[i] == ',' || line_[i] == ';')) {
      first = i;
      break;
    }
  }
  st.comma_mode = first == std::string_view::npos || line_[first] == ',';
  if (st.file) ++p;  // the separator after #n only chooses the mode
  size_t end = e;
  if (end > p && line_[end - 1] == ';') {  // a final ';' keeps the line open
    st.newline = false;
    --end;
  }
  if (skip_space(p, end) == end) return {loc(b), std::move(st)};
  size_t start = p;
  bool quoted = false;
  for (size_t i = p; i < end; ++i) {
    if (line_[i] == '"') quoted = !quoted;
    const bool split = st.comma_mode ? line_[i] == ',' : (!quoted && line_[i] == ';');
    if (st.comma_mode && !quoted && line_[i] == ';')
      error(i,
            "a ';' inside a comma-separated list: use ',' between items (a ';' may only "
            "end the line)");
    if (!split) continue;
    st.items.push_back(arg(start, i, !st.comma_mode));
    start = i + 1;
  }
  st.items.push_back(arg(start, end, !st.comma_mode));
  return {loc(b), std::move(st)};
}

std::vector<LValue> LineParser::lvalues(size_t b, size_t e) const {
  std::vector<LValue> out;
  for (auto [fb, fe] : split_commas(b, e)) out.push_back(lvalue(fb, fe));
  return out;
}

// INPUT #n, &v...  |  INPUT [prompt][;] [: &default,] &v {, &v}
Statement LineParser::input(size_t b, size_t w, size_t e) const {
  InputStmt st;
  size_t p = skip_space(w, e);
  const std::string_view s = line_.substr(0, e);
  if (p < e && line_[p] == '#') {
    st.file = file_number(&p, e);
    p = skip_space(p, e);
    if (p < e && line_[p] == ',') ++p;
    st.vars = lvalues(p, e);
    return {loc(b), std::move(st)};
  }
  size_t rest = p;
  const size_t semi = find_top_level(s, ';', p);
  if (semi != std::string_view::npos) {
    st.prompt = arg(p, semi);
    rest = semi + 1;
  } else if (p < e && line_[p] == '"') {
    const size_t close = s.find('"', p + 1);
    if (close == std::string_view::npos) error(p, "the prompt's quote is never closed");
    st.prompt = arg(p, close + 1);
    rest = close + 1;
  }
  rest = skip_space(rest, e);
  if (rest < e && line_[rest] == ',') rest = skip_space(rest + 1, e);
  bool has_default = false;
  if (rest < e && line_[rest] == ':') {
    has_default = true;
    ++rest;
  }
  if (skip_space(rest, e) == e) error(rest, "INPUT needs a variable to receive the answer");
  st.vars = lvalues(rest, e);
  if (has_default) {
    st.default_var = st.vars.front();
    if (st.vars.size() > 1) st.vars.erase(st.vars.begin());
  }
  if (st.vars.size() > 10) error(rest, "INPUT takes at most 10 variables");
  return {loc(b), std::move(st)};
}

// MSGBOX(body, buttons, title): split at the first two commas; the title runs to the last ')'.
// Commas inside quotes or inside a matched pair of parentheses (`ROUND(&x, 2)`) do not split;
// a lone '(' in the body is text and hides nothing.
Statement LineParser::msgbox(size_t b, size_t w, size_t e) const {
  size_t p = skip_space(w, e);
  if (p >= e || line_[p] != '(') error(p, "MSGBOX needs (text, buttons, title)");
  const size_t close = line_.substr(0, e).rfind(')');
  if (close == std::string_view::npos || close < p) error(p, "MSGBOX is missing its ')'");
  if (skip_space(close + 1, e) < e) error(close + 1, "unexpected text after MSGBOX(...)");
  MsgBoxStmt st;
  const std::string_view s = line_.substr(0, close);
  const size_t c1 = find_top_level_matched(s, ',', p + 1);
  const size_t c2 = c1 == std::string_view::npos ? c1 : find_top_level_matched(s, ',', c1 + 1);
  st.body = arg(p + 1, c1 == std::string_view::npos ? close : c1);
  st.buttons = c1 == std::string_view::npos
                   ? arg(close, close)
                   : arg(c1 + 1, c2 == std::string_view::npos ? close : c2);
  st.title = c2 == std::string_view::npos ? arg(close, close) : arg(c2 + 1, close);
  return {loc(b), std::move(st)};
}

// DIALOG message [, NAME = value ...] (FabMo).
Statement LineParser::dialog(size_t b, size_t w, size_t e) const {
  size_t p = skip_space(w, e);
  bool paren = p < e && line_[p] == '(' && line_[e - 1] == ')';
  auto fields = split_commas(paren ? p + 1 : p, paren ? e - 1 : e);
  DialogStmt st;
  st.message = arg(fields[0].first, fields[0].second);
  for (size_t i = 1; i < fields.size(); ++i) {
    const auto [fb, fe] = fields[i];
    const size_t eq = find_top_level(line_.substr(0, fe), '=', fb);
    if (eq == std::string_view::npos)
      error(fb, "DIALOG options are written NAME = value, e.g. OKTEXT = \"Continue\"");
    st.options.emplace_back(upper(trim(line_.substr(fb, eq - fb))), arg(eq + 1, fe));
  }
  return {loc(b), std::move(st)};
}

// OPEN path FOR INPUT|OUTPUT|APPEND AS #n
Statement LineParser::open(size_t b, size_t w, size_t e) const {
  const std::string_view s = line_.substr(0, e);
  const size_t f = find_keyword(s, "FOR", w);
  const size_t as = f == std::string_view::npos ? f : find_keyword(s, "AS", f);
  if (as == std::string_view::npos) error(b, "write OPEN \"file\" FOR INPUT|OUTPUT|APPEND AS #n");
  OpenStmt st;
  st.path = arg(w, f);
  if (st.path.blank()) error(w, "OPEN needs a file name");
  const std::string mode = upper(trim(line_.substr(f + 3, as - f - 3)));
  if (mode == "INPUT")
    st.mode = OpenStmt::Mode::Input;
  else if (mode == "OUTPUT")
    st.mode = OpenStmt::Mode::Output;
  else if (mode == "APPEND")
    st.mode = OpenStmt::Mode::Append;
  else
    error(f + 3, "the mode after FOR is INPUT, OUTPUT or APPEND");
  size_t p = skip_space(as + 2, e);
  st.number = file_number(&p, e);
  if (skip_space(p, e) < e) error(p, "unexpected text after the file number");
  return {loc(b), std::move(st)};
}

Statement LineParser::registry(const std::string& word, size_t b, size_t w, size_t e) const {
  size_t p = w;
  if (p < e && line_[p] == ',') ++p;
  RegistryStmt st;
  st.name = word;
  if (word.rfind("GET", 0) == 0) {
    st.target = lvalue(p, e);
  } else {
    st.arg = arg(p, e);
    if (st.arg.blank()) error(p, fmt::format("{} needs a value", word));
  }
  return {loc(b), std::move(st)};
}

}  // namespace gantry
