// The work-offset view: per axis where the tool is in table base (machine) coordinates, the
// offset to working 0 (the Z commands' zero and any applied offset) and the working position,
// with a Zero button per axis that runs the console's own Z command (ZX, ZY ...).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandTable
#include "gantry/core/axes.hpp"               // Vec6
#include "gantry/interp/modal_state.hpp"      // ModalState

namespace gantry::ui {

struct OffsetRow {
  char axis;
  double table, offset, work;  // table = work + offset
  std::string zero_code;       // the command that zeroes it ("" when there is none)
};

// The rows for the first `axes` axes, the tool at `work` (working coordinates).
std::vector<OffsetRow> offset_rows(const Vec6& work, const ModalState& m, int axes,
                                   const CommandTable& table);

// Draws the rows in the current window. `button(label)` draws a button as the window does
// (a script may click it by its label) and says whether it was pressed. Returns the Z command
// a Zero button asks for, or "".
std::string offsets_panel(const std::vector<OffsetRow>& rows, const char* units, bool can_zero,
                          const std::function<bool(const std::string&, bool)>& button);

}  // namespace gantry::ui
