// The work-offset view: session::offset_rows drawn as a table, with a Zero button per axis that
// runs the console's own Z command (ZX, ZY ...).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "gantry/session/work_offsets.hpp"  // OffsetRow

namespace gantry::ui {

using session::OffsetRow;

// Draws the rows in the current window. `button(label)` draws a button as the window does
// (a script may click it by its label) and says whether it was pressed. Returns the Z command
// a Zero button asks for, or "".
std::string offsets_panel(const std::vector<OffsetRow>& rows, const char* units, bool can_zero,
                          const std::function<bool(const std::string&, bool)>& button);

}  // namespace gantry::ui
