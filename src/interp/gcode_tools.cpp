// G-code's tools (docs/gcode.md, "Tool table"): T, M6, M61, G43 H, G10 L1/L10/L11 and
// #5400-#5413, over the profile's tool table file or, with none configured, the implicit
// table where every tool has length 0 (SB3's way: Z is zeroed after each tool change).
#include <fmt/format.h>  // messages

#include <cmath>  // round

#include "gantry/core/text_file.hpp"  // read_text_file
#include "gantry/interp/gcode_executor.hpp"
#include "gantry/interp/tool_changer.hpp"  // the rack and the sensor
#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;

namespace {

// A whole number of 0 or more (a tool number), or a located error.
int tool_number(const char* code, char letter, double v, const SourceLoc& at) {
  if (v != std::round(v) || v < 0 || v > 1e9)
    fail(at, fmt::format("{}: {}{} is not a tool number (a whole number, 0 or more)", code, letter,
                         format_number(v)));
  return static_cast<int>(v);
}

}  // namespace

// The file is the table: once per G-code file it is read again when its text differs from
// what was last read or written here (an editor changed it between jobs); a loop's T words
// do not read it each time. Changes a check or a preview makes stay in this memory only,
// over the unchanged file.
ToolTable& GcodeExecutor::tool_table(const SourceLoc& loc) {
  ToolTable& t = ctx_.state().gcode.tools;
  const std::string& path = ctx_.settings().tool_table_path;
  if (path.empty()) {
    if (!t.implicit()) t = ToolTable{};  // the profile no longer names a file
    return t;
  }
  if (table_read_ && t.path() == path) return t;
  const std::optional<std::string> text = read_text_file(path);
  table_read_ = true;
  if (t.path() == path && text && *text == t.source_text()) return t;
  try {
    t = load_tool_table(path, loc);
  } catch (const GantryError& e) {
    Diagnostic d = e.diagnostic();
    if (d.loc.file && *d.loc.file == path && loc.file) d.via.insert(d.via.begin(), loc);
    throw GantryError(std::move(d));
  }
  return t;
}

const ToolEntry& GcodeExecutor::tool_entry(int number, const SourceLoc& at) {
  static const ToolEntry kNoTool;  // T0: the empty spindle
  ToolTable& table = tool_table(at);
  if (number == 0) return kNoTool;
  const ToolEntry* e = table.find(number);
  if (!e)  // LinuxCNC refuses it too ("Requested tool N not found in the tool table")
    fail(at, fmt::format("tool {} is not in the tool table {}; add a line for it, as T{} P{} "
                         "Z<length> D<diameter>, or use a tool it lists",
                         number, table.path(), number, number));
  return *e;
}

void GcodeExecutor::tool_change(const Words& w, const SourceLoc& loc) {
  GcodeOffsets& o = ctx_.state().gcode;
  if (w.has('T')) {
    const int t = tool_number("T", 'T', w.get('T'), w.at('T', loc));
    tool_entry(t, w.at('T', loc));
    selected_tool_ = t;
  }
  const int code = w.m[6];
  if (code != 60 && code != 610) return;
  SourceLoc at = loc;
  at.column = w.m_col[6];
  int number = selected_tool_;
  if (code == 610) {
    if (!w.has('Q')) fail(at, "M61 needs Q, the number of the tool in the spindle: M61 Q1");
    number = tool_number("M61", 'Q', w.get('Q'), w.at('Q', loc));
  }
  // A copy: the sensor's measure may write the table, which moves its entries.
  const ToolEntry e = tool_entry(number, code == 610 ? w.at('Q', loc) : at);
  if (code == 60 && number != o.tool) {
    // The profile's tool changer (docs/hardware.md, "Tool changer"): the rack's sequence or
    // the operator, then the sensor's measure, and back over where the change began.
    const ToolChangerSettings& tc = ctx_.settings().toolchanger;
    check_tool_change(ctx_, o.tool, number, at);  // a change refused moves nothing
    ctx_.come_to_rest(loc);
    const Vec6 start = ctx_.state().position + ctx_.state().zero;
    if (tc.rack()) {
      rack_tool_change(ctx_, o.tool, number, at);
    } else if (!io_.confirm(fmt::format("Change to tool {} (M6), then continue", number), loc)) {
      throw OperatorStop({loc, Severity::Error, "stopped by the operator at M6"});
    }
    o.tool = number;
    measure_tool(ctx_, number, at);
    if (tc.rack() || (tc.sensor_input != 0 && number != 0))
      return_from_change(ctx_, start[0], start[1], at);
  }
  o.tool = number;
  const ToolTable& table = o.tools;
  if (table.implicit()) {
    if (number != 0 && !tool_note_given_)
      ctx_.warn(at, fmt::format("no tool table is configured (tool_table in the profile, or "
                                "--tool-table): tool {} has length 0 unless G10 L1 gives one, "
                                "as when Z is zeroed after each tool change",
                                number));
    tool_note_given_ = tool_note_given_ || number != 0;
  } else if (number != 0 && e.diameter > 0 && e.diameter != ctx_.settings().cutter.diameter) {
    // SB3's cutter (VC) is the tool in the spindle, for the cut commands; the motion stream
    // hears of it (at rest) so that a preview draws the cuts after it with this cutter.
    ctx_.change_values(ValueScope::Permanent).cutter.diameter = e.diameter;
    ctx_.values_reach_motion(loc);
  }
}

