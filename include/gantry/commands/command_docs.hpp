// Help text and the command reference page, generated from the command table.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandTable, CommandSpec
#include "gantry/lang/statement_table.hpp"    // StatementSpec

namespace gantry {

// One command: its name, what it does, and its parameters in part-file order.
std::string command_help(const CommandSpec& spec);
// Every command, one line each, grouped.
std::string command_list(const CommandTable& table);
// One keyword statement: its forms and where docs/language.md describes it.
std::string statement_help(const StatementSpec& spec);
// Custom cut `number`: the opening comment of the first C<n>.sbp or macro_<n>.sbp found in
// `macro_folders` (in order, as a part file's C<n> finds it), with its path; none found: say
// where it was looked for.
std::string custom_cut_help(int number, const std::vector<std::string>& macro_folders);
// `help WORD` at any front end: a two-letter command, a keyword statement or a custom cut
// C<n>; empty when the word is none of them.
std::optional<std::string> help_topic(std::string_view word,
                                      const std::vector<std::string>& macro_folders);

// docs/commands.md, exactly.
std::string commands_markdown(const CommandTable& table);

}  // namespace gantry
