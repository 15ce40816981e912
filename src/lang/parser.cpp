// OpenSBP line syntax: comments, labels, END, and two-letter commands with comma parameters.
#include "gantry/lang/parser.hpp"

#include <fmt/format.h>  // messages

#include <cctype>  // character classes

#include "gantry/core/text_file.hpp"  // read_text_file

namespace gantry {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}
bool is_word(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// Reads one line; `line` excludes the newline. Columns are 1-based byte offsets.
class LineParser {
 public:
  LineParser(std::string_view line, int line_no, const Program& prog)
      : s_(line), line_no_(line_no), prog_(prog) {}

  // Appends the line's statement (if any) or its error to the program.
  void parse(Program& out) {
    skip_space();
    if (at_end() || peek() == '\'') return;  // blank line or comment
    const size_t start = pos_;
    while (!at_end() && is_word(peek())) ++pos_;
    const std::string_view word = s_.substr(start, pos_ - start);
    const SourceLoc at = loc(start);
    if (word.empty()) {
      error(out, start,
            fmt::format("unexpected '{}' at the start of a statement; a line "
                        "starts with a two-letter command, a label or a comment",
                        s_[start]));
      return;
    }
    const std::string key = upper(word);
    if (key == "REM" && (at_end() || is_space(peek()))) return;  // REM comment
    skip_space();
    if (!at_end() && peek() == ':') {
      ++pos_;
      if (!rest_is_empty()) {
        error(out, pos_, "unexpected text after the label; put the next statement on its own line");
        return;
      }
      out.statements.push_back({at, LabelStmt{key}});
      return;
    }
    if (key == "END") {
      if (!rest_is_empty()) {
        error(out, pos_, "END takes no parameters");
        return;
      }
      out.statements.push_back({at, EndStmt{}});
      return;
    }
    if (key.size() != 2 || !std::isalpha(static_cast<unsigned char>(key[0]))) {
      error(out, start,
            fmt::format("unknown statement '{}'; commands are two characters, such as MX or J3",
                        word));
      return;
    }
    CommandStmt cmd{key, {}};
    if (!parse_params(out, cmd)) return;
    out.statements.push_back({at, std::move(cmd)});
  }

 private:
  // After the code: optional spaces, one optional comma, then comma-separated values up to
  // a comment. `MX 5`, `MX,5` and `MX, 5` are the same; `M3, , 2` leaves X blank.
  bool parse_params(Program& out, CommandStmt& cmd) {
    if (at_end() || peek() == '\'') return true;
    if (peek() == ',') {
      ++pos_;
    } else if (pos_ > 0 && !is_space(s_[pos_ - 1])) {
      std::string_view rest = s_.substr(pos_, s_.find_first_of(",'", pos_) - pos_);
      while (!rest.empty() && is_space(rest.back())) rest.remove_suffix(1);
      error(out, pos_,
            fmt::format("expected a space or a comma after the command {}; write `{}, {}`",
                        cmd.code, cmd.code, rest));
      return false;
    }
    while (true) {
      const size_t field_start = pos_;
      size_t end = pos_;
      size_t open_quote = std::string_view::npos;
      while (end < s_.size() &&
             (open_quote != std::string_view::npos || (s_[end] != ',' && s_[end] != '\''))) {
        if (s_[end] == '"')
          open_quote = open_quote == std::string_view::npos ? end : std::string_view::npos;
        ++end;
      }
      if (open_quote != std::string_view::npos) {
        error(out, open_quote, "this parameter opens a quote (\") that is never closed");
        return false;
      }
      size_t a = field_start, b = end;
      while (a < b && is_space(s_[a])) ++a;
      while (b > a && is_space(s_[b - 1])) --b;
      // A blank parameter is located at its field (just after its comma).
      cmd.params.push_back({std::string(s_.substr(a, b - a)), loc(a == b ? field_start : a)});
      pos_ = end;
      if (at_end() || peek() == '\'') break;
      ++pos_;  // the comma
    }
    // Trailing blank parameters carry no information: `MX, 5,` is `MX, 5`.
    while (!cmd.params.empty() && cmd.params.back().blank()) cmd.params.pop_back();
    return true;
  }

  bool rest_is_empty() {
    skip_space();
    return at_end() || peek() == '\'';
  }
  void skip_space() {
    while (!at_end() && is_space(peek())) ++pos_;
  }
  bool at_end() const { return pos_ >= s_.size(); }
  char peek() const { return s_[pos_]; }
  SourceLoc loc(size_t col0) const {
    return SourceLoc{prog_.file, line_no_, static_cast<int>(col0) + 1};
  }
  void error(Program& out, size_t col0, std::string msg) {
    out.errors.push_back({loc(col0), Severity::Error, std::move(msg)});
  }

  std::string_view s_;
  size_t pos_ = 0;
  int line_no_;
  const Program& prog_;
};

}  // namespace

Program parse_program(std::string_view text, const std::string& file_name) {
  Program prog;
  prog.file = std::make_shared<const std::string>(file_name);
  int line_no = 0;
  size_t start = 0;
  while (start < text.size()) {
    size_t nl = text.find('\n', start);
    if (nl == std::string_view::npos) nl = text.size();
    ++line_no;
    LineParser(text.substr(start, nl - start), line_no, prog).parse(prog);
    start = nl + 1;
  }
  return prog;
}

Program parse_file(const std::string& path) {
  const std::optional<std::string> text = read_text_file(path);
  if (!text) {
    Program prog;
    prog.file = std::make_shared<const std::string>(path);
    prog.errors.push_back({SourceLoc{prog.file, 0, 0}, Severity::Error,
                           "cannot open the part file; check the name and that it exists"});
    return prog;
  }
  return parse_program(*text, path);
}

}  // namespace gantry
