// Generated help: the command table is the only place a command is described.
#include "gantry/commands/command_docs.hpp"

#include <fmt/format.h>  // layout

#include <charconv>    // from_chars
#include <filesystem>  // the macro files
#include <fstream>

#include "gantry/core/text.hpp"  // ascii::upper, trim

namespace gantry {
namespace {

// SB3's menu order, with FabMo's probe commands after the moves.
constexpr CommandGroup kGroupOrder[] = {
    CommandGroup::Cuts,  CommandGroup::File,      CommandGroup::Help,   CommandGroup::Jog,
    CommandGroup::Move,  CommandGroup::Probe,     CommandGroup::Record, CommandGroup::Settings,
    CommandGroup::Tools, CommandGroup::Utilities, CommandGroup::Values, CommandGroup::Zero};

std::string coverage(const CommandSpec& s) {
  return s.coverage.empty() ? "complete" : std::string(s.coverage);
}

std::string param_default(const ParamSpec& p) {
  if (p.required) return "required";
  if (p.default_value) return fmt::format("{}", *p.default_value);
  return "blank: unchanged";
}

}  // namespace

std::string command_help(const CommandSpec& spec) {
  std::string out = fmt::format("{} - {}\n  {}\n", spec.code, spec.name, spec.help);
  if (spec.params.empty()) return out + "  No parameters.\n";
  out += fmt::format("  Usage: {}", spec.code);
  for (const ParamSpec& p : spec.params) out += fmt::format(", {}", p.name);
  out += "\n";
  for (size_t i = 0; i < spec.params.size(); ++i) {
    const ParamSpec& p = spec.params[i];
    out += fmt::format("  {:>2}. {} ({}{}{}): {}\n", i + 1, p.name, p.unit,
                       p.unit.empty() ? "" : "; ", param_default(p), p.help);
  }
  return out;
}

std::string statement_help(const StatementSpec& spec) {
  std::string out = fmt::format("{} - {}\n", spec.word, spec.title);
  std::string_view forms = spec.forms;
  while (!forms.empty()) {
    const size_t nl = forms.find('\n');
    out += fmt::format("  {}\n", forms.substr(0, nl));
    forms = nl == std::string_view::npos ? std::string_view{} : forms.substr(nl + 1);
  }
  return out + fmt::format("  docs/language.md, section {}.\n", spec.section);
}

std::string custom_cut_help(int number, const std::vector<std::string>& folders) {
  namespace fs = std::filesystem;
  std::vector<std::string> macro_folders;
  for (const std::string& f : folders)
    if (!f.empty()) macro_folders.push_back(f);
  for (const std::string& dir : macro_folders)
    for (const std::string& name :
         {fmt::format("C{}.sbp", number), fmt::format("macro_{}.sbp", number)}) {
      const fs::path path = fs::path(dir) / name;
      std::error_code ec;
      if (!fs::is_regular_file(path, ec)) continue;
      std::ifstream in(path);
      std::string out = fmt::format("C{} - custom cut {}: {}\n", number, number, path.string());
      std::string line;
      // The opening comment block says what the macro does (the shipped ones are written so).
      for (int n = 0; n < 60 && std::getline(in, line); ++n) {
        std::string_view t = ascii::trim_back(line);
        if (t.empty() || t[0] != '\'') break;
        t.remove_prefix(t.size() > 1 && t[1] == ' ' ? 2 : 1);  // the quote and one space
        out += t.empty() ? std::string("\n") : fmt::format("  {}\n", t);
      }
      return out;
    }
  std::string where;
  for (size_t i = 0; i < macro_folders.size(); ++i)
    where += (i == 0 ? "" : i + 1 == macro_folders.size() ? " or " : ", ") + macro_folders[i];
  return fmt::format("C{0} - custom cut {0}: there is no C{0}.sbp or macro_{0}.sbp in {1}{2}\n",
                     number, where, number == 3 ? " (C3 then runs the built-in homing)" : "");
}

std::optional<std::string> help_topic(std::string_view word,
                                      const std::vector<std::string>& macro_folders) {
  const std::string up = ascii::upper(ascii::trim(word));
  const CommandSpec* command = CommandTable::standard().find(up);
  int n = -1;  // C<n>: C and one to four digits, as the parser reads a custom cut
  if (up.size() >= 2 && up.size() <= 5 && up[0] == 'C' &&
      up.find_first_not_of("0123456789", 1) == std::string::npos &&
      std::from_chars(up.data() + 1, up.data() + up.size(), n).ec == std::errc{})
    return (command ? command_help(*command) : "") + custom_cut_help(n, macro_folders);  // C3
  if (command) return command_help(*command);
  if (const StatementSpec* spec = find_statement(up)) return statement_help(*spec);
  return std::nullopt;
}

namespace {

// How the plain list marks a command that is not complete.
std::string coverage_note(const CommandSpec& s) {
  if (s.coverage.empty()) return "";
  if (s.coverage.starts_with("refused by name: ")) return " (cannot run here)";
  return fmt::format(" (partial; missing: {})", s.coverage);
}

}  // namespace

std::string command_list(const CommandTable& table) {
  std::string out;
  for (CommandGroup g : kGroupOrder) {
    out += fmt::format("{}:\n", group_name(g));
    for (const CommandSpec& s : table.all())
      if (s.group == g) out += fmt::format("  {}  {}{}\n", s.code, s.name, coverage_note(s));
  }
  out += "Statements:\n";
  for (const StatementSpec& s : statement_table())
    if (s.keyword != Keyword::DataSend) out += fmt::format("  {:<16}  {}\n", s.word, s.title);
  return out +
         "Custom cuts: C<n> runs C<n>.sbp from the macro folders (C2 zero Z, C3 home, C6 and C7 "
         "spindle, C9 tool change).\n"
         "Friendly Motion files (.fm): `gantry help fm` lists their commands.\n"
         "Type `gantry help WORD` for a command's parameters, a statement's forms or a custom "
         "cut's description.\n";
}

std::string commands_markdown(const CommandTable& table) {
  std::string out =
      "# Gantry commands\n\n"
      "Generated from the command table by `gantry help --markdown`; do not edit by hand.\n"
      "Parameters are listed in part-file order. A blank parameter (nothing between two "
      "commas) keeps the current value unless the table says otherwise.\n";
  size_t complete = 0;
  for (const CommandSpec& s : table.all()) complete += s.coverage.empty();
  out += fmt::format(
      "\n{} of {} codes complete. A code refused by name stops the file with an error "
      "saying why; nothing else happens.\n\n| Code | Name | Group | Coverage |\n"
      "|---|---|---|---|\n",
      complete, table.all().size());
  for (CommandGroup g : kGroupOrder)
    for (const CommandSpec& s : table.all())
      if (s.group == g)
        out += fmt::format("| {} | {} | {} | {} |\n", s.code, s.name, group_name(g), coverage(s));
  for (CommandGroup g : kGroupOrder) {
    out += fmt::format("\n## {}\n", group_name(g));
    for (const CommandSpec& s : table.all()) {
      if (s.group != g) continue;
      out += fmt::format("\n### {} - {}\n\n{}\n\nCoverage: {}.\n", s.code, s.name, s.help,
                         coverage(s));
      if (s.params.empty()) {
        out += "\nNo parameters.\n";
        continue;
      }
      out += "\n| # | Parameter | Unit | Default | Meaning |\n|---|---|---|---|---|\n";
      for (size_t i = 0; i < s.params.size(); ++i) {
        const ParamSpec& p = s.params[i];
        out += fmt::format("| {} | {} | {} | {} | {} |\n", i + 1, p.name, p.unit, param_default(p),
                           p.help);
      }
    }
  }
  return out;
}

}  // namespace gantry
