// The simple-command reader's check for the load pass (src/lang/simple_command.cpp).
#pragma once

#include <string_view>

namespace gantry {

// is_simple_command (gantry/lang/parser.hpp), and `code` receives the command's two letters,
// upper case: all the load pass checks of such a line. Its numbers are not valued (the run
// reads them).
bool simple_command_code(std::string_view line, char code[2]);

}  // namespace gantry
