// The rack's automatic tool change and the tool-length sensor (docs/hardware.md, "Tool
// changer"): every place is the profile's, in table base coordinates, reached through the
// running file's frame so that the soft limits and FP's transform apply as to any move.
#include "gantry/interp/tool_changer.hpp"

#include <fmt/format.h>  // messages

#include <array>
#include <vector>

#include "gantry/interp/command_context.hpp"
#include "gantry/interp/tool_table.hpp"
#include "gantry/interp/value.hpp"  // format_number

namespace gantry {

namespace {

constexpr int kX = 0, kY = 1, kZ = 2;

// The running file's coordinates of a table base point.
Vec6 file_point(CommandContext& ctx, const Vec6& table_base) {
  return ctx.transform().to_file(table_base - ctx.state().zero);
}

Vec6 table_base_here(CommandContext& ctx) {
  return ctx.state().position + ctx.state().zero;
}

// A straight move of X, Y and Z to the table base point given, the other axes kept.
void go(CommandContext& ctx, double x, double y, double z, SpeedClass cls, const SourceLoc& loc) {
  Vec6 p = table_base_here(ctx);
  p[kX] = x;
  p[kY] = y;
  p[kZ] = z;
  ctx.line_to(file_point(ctx, p), cls, loc);
}

void go_z(CommandContext& ctx, double z, SpeedClass cls, const SourceLoc& loc) {
  const Vec6 p = table_base_here(ctx);
  go(ctx, p[kX], p[kY], z, cls, loc);
}

const std::array<double, 2>& slot(const ToolChangerSettings& tc, int tool) {
  return tc.slots[static_cast<size_t>(tool - 1)];
}

// The drawbar opens or closes, then the machine waits for it.
void drawbar(CommandContext& ctx, bool open, const SourceLoc& loc) {
  const ToolChangerSettings& tc = ctx.settings().toolchanger;
  ctx.set_output(tc.release_output, open, loc);
  ctx.dwell(tc.release_s, loc);
}

// The tool table as it is on disk now (an editor may have changed it since it was read).
ToolTable& current_table(CommandContext& ctx, const SourceLoc& loc) {
  const std::string& path = ctx.settings().tool_table_path;
  ToolTable& table = ctx.state().gcode.tools;
  if (path.empty()) {
    if (!table.implicit()) table = ToolTable{};
    return table;
  }
  refresh_tool_table(table, path, loc);
  return table;
}

// Before anything moves: a measured length needs the tool's line in the tool table file (a
// profile without one keeps lengths in memory).
void require_table_line(CommandContext& ctx, int tool, const SourceLoc& loc) {
  if (ctx.settings().tool_table_path.empty()) return;
  const ToolTable& table = current_table(ctx, loc);
  if (!table.find(tool))
    fail(loc, fmt::format("tool {} is not in the tool table {}, so the length the sensor "
                          "measures could not be written; add a line T{} P{} for it; nothing "
                          "moved",
                          tool, table.path(), tool, tool));
}

// Tool `tool`'s length becomes `length` in the tool table, written back to its file at once
// (atomically, as G10 L1 writes it); a check or a preview changes it in memory only.
void length_to_tool_table(CommandContext& ctx, int tool, double length, const SourceLoc& loc) {
  ToolTable& table = current_table(ctx, loc);
  ToolTable changed = table;  // a failed write keeps the file and this table as they were
  ToolEntry* e = changed.change(tool);
  if (!e)  // check_tool_change refused it before anything moved; the file changed since
    fail(loc, fmt::format("tool {} is not in the tool table {}, so its measured length ({}) "
                          "cannot be written there; add a line T{} P{} for it",
                          tool, table.path(), format_number(length), tool, tool));
  e->offset[kZ] = length;
  if (!changed.implicit() && ctx.writes_to_disk()) {
    if (std::string why; !save_tool_table(changed, &why))
      fail(loc, fmt::format("could not write tool {}'s measured length ({}) to the tool table "
                            "{} ({}); the previous file is kept",
                            tool, format_number(length), changed.path(), why));
  }
  table = std::move(changed);
}

}  // namespace

void check_tool_change(CommandContext& ctx, int from, int to, const SourceLoc& loc) {
  const ToolChangerSettings& tc = ctx.settings().toolchanger;
  const int slots = static_cast<int>(tc.slots.size());
  if (tc.rack()) {
    if (to > slots)
      fail(loc, fmt::format("tool {} has no slot in the tool rack (toolchanger.slots lists {} "
                            "slot{}: tools 1 to {}); nothing moved",
                            to, slots, slots == 1 ? "" : "s", slots));
    if (from > slots)
      fail(loc, fmt::format("tool {}, in the spindle, has no slot in the tool rack to go back to "
                            "(toolchanger.slots lists tools 1 to {}); take it out by hand and "
                            "tell Gantry the spindle is empty (M61 Q0) before changing; nothing "
                            "moved",
                            from, slots));
  }
  if (tc.sensor_input != 0 && to != 0) require_table_line(ctx, to, loc);
  // Every place the sequence goes to within the soft limits (the profile's check holds them
  // within the table, but a VL or a zero may narrow what a file reaches).
  const Vec6 here = table_base_here(ctx);
  std::vector<Vec6> places;
  auto place = [&](double x, double y, double z) {
    Vec6 p = here;
    p[kX] = x;
    p[kY] = y;
    p[kZ] = z;
    places.push_back(p);
  };
  place(here[kX], here[kY], tc.clear_z);
  if (tc.rack())
    for (int t : {from, to})
      if (t > 0) {
        place(slot(tc, t)[0], slot(tc, t)[1], tc.clear_z);
        place(slot(tc, t)[0], slot(tc, t)[1], tc.slot_z);
      }
  if (tc.sensor_input != 0 && to != 0) {
    place(tc.sensor_x, tc.sensor_y, tc.clear_z);
    place(tc.sensor_x, tc.sensor_y, tc.sensor_min_z);
  }
  for (const Vec6& p : places) ctx.check_reach(file_point(ctx, p), loc);
}

void check_tool_measure(CommandContext& ctx, int tool, const char* code, const SourceLoc& loc,
                        bool writes_table) {
  const ToolChangerSettings& tc = ctx.settings().toolchanger;
  if (tc.sensor_input == 0)
    fail(loc, fmt::format("{} measures the tool in the spindle on the tool-length sensor, and "
                          "this machine's profile has none (toolchanger.sensor_input); give "
                          "its length with G10 L1 (or M37 Z in the WinCNC dialect)",
                          code));
  if (tool == 0)
    fail(loc, fmt::format("{}: the spindle holds no tool (tool 0); load one with M6 T, or say "
                          "which it holds with M61 Q; nothing moved",
                          code));
  if (writes_table) require_table_line(ctx, tool, loc);
  const Vec6 here = table_base_here(ctx);
  for (const auto& [x, y, z] : {std::array{here[kX], here[kY], tc.clear_z},
                                std::array{tc.sensor_x, tc.sensor_y, tc.clear_z},
                                std::array{tc.sensor_x, tc.sensor_y, tc.sensor_min_z}}) {
    Vec6 p = here;
    p[kX] = x;
    p[kY] = y;
    p[kZ] = z;
    ctx.check_reach(file_point(ctx, p), loc);
  }
}

std::optional<double> measure_tool_in_spindle(CommandContext& ctx, const char* code,
                                              const SourceLoc& loc) {
  const int tool = ctx.state().gcode.tool;
  check_tool_measure(ctx, tool, code, loc, true);
  ctx.come_to_rest(loc);
  const Vec6 start = table_base_here(ctx);
  const std::optional<double> length = measure_tool(ctx, tool, loc);
  return_from_change(ctx, start[kX], start[kY], loc);
  return length;
}

void rack_tool_change(CommandContext& ctx, int from, int to, const SourceLoc& loc) {
  const ToolChangerSettings& tc = ctx.settings().toolchanger;
  GcodeOffsets& o = ctx.state().gcode;
  ctx.spindle(0, loc);  // stopped, and spun down, before the tool is let go
  go_z(ctx, tc.clear_z, SpeedClass::Jog, loc);
  if (from > 0) {  // back to its slot: down into it, let go, up without it
    go(ctx, slot(tc, from)[0], slot(tc, from)[1], tc.clear_z, SpeedClass::Jog, loc);
    go_z(ctx, tc.slot_z, SpeedClass::Move, loc);
    drawbar(ctx, true, loc);
    o.tool = 0;
    go_z(ctx, tc.clear_z, SpeedClass::Move, loc);
    drawbar(ctx, false, loc);
  }
  if (to > 0) {  // the new one: the drawbar open, down over it, closed, up with it
    go(ctx, slot(tc, to)[0], slot(tc, to)[1], tc.clear_z, SpeedClass::Jog, loc);
    drawbar(ctx, true, loc);
    go_z(ctx, tc.slot_z, SpeedClass::Move, loc);
    drawbar(ctx, false, loc);
    o.tool = to;
    go_z(ctx, tc.clear_z, SpeedClass::Move, loc);
  }
  o.tool = to;
}

std::optional<double> sensor_trip_z(CommandContext& ctx, int tool, const SourceLoc& loc) {
  const ToolChangerSettings& tc = ctx.settings().toolchanger;
  go_z(ctx, tc.clear_z, SpeedClass::Jog, loc);
  go(ctx, tc.sensor_x, tc.sensor_y, tc.clear_z, SpeedClass::Jog, loc);
  go_z(ctx, tc.sensor_start_z, SpeedClass::Jog, loc);
  const bool live = ctx.sync().has_value();  // a check or a preview measures nothing
  Vec6 bottom = table_base_here(ctx);
  bottom[kZ] = tc.sensor_min_z;
  const bool hit = ctx.probe(file_point(ctx, bottom), tc.sensor_speed, tc.sensor_input, loc);
  if (!live) {
    go_z(ctx, tc.clear_z, SpeedClass::Jog, loc);
    return std::nullopt;
  }
  if (!hit)
    fail(loc, fmt::format("tool {} did not close the tool-length sensor (input switch {}) "
                          "between Z {} and Z {} (toolchanger.sensor_start_z, sensor_min_z): "
                          "is the tool in the spindle, and the sensor wired? The job stops "
                          "with the tool at the sensor's lowest point; its length was not "
                          "changed",
                          tool, tc.sensor_input, format_number(tc.sensor_start_z),
                          format_number(tc.sensor_min_z)));
  return table_base_here(ctx)[kZ];
}

std::optional<double> measure_tool(CommandContext& ctx, int tool, const SourceLoc& loc) {
  const ToolChangerSettings& tc = ctx.settings().toolchanger;
  if (tc.sensor_input == 0 || tool == 0) return std::nullopt;
  const std::optional<double> trip = sensor_trip_z(ctx, tool, loc);
  if (!trip) return std::nullopt;
  const double length = *trip - tc.sensor_zero_z;
  length_to_tool_table(ctx, tool, length, loc);
  go_z(ctx, tc.clear_z, SpeedClass::Jog, loc);
  return length;
}

std::optional<double> calibrate_sensor(CommandContext& ctx, double length, const char* code,
                                       const SourceLoc& loc) {
  const int tool = ctx.state().gcode.tool;
  check_tool_measure(ctx, tool, code, loc, false);
  ctx.come_to_rest(loc);
  const Vec6 start = table_base_here(ctx);
  const std::optional<double> trip = sensor_trip_z(ctx, tool, loc);
  go_z(ctx, ctx.settings().toolchanger.clear_z, SpeedClass::Jog, loc);
  return_from_change(ctx, start[kX], start[kY], loc);
  if (!trip) return std::nullopt;
  return *trip - length;
}

void return_from_change(CommandContext& ctx, double x, double y, const SourceLoc& loc) {
  const ToolChangerSettings& tc = ctx.settings().toolchanger;
  go_z(ctx, tc.clear_z, SpeedClass::Jog, loc);
  go(ctx, x, y, tc.clear_z, SpeedClass::Jog, loc);
}

void opensbp_rack_change(CommandContext& ctx, int to, const SourceLoc& loc) {
  ModalState& st = ctx.state();
  const int from = st.gcode.tool;
  if (to == from) return;
  check_tool_change(ctx, from, to, loc);
  ctx.come_to_rest(loc);
  const Vec6 start = table_base_here(ctx);
  const ToolEntry* old_entry = from == 0 ? nullptr : current_table(ctx, loc).find(from);
  const double old_length = old_entry ? old_entry->length() : 0;
  rack_tool_change(ctx, from, to, loc);
  if (const std::optional<double> length = measure_tool(ctx, to, loc); length && from != 0) {
    // The tip is `length` below the spindle's Z: working Z keeps measuring the tip's height.
    const double shift = *length - old_length;
    st.zero[kZ] += shift;
    st.position[kZ] -= shift;  // the tool stays where it is on the table
  }
  return_from_change(ctx, start[kX], start[kY], loc);
}

}  // namespace gantry
