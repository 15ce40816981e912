// OpenSBP text to statements, one physical line at a time: pure, no I/O.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "gantry/lang/statement.hpp"  // Statement

namespace gantry {

// One physical line: nothing (blank or comment), a statement, or the reason it is not one.
struct LineParse {
  std::optional<Statement> statement;
  std::optional<Diagnostic> error;
  std::optional<std::string> comment;  // the text of a full-line comment (`'` or REM)
};

// `line` excludes its line terminator. `file` and `line_no` locate everything in it.
LineParse parse_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                     int line_no);

}  // namespace gantry
