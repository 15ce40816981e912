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

// The common line, a two-letter command whose parameters are blank or plain numbers
// (`M3, 1.5, , -2`), read quickly. When `line` is one, `out` receives exactly the statement
// parse_line would give (its storage is reused: pass the same Statement line after line) and
// the result is true; otherwise false, and parse_line reads it.
bool parse_simple_command(std::string_view line, const std::shared_ptr<const std::string>& file,
                          int line_no, Statement* out);
// The common statements of hand-written files read quickly, as parse_simple_command reads
// commands: `&name = expression`, `IF test THEN` GOTO, GOSUB, RETURN or such an assignment,
// `GOTO label`, `GOSUB label`, `RETURN`, `LABEL:` (src/lang/common_statement.cpp says which
// spellings). When `line` is one, `out` receives exactly the statement parse_line would give
// (under ExprCheckOnly, its placeholders) and the result is true; otherwise false, `out` is
// left in any state, and parse_line reads the line. Reuse `out` line after line.
bool parse_common_statement(std::string_view line, const std::shared_ptr<const std::string>& file,
                            int line_no, Statement* out);
// Whether parse_simple_command would accept `line`: such a line has no syntax error.
bool is_simple_command(std::string_view line);

// A line of a G-code file (docs/gcode.md): a G-code block (GcodeStmt), nothing (blank,
// comments, `%`), or the reason it is not G-code.
LineParse parse_gcode_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                           int line_no);
// The same without allocating for a plain block: true when `line` holds a block without error,
// which `out` receives (pass the same Statement line after line); otherwise false, and
// parse_gcode_line reads it.
bool parse_gcode_statement(std::string_view line, const std::shared_ptr<const std::string>& file,
                           int line_no, Statement* out);

}  // namespace gantry
