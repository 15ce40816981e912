// The command line's model: completion, parameter line, history and menus.
#include "command_line.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace gantry::ui {
namespace {

char up(char c) {
  return static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
}

bool code_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0;
}

// The first parameter of `line` starts after its first comma (or blank after the code).
std::size_t params_start(std::string_view line) {
  std::size_t i = 2;
  while (i < line.size() && line[i] == ' ') ++i;
  if (i < line.size() && line[i] == ',') ++i;
  return i;
}

}  // namespace

std::vector<const CommandSpec*> completions(const CommandTable& table, std::string_view typed) {
  const std::size_t b = typed.find_first_not_of(' ');
  if (b == std::string_view::npos) return {};
  const std::string_view t = typed.substr(b);
  if (t.size() > 2 || !std::all_of(t.begin(), t.end(), code_char)) return {};
  std::vector<const CommandSpec*> out;
  for (const CommandSpec& s : table.all()) {
    bool match = true;
    for (std::size_t i = 0; i < t.size(); ++i) match = match && s.code[i] == up(t[i]);
    if (match) out.push_back(&s);
  }
  return out;
}

std::string complete(const CommandTable& table, std::string_view typed) {
  const std::vector<const CommandSpec*> m = completions(table, typed);
  if (m.empty()) return std::string(typed);
  if (m.size() == 1) return std::string(m[0]->code) + (m[0]->params.empty() ? "" : ", ");
  // The longest prefix every match shares (a code is two letters: the first, or none).
  std::string prefix(m[0]->code);
  for (const CommandSpec* s : m)
    while (!prefix.empty() && s->code.substr(0, prefix.size()) != prefix) prefix.pop_back();
  const std::size_t b = typed.find_first_not_of(' ');
  return prefix.size() >= typed.size() - b ? prefix : std::string(typed);
}

const CommandSpec* command_of(const CommandTable& table, std::string_view line) {
  const std::size_t b = line.find_first_not_of(' ');
  if (b == std::string_view::npos) return nullptr;
  line = line.substr(b);
  if (line.size() < 2 || (line.size() > 2 && line[2] != ',' && line[2] != ' ')) return nullptr;
  const std::string code{up(line[0]), up(line[1])};
  return table.find(code);
}

ParamLine param_line(const CommandSpec& spec, Dialect dialect, std::string_view line,
                     std::size_t cursor) {
  ParamLine out;
  const std::vector<ParamSpec>& params = spec.params_for(dialect);
  const std::size_t b = line.find_first_not_of(' ');
  const std::string_view rest = b == std::string_view::npos ? line : line.substr(b);
  cursor = cursor > b && b != std::string_view::npos ? cursor - b : 0;
  // Which parameter holds the cursor: the number of commas before it (quotes aside).
  const std::size_t start = params_start(rest);
  if (rest.size() > 2 && cursor > 2) {
    int commas = 0;
    bool quoted = false;
    for (std::size_t i = start; i < std::min(cursor, rest.size()); ++i) {
      if (rest[i] == '"') quoted = !quoted;
      if (rest[i] == ',' && !quoted) ++commas;
    }
    out.current = params.empty() ? -1 : std::min<int>(commas, static_cast<int>(params.size()) - 1);
  }
  out.text = fmt::format("{}  {}", spec.code, spec.name);
  for (std::size_t i = 0; i < params.size(); ++i) {
    const ParamSpec& p = params[i];
    std::string unit = p.unit.empty() ? "" : fmt::format(" {}", p.unit);
    std::string def = p.default_value ? fmt::format(" ={}", *p.default_value) : "";
    const bool here = static_cast<int>(i) == out.current;
    out.text += fmt::format("{} {}{}{}{}{}", i == 0 ? ":" : ",", here ? "[" : "", p.name, unit, def,
                            here ? "]" : "");
  }
  if (out.current >= 0)
    out.help = fmt::format("{}: {}", params[static_cast<std::size_t>(out.current)].name,
                           params[static_cast<std::size_t>(out.current)].help);
  else
    out.help = std::string(spec.help);
  return out;
}

EnterAction enter_action(const CommandTable& table, std::string_view line) {
  const std::size_t b = line.find_first_not_of(" \t");
  if (b == std::string_view::npos) return EnterAction::Nothing;
  const std::size_t e = line.find_last_not_of(" \t,");
  const CommandSpec* spec = command_of(table, line);
  // A code alone (perhaps with its comma): its parameters are asked for, unless it has none.
  if (spec && e - b + 1 == 2 && !spec->immediate) return EnterAction::OpenSheet;
  return EnterAction::Run;
}

void History::add(const std::string& line) {
  pos_ = lines_.size();
  if (line.find_first_not_of(" \t") == std::string::npos) return;
  if (!lines_.empty() && lines_.back() == line) return;
  lines_.push_back(line);
  if (lines_.size() > limit_) lines_.erase(lines_.begin());
  pos_ = lines_.size();
}

std::optional<std::string> History::up(const std::string& current) {
  if (pos_ > lines_.size()) pos_ = lines_.size();
  if (pos_ == 0) return std::nullopt;
  if (pos_ == lines_.size()) draft_ = current;
  return lines_[--pos_];
}

std::optional<std::string> History::down() {
  if (pos_ >= lines_.size()) return std::nullopt;
  ++pos_;
  return pos_ == lines_.size() ? draft_ : lines_[pos_];
}

std::vector<Menu> menus(const CommandTable& table) {
  using G = CommandGroup;
  const G order[] = {G::Cuts,     G::File,  G::Jog,       G::Move, G::Zero,  G::Values,
                     G::Settings, G::Tools, G::Utilities, G::Help, G::Probe, G::Record};
  std::vector<Menu> out;
  for (G g : order) {
    Menu m;
    m.title = group_name(g);
    for (const CommandSpec& s : table.all())
      if (s.group == g) m.commands.push_back(&s);
    if (m.commands.empty()) continue;
    // The hot key: the letter most of the group's codes start with (M for Move: MS is a
    // Move command too, Z2 is Zero's).
    int best = 0;
    for (const CommandSpec* s : m.commands) {
      const int n = static_cast<int>(
          std::count_if(m.commands.begin(), m.commands.end(),
                        [&](const CommandSpec* o) { return o->code[0] == s->code[0]; }));
      if (n > best) best = n, m.key = s->code[0];
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace gantry::ui
