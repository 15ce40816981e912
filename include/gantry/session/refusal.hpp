// How a refused line or file is shown: a diagnostic located in the line typed at the console
// gets its column (and, at a terminal, a caret under the line); others are shown as
// `FILE:LINE:COL: error: ...`.
#pragma once

#include <string>
#include <vector>

#include "gantry/core/diagnostic.hpp"     // Diagnostic
#include "gantry/machine/controller.hpp"  // Outcome

namespace gantry::session {

// The diagnostic is in the one line typed at the console (not in a file it ran).
bool in_typed_line(const Diagnostic& d);

// At a terminal: under the line typed after `prompt`, a caret at each diagnostic's column.
// `echo_first`: print the line again before the first caret (it scrolled off); `estop`: the
// machine is E-stopped (a reason then says to type ack). Ends with a newline.
std::string refusal_under_line(const std::string& prompt, const std::string& line, const Outcome& o,
                               bool echo_first, bool estop);

// In a log: one entry per diagnostic, or "WHAT: reason" when the refusal has none.
std::vector<std::string> refusal_entries(const Outcome& o, const std::string& what);

}  // namespace gantry::session