// G43: the length of tool H (H0 or none: the tool in the spindle, as in LinuxCNC).
void GcodeExecutor::tool_length(const Words& w, const SourceLoc& loc) {
  GcodeOffsets& o = ctx_.state().gcode;
  SourceLoc at = loc;
  at.column = w.g_col[8];
  int number = o.tool;
  if (w.has('H')) {
    at = w.at('H', loc);
    const int h = tool_number("G43", 'H', w.get('H'), at);
    if (h != 0) number = h;
  }
  const ToolEntry& e = tool_entry(number, at);
  for (size_t a = 0; a < e.offset.size(); ++a)
    if (a != 2 && e.offset[a] != 0)
      fail(at, fmt::format("tool {} has a {} offset ({}) in the tool table {}; Gantry applies "
                           "tool lengths (Z) only: make it {}0 on the tool's line",
                           number, kToolOffsetLetters[a], format_number(e.offset[a]),
                           o.tools.path(), kToolOffsetLetters[a]));
  o.tool_length = e.length();
  if (o.tools.implicit() && number != 0 && !tool_note_given_) {
    ctx_.warn(at, fmt::format("no tool table is configured (tool_table in the profile, or "
                              "--tool-table): tool {}'s length is {} (0 unless G10 L1 gave "
                              "one), as when Z is zeroed after each tool change",
                              number, format_number(e.length())));
    tool_note_given_ = true;
  }
}

// G37: the tool in the spindle measured on the profile's tool-length sensor, with no change
// (docs/gcode.md, "Tool table"), its length written to the tool table as M6's measure writes
// it. G43 (G43 H) applies it from the next block on, as after G10 L1; in the WinCNC dialect
// G37 turns the length on at once, as M37 does (its G43 takes the last measure).
void GcodeExecutor::tool_measure(const Words& w, const SourceLoc& loc) {
  SourceLoc at = loc;
  at.column = w.g_col[0];
  if (comp_active())
    fail(at, "G37 with cutter compensation on: turn it off (G40) before measuring the tool");
  GcodeOffsets& o = ctx_.state().gcode;
  if (o.tool != 0) tool_entry(o.tool, at);  // the table read (and its file refreshed) first
  const std::optional<double> length = measure_tool_in_spindle(ctx_, "G37", at);
  if (length && ctx_.settings().gcode_dialect == GcodeDialect::WinCNC) {
    o.measured_length = *length;
    o.tool_length = *length;
  }
}

// G10 L1 sets tool P's offsets to the values given; L10 so that, with its length applied,
// the current position reads them in the coordinate system in use; L11 the same in G59.3
// without the G92 offsets. R is the radius (the table keeps the diameter). The file is
// written back at once, atomically; a check or a preview changes the table in memory only.
void GcodeExecutor::tool_data(const Words& w, const SourceLoc& loc) {
  ModalState& st = ctx_.state();
  GcodeOffsets& o = st.gcode;
  const int l = static_cast<int>(w.get('L'));
  const std::string code = fmt::format("G10 L{}", l);
  const int p = tool_number(code.c_str(), 'P', w.get('P'), w.at('P', loc));
  bool any = w.has('R');
  for (char c : kAxes) any = any || w.has(c);
  if (!any)
    fail(loc, fmt::format("{} without offsets has no effect: give Z (the tool's length), R (its "
                          "radius) or another axis",
                          code));
  ToolTable& table = tool_table(loc);
  ToolTable changed = table;  // a failed write keeps the file and this table as they were
  ToolEntry* e = p == 0 ? nullptr : changed.change(p);
  if (!e)
    fail(w.at('P', loc),
         p == 0 ? fmt::format("{} P0: tool 0 is the empty spindle; give the tool's number", code)
                : fmt::format("tool {} is not in the tool table {}; {} changes a tool's line "
                              "and does not add one: add T{} P{} to the file first",
                              p, table.path(), code, p, p));
  const Vec6 k = axis_scale();
  const Vec6 here = ctx_.position();  // file coordinates: program + G92 + the length
  const Transform& tr = ctx_.transform();
  const Vec6& g59_3 = o.system == 8 ? st.zero : o.origin[8];
  for (int a = 0; a < kAxisCount; ++a) {
    const char letter = kAxes[static_cast<size_t>(a)];
    if (!w.has(letter)) continue;
    const double v = w.get(letter) * k[a];
    double& offset = e->offset[static_cast<size_t>(a)];
    if (l == 1)
      offset = v;
    else if (l == 10)
      offset = here[a] - o.axis_offset[a] - v;
    else  // L11: where the tool is in G59.3, neither G92 nor a length applied
      offset = here[a] + (st.zero[a] - g59_3[a]) / tr.scale[a] - v;
  }
  if (w.has('R')) e->diameter = 2 * w.get('R') * length_scale();
  if (!changed.implicit() && ctx_.writes_to_disk()) {
    if (std::string why; !save_tool_table(changed, &why))
      fail(loc, fmt::format("could not write the tool table {} ({}); the previous file and "
                            "tool {}'s offsets are kept",
                            changed.path(), why, p));
  }
  table = std::move(changed);
}

// LinuxCNC's #5400 (the tool in the spindle) and #5401-#5413 (its table line: offsets X..W,
// diameter, front and back angle, orientation), in the table's (machine) units.
std::optional<double> GcodeExecutor::tool_parameter(int n) const {
  const GcodeOffsets& o = ctx_.state().gcode;
  if (n == 5400) return o.tool;
  if (n < 5401 || n > 5413) return std::nullopt;
  const ToolEntry* e = o.tool == 0 ? nullptr : o.tools.find(o.tool);
  if (!e) return 0;
  if (n <= 5409) return e->offset[static_cast<size_t>(n - 5401)];
  if (n == 5410) return e->diameter;
  if (n == 5411) return e->front_angle;
  if (n == 5412) return e->back_angle;
  return e->orientation;
}

}  // namespace gantry
