// gantry(1), the manual page, generated from the program's own subcommands and options, the
// command table and the statement table (`gantry help --man`; the install step ships it).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace gantry {

std::string man_page(const CLI::App& app);

}  // namespace gantry
