// The standard command table, assembled from each command family's registration.
#include "gantry/commands/command_table.hpp"

#include <algorithm>  // find_if

namespace gantry {

CommandTable::CommandTable(std::vector<CommandSpec> specs) : specs_(std::move(specs)) {}

const CommandTable& CommandTable::standard() {
  static const CommandTable table = [] {
    std::vector<CommandSpec> specs;
    add_move_commands(specs);
    add_mode_commands(specs);
    add_file_commands(specs);
    return CommandTable(std::move(specs));
  }();
  return table;
}

const CommandSpec* CommandTable::find(std::string_view code) const {
  auto it = std::find_if(specs_.begin(), specs_.end(),
                         [&](const CommandSpec& s) { return s.code == code; });
  return it == specs_.end() ? nullptr : &*it;
}

const char* group_name(CommandGroup g) {
  switch (g) {
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
  }
  return "?";
}

}  // namespace gantry
