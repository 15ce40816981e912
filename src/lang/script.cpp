// Line access, the label index and the whole-file syntax pass.
#include "gantry/lang/script.hpp"

#include <fmt/format.h>  // messages

#include "gantry/core/text_file.hpp"  // read_text_file

namespace gantry {
namespace {

// Jumps found in a statement (GOTO/GOSUB, also as IF and ON INPUT actions).
void collect_jumps(const Statement& st, std::vector<const JumpStmt*>& out) {
  if (const auto* j = std::get_if<JumpStmt>(&st.body)) out.push_back(j);
  if (const auto* i = std::get_if<IfStmt>(&st.body)) collect_jumps(*i->action, out);
  if (const auto* o = std::get_if<OnInputStmt>(&st.body))
    if (o->action) collect_jumps(*o->action, out);
}

}  // namespace

Script::Script(std::string text, const std::string& name)
    : text_(std::move(text)), name_(std::make_shared<const std::string>(name)) {
  if (text_.rfind("\xEF\xBB\xBF", 0) == 0) text_start_ = 3;
}

std::shared_ptr<const Script> Script::load(const std::string& path) {
  std::optional<std::string> text = read_text_file(path);
  std::shared_ptr<Script> s(new Script(text ? std::move(*text) : std::string(), path));
  if (!text) {
    s->errors_.push_back({SourceLoc{s->name_, 0, 0}, Severity::Error,
                          "cannot open the part file; check the name and that it exists"});
    return s;
  }
  s->index();
  return s;
}

std::shared_ptr<const Script> Script::from_text(std::string text, const std::string& name) {
  std::shared_ptr<Script> s(new Script(std::move(text), name));
  s->index();
  return s;
}

bool Script::ok() const {
  for (const Diagnostic& d : errors_)
    if (d.severity == Severity::Error) return false;
  return true;
}

// Lines end at "\n", "\r\n" or a lone "\r" (DOS, Unix and old Mac files alike).
std::string_view Script::line_at(Cursor c, Cursor* next) const {
  // A plain scan: find_first_of with a set calls memchr once per character.
  size_t stop = std::min(c.offset, text_.size());
  while (stop < text_.size() && text_[stop] != '\n' && text_[stop] != '\r') ++stop;
  size_t after = stop;
  if (after < text_.size())
    after += (text_[after] == '\r' && after + 1 < text_.size() && text_[after + 1] == '\n') ? 2 : 1;
  if (next) *next = {after, c.line + 1};
  return std::string_view(text_).substr(c.offset, stop - c.offset);
}

std::optional<std::string_view> Script::line_before(Cursor c) const {
  if (c.offset <= text_start_) return std::nullopt;
  size_t end = c.offset;  // strip this line's predecessor's terminator
  if (end > 0 && text_[end - 1] == '\n') --end;
  if (end > 0 && text_[end - 1] == '\r') --end;
  size_t begin = text_.find_last_of("\r\n", end == 0 ? 0 : end - 1);
  begin = (begin == std::string::npos || end == 0) ? text_start_ : begin + 1;
  if (begin > end) begin = end;
  return std::string_view(text_).substr(begin, end - begin);
}

std::optional<Cursor> Script::label(const std::string& name) const {
  auto it = labels_.find(name);
  if (it == labels_.end()) return std::nullopt;
  return it->second;
}

LineParse Script::parse(Cursor c, Cursor* next) const {
  return parse_line(line_at(c, next), name_, c.line);
}

void Script::index() {
  std::vector<std::pair<std::string, SourceLoc>> targets;
  Cursor c = start();
  while (!at_end(c)) {
    Cursor next;
    LineParse lp = parse(c, &next);
    ++lines_;
    if (lp.error) errors_.push_back(*lp.error);
    if (lp.statement) {
      if (const auto* l = std::get_if<LabelStmt>(&lp.statement->body)) {
        if (!labels_.emplace(l->name, next).second)
          errors_.push_back({lp.statement->loc, Severity::Warning,
                             fmt::format("label {} is defined again; jumps go to the first one, "
                                         "line {}",
                                         l->name, labels_.at(l->name).line - 1)});
      }
      std::vector<const JumpStmt*> jumps;
      collect_jumps(*lp.statement, jumps);
      for (const JumpStmt* j : jumps) targets.emplace_back(j->label, j->label_loc);
    }
    c = next;
  }
  for (const auto& [label, loc] : targets)
    if (!labels_.count(label))
      errors_.push_back({loc, Severity::Error,
                         fmt::format("no label {}: in this file; labels are written on their own "
                                     "line as NAME:",
                                     label)});
}

}  // namespace gantry
