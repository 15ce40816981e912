// The modal state: what the language defines and commands change (position, zero, speeds...).
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "gantry/canon/canon_move.hpp"      // IndependentMotion
#include "gantry/core/vec6.hpp"             // Vec6
#include "gantry/core/diagnostic.hpp"       // SourceLoc
#include "gantry/interp/gcode_state.hpp"    // GcodeOffsets
#include "gantry/settings/settings.hpp"     // SpeedSettings

namespace gantry {

// Where the tool was when SP started a preview: SM returns there.
struct PreviewReturn {
  Vec6 position, zero, machine_origin, applied_offset, tool_offset;
};

// The state the language defines and commands change.
struct ModalState {
  Vec6 position = Vec6::Zero();  // commanded position: working coordinates, machine units
  Vec6 zero = Vec6::Zero();      // where working 0 is in table base coordinates (Z commands)
  bool absolute = true;          // SA (true) or SR (false)
  SpeedSettings speeds;          // MS / JS / VS
  std::uint32_t outputs = 0;     // SO: bit n-1 set while output switch n is on
  double spindle_rpm = 0;        // TR: the speed asked for; the spindle (output 1) runs at it
  std::optional<std::array<double, 2>> last_xy_move;  // its X, Y displacement (for MD)
  // Where table base 0 is in the machine's own frame, the one the step counts are in: ZT,
  // UZ and VA's table base fields move table base coordinates without moving the tool.
  Vec6 machine_origin = Vec6::Zero();
  // VO: the offset the next move adds (zero while off), the one the tool is at now, and the
  // values last entered (turning VO on again uses them).
  Vec6 tool_offset = Vec6::Zero(), applied_offset = Vec6::Zero(), tool_offset_values = Vec6::Zero();
  // VB's in-file tab control, for the cut commands: on, how many tabs, where the first is.
  bool tabs_on = false;
  int tab_count = 0;
  double first_tab = 0;
  // Tabs on plain moves (VB on, FP's tab feature): how far the tool has gone along the path
  // since it last came down from Safe-Z, how far above the file's Z a tab holds it now, and
  // how many tabs of this path it has passed.
  double tab_travel = 0;
  double tab_lift = 0;
  int tabs_passed = 0;
  std::optional<PreviewReturn> preview;  // SP: moves reach no motor until SM
  // CG's centre offsets I and J: modal, as in G-code; a blank one keeps the last given.
  std::array<double, 2> cg_center_offset{0, 0};
  // SC 0 (table base system): the user system's offsets (`zero` when SC 1), set aside.
  std::optional<Vec6> user_zero;
  GcodeOffsets gcode;  // G54..G59.3, G92, G28/G30 positions, the tool table (docs/gcode.md)
  // MI: the axis moving on its own (no move of the file may move it meanwhile; its location
  // here is where it started, until it stops), and the line that started it.
  std::optional<IndependentMotion> independent;
  SourceLoc independent_loc;
};

}  // namespace gantry
