// Help text and the command reference page, generated from the command table.
#pragma once

#include <string>

#include "gantry/commands/command_table.hpp"  // CommandTable, CommandSpec

namespace gantry {

// One command: its name, what it does, and its parameters in part-file order.
std::string command_help(const CommandSpec& spec);
// Every command, one line each, grouped.
std::string command_list(const CommandTable& table);
// docs/commands.md, exactly.
std::string commands_markdown(const CommandTable& table);

}  // namespace gantry
