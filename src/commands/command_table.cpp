// The standard command table, assembled from each command family's registration.
#include "gantry/commands/command_table.hpp"

#include <fmt/format.h>  // ranges in words

#include <algorithm>  // find_if

namespace gantry {

namespace {

// Two characters of [A-Z0-9] as an index 0..1295, or -1.
int code_index(std::string_view code) {
  auto digit = [](char c) {
    return c >= 'A' && c <= 'Z' ? c - 'A' : c >= '0' && c <= '9' ? 26 + c - '0' : -1;
  };
  if (code.size() != 2 || digit(code[0]) < 0 || digit(code[1]) < 0) return -1;
  return digit(code[0]) * 36 + digit(code[1]);
}

}  // namespace

CommandTable::CommandTable(std::vector<CommandSpec> specs) : specs_(std::move(specs)) {
  index_.fill(-1);
  for (CommandSpec& s : specs_) s.immediate |= s.params.empty();  // nothing to ask for
  for (size_t i = 0; i < specs_.size(); ++i)
    if (const int k = code_index(specs_[i].code); k >= 0) index_[k] = static_cast<int>(i);
}

const CommandTable& CommandTable::standard() {
  static const CommandTable table = [] {
    std::vector<CommandSpec> specs;
    add_move_commands(specs);
    add_probe_commands(specs);
    add_mode_commands(specs);
    add_file_commands(specs);
    add_output_commands(specs);
    add_zero_commands(specs);
    add_move_distance(specs);
    add_values_commands(specs);
    add_settings_commands(specs);
    add_help_commands(specs);
    add_tool_commands(specs);
    add_utility_commands(specs);
    add_cut_commands(specs);
    add_record_commands(specs);
    add_nudge_commands(specs);
    return CommandTable(std::move(specs));
  }();
  return table;
}

const CommandSpec* CommandTable::find(std::string_view code) const {
  const int k = code_index(code);  // every command is looked up once per executed line
  return k < 0 || index_[k] < 0 ? nullptr : &specs_[index_[k]];
}

std::string_view param_type(const ParamSpec& p) {
  if (p.kind == ParamKind::Text)
    return !p.choices.empty()                              ? "choice"
           : p.name.find("file") != std::string_view::npos ? "filename"
                                                           : "text";
  if (p.whole) return p.min == 0 && p.max == 1 ? "flag" : "int";
  if (p.unit == "units") return "distance";
  if (p.unit == "units/s") return "speed";
  if (p.unit == "deg") return "angle";
  return "number";
}

std::string param_range(const ParamSpec& p) {
  if (!p.choices.empty()) {
    std::string out;
    std::string_view rest = p.choices;
    while (!rest.empty()) {
      const size_t space = rest.find(' ');
      const std::string_view word = rest.substr(0, space);
      rest = space == std::string_view::npos ? std::string_view{} : rest.substr(space + 1);
      out += fmt::format("{}{}", out.empty() ? "" : rest.empty() ? " or " : ", ", word);
    }
    return out;
  }
  if (p.min && p.max) return fmt::format("{} to {}", *p.min, *p.max);
  if (p.min) return fmt::format(">= {}", *p.min);
  if (p.max) return fmt::format("<= {}", *p.max);
  return "";
}

const char* group_name(CommandGroup g) {
  switch (g) {
    case CommandGroup::Cuts:
      return "Cuts";
    case CommandGroup::Help:
      return "Help";
    case CommandGroup::Probe:
      return "Probe";
    case CommandGroup::Record:
      return "Record";
    case CommandGroup::Tools:
      return "Tools";
    case CommandGroup::Utilities:
      return "Utilities";
    case CommandGroup::File:
      return "File";
    case CommandGroup::Jog:
      return "Jog";
    case CommandGroup::Move:
      return "Move";
    case CommandGroup::Settings:
      return "Settings";
    case CommandGroup::Values:
      return "Values";
    case CommandGroup::Zero:
      return "Zero";
  }
  return "?";
}

}  // namespace gantry
