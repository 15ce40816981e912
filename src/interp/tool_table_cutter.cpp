// SB3's cutter (VC) and G-code's tool table in step (docs/gcode.md, "Tool table"): M6/M61
// (gcode_tools.cpp) and an &Tool + C9 change give VC the diameter of the tool in the spindle;
// a VC that changes the diameter writes it back as that tool's D, through the same atomic
// writer as G10 L1.
#include <fmt/format.h>  // messages

#include "gantry/interp/command_context.hpp"
#include "gantry/interp/tool_table.hpp"
#include "gantry/interp/value.hpp"  // format_number

namespace gantry {

void cutter_to_tool_table(CommandContext& ctx, double diameter, const SourceLoc& loc) {
  const std::string& path = ctx.settings().tool_table_path;
  GcodeOffsets& o = ctx.state().gcode;
  if (path.empty() || o.tool == 0) return;  // no file, or the empty spindle: VC only
  ToolTable& table = o.tools;
  // The file as it is now (an editor may have changed it since G-code last read it).
  refresh_tool_table(table, path, loc);
  ToolTable changed = table;  // a failed write keeps the file and this table as they were
  ToolEntry* e = changed.change(o.tool);
  if (!e)
    fail(loc, fmt::format("VC: tool {} (in the spindle) is not in the tool table {}, so its "
                          "diameter cannot be written there; add a line T{} P{} for it",
                          o.tool, path, o.tool, o.tool));
  if (e->diameter == diameter) return;
  e->diameter = diameter;
  if (ctx.writes_to_disk()) {  // a check or a preview changes the table in memory only
    if (std::string why; !save_tool_table(changed, &why))
      fail(loc, fmt::format("VC: could not write tool {}'s diameter to the tool table {} ({}); "
                            "the previous file is kept",
                            o.tool, path, why));
  }
  table = std::move(changed);
}

void tool_into_spindle(CommandContext& ctx, int number, const SourceLoc& loc) {
  GcodeOffsets& o = ctx.state().gcode;
  o.tool = number;  // the drawing state carries it to a preview with the next move
  const std::string& path = ctx.settings().tool_table_path;
  if (path.empty() || number == 0) return;  // no file: the cutter stays VC's
  ToolTable& table = o.tools;
  refresh_tool_table(table, path, loc);
  const ToolEntry* e = table.find(number);
  if (!e) {
    ctx.warn(loc, fmt::format("tool {} is not in the tool table {}, so the cutter stays VC's "
                              "({}); add a line T{} P{} D<diameter> for it",
                              number, path, format_number(ctx.settings().cutter.diameter), number,
                              number));
    return;
  }
  if (e->diameter <= 0 || e->diameter == ctx.settings().cutter.diameter) return;
  // As M6 does: the cutter (VC) is the tool in the spindle; the motion stream hears of it at
  // rest, so a preview draws the cuts after it with this cutter.
  ctx.change_values(ValueScope::Permanent).cutter.diameter = e->diameter;
  ctx.values_reach_motion(loc);
}

}  // namespace gantry
