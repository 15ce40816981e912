// OpenSBP text to statements: pure, no I/O beyond reading the file it is given.
#pragma once

#include <string>

#include "gantry/lang/statement.hpp"  // Program

namespace gantry {

// Parses part-file text. Every line that cannot be read adds one located diagnostic;
// parsing continues so that a check reports all of them.
Program parse_program(std::string_view text, const std::string& file_name);

// Reads and parses a file; an unreadable file gives a Program with one error.
Program parse_file(const std::string& path);

}  // namespace gantry
