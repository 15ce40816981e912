// G-code's coordinate data and tool table, kept with the machine's modal state so that they
// last from job to job as SB3's zero does (docs/gcode.md, "Offsets").
#pragma once

#include <array>

#include "gantry/core/vec6.hpp"          // Vec6
#include "gantry/interp/tool_table.hpp"  // ToolTable

namespace gantry {

struct GcodeOffsets {
  // The work coordinate systems G54 (0) .. G59.3 (8): where each one's 0 is, in table base
  // coordinates. The active one is SB3's zero (ModalState::zero, which the Z commands set);
  // its slot here is written when another system is selected.
  int system = 0;
  std::array<Vec6, 9> origin{};
  // G92: added to program coordinates to give working ones; `saved` keeps the last values
  // set (G92.2 suspends them, G92.3 restores them).
  Vec6 axis_offset = Vec6::Zero();
  Vec6 axis_offset_saved = Vec6::Zero();
  std::array<Vec6, 2> stored{};  // G28 and G30 positions (G28.1, G30.1), table base
  // The tool table: the profile's file (tool_table, --tool-table) as last read or written,
  // or the implicit one (no file: every tool of length 0).
  ToolTable tools;
  int tool = 0;            // the tool in the spindle (M6, M61)
  double tool_length = 0;  // G43: program Z 0 is this far above the spindle's working Z 0
  double measured_length = 0;  // WinCNC's M37: the length G43 turns on (G49 off)

  GcodeOffsets() {
    for (Vec6& v : origin) v.setZero();
    for (Vec6& v : stored) v.setZero();
  }
  // A change of the machine's units (VD, SU): every length scales by `k` (per axis).
  void scale(const Vec6& k) {
    for (Vec6& v : origin) v = v.cwiseProduct(k);
    for (Vec6& v : stored) v = v.cwiseProduct(k);
    axis_offset = axis_offset.cwiseProduct(k);
    axis_offset_saved = axis_offset_saved.cwiseProduct(k);
    tools.scale(k[2]);
    tool_length *= k[2];
    measured_length *= k[2];
  }
};

}  // namespace gantry
