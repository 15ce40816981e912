// Generated help: the command table is the only place a command is described.
#include "gantry/commands/command_docs.hpp"

#include <fmt/format.h>  // layout

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
  return out + "Type `gantry help CODE` for a command's parameters.\n";
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
