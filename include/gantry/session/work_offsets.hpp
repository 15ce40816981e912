// The work offsets per axis, as the window's offsets view shows them: where the tool is in
// table base (machine) coordinates, the offset to working 0 (the Z commands' zero and any
// applied offset), the working position, and the Z command that zeroes the axis.
#pragma once

#include <string>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandTable
#include "gantry/core/axes.hpp"               // Vec6
#include "gantry/interp/modal_state.hpp"      // ModalState

namespace gantry::session {

struct OffsetRow {
  char axis;
  double table, offset, work;  // table = work + offset
  std::string zero_code;       // the command that zeroes it ("" when there is none)
};

// The rows for the first `axes` axes, the tool at `work` (working coordinates).
std::vector<OffsetRow> offset_rows(const Vec6& work, const ModalState& m, int axes,
                                   const CommandTable& table);

}  // namespace gantry::session
