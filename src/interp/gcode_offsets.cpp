// G-code's coordinate data: work coordinate systems, G10, G28/G30 and G92 (docs/gcode.md,
// "Offsets").
#include "gantry/interp/gcode_executor.hpp"

#include <fmt/format.h>  // messages

#include <cmath>  // round

#include "gantry/commands/command_table.hpp"  // home_on_switches (WinCNC's G28)

#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;

// The tool stays where it is on the table; its working location follows the new zero.
void GcodeExecutor::set_zero(const Vec6& zero) {
  ModalState& st = ctx_.state();
  st.position += st.zero - zero;
  st.zero = zero;
}

void GcodeExecutor::select_system(int n) {
  GcodeOffsets& o = ctx_.state().gcode;
  if (n == o.system) return;
  o.origin[static_cast<size_t>(o.system)] = ctx_.state().zero;
  set_zero(o.origin[static_cast<size_t>(n)]);
  o.system = n;
}

// G10, G28, G30, G92: coordinate data and stored positions.
void GcodeExecutor::non_modal(const Words& w, int code, const SourceLoc& loc) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  ModalState& st = ctx_.state();
  GcodeOffsets& o = st.gcode;
  const Vec6 k = axis_scale();
  switch (code) {
    case 100:
      return coordinate_data(w, loc);
    case 280:
    case 300: {
      if (wincnc && code == 280) return wincnc_home(w, loc);  // WinCNC: G28 homes
      const Vec6 here = program_position();
      if (w.any_axis()) line(axis_target(w, here, modes_.incremental), SpeedClass::Jog, 0, loc);
      // The stored position (table base) in program coordinates, for the axes given or all.
      const Vec6& stored = o.stored[code == 280 ? 0 : 1];
      Vec6 working = st.position;
      for (int a = 0; a < kAxisCount; ++a)
        if (!w.any_axis() || w.has(kAxes[static_cast<size_t>(a)]))
          working[a] = stored[a] - st.zero[a];
      Vec6 file = ctx_.transform().to_file(working) - o.axis_offset;
      file[2] -= o.tool_length;
      line(file, SpeedClass::Jog, 0, loc);
      return;
    }
    case 281:
    case 301:
      o.stored[code == 281 ? 0 : 1] = st.position + st.zero;
      return;
    case 920: {
      if (wincnc && !w.any_axis()) {  // WinCNC: G92 alone restores machine coordinates
        o.axis_offset.setZero();
        return;
      }
      if (!w.any_axis()) fail(loc, "G92 needs the axes to set, as G92 X0 Y0");
      const Vec6 file = ctx_.position();
      for (int a = 0; a < kAxisCount; ++a)
        if (w.has(kAxes[static_cast<size_t>(a)]))
          o.axis_offset[a] =
              file[a] - (a == 2 ? o.tool_length : 0) - w.get(kAxes[static_cast<size_t>(a)]) * k[a];
      if (!wincnc) o.axis_offset_saved = o.axis_offset;  // WinCNC's store is G92.3's own
      return;
    }
    case 921:
      if (wincnc) {  // WinCNC: local zero is machine zero shifted by the values; no motion
        if (!w.any_axis())
          fail(loc, "G92.1 needs the axes to shift, as G92.1 X20 Y20 Z1 (G92 alone clears them)");
        for (int a = 0; a < kAxisCount; ++a)
          if (w.has(kAxes[static_cast<size_t>(a)]))
            o.axis_offset[a] = w.get(kAxes[static_cast<size_t>(a)]) * k[a];
        return;
      }
      o.axis_offset.setZero();
      o.axis_offset_saved.setZero();
      return;
    case 922:
      if (wincnc) {  // WinCNC: the shift adds to local zero (G92.2 Z-.01 cuts .01 deeper)
        if (!w.any_axis()) fail(loc, "G92.2 needs the axes to shift, as G92.2 Z-.01");
        for (int a = 0; a < kAxisCount; ++a)
          if (w.has(kAxes[static_cast<size_t>(a)]))
            o.axis_offset[a] += w.get(kAxes[static_cast<size_t>(a)]) * k[a];
        return;
      }
      o.axis_offset.setZero();
      return;
    case 370:
      return tool_measure(w, loc);  // gcode_tools.cpp
    case 923:
      if (wincnc && !o.axis_offset.isZero(0)) {  // WinCNC: offsets set: store and clear them
        o.axis_offset_saved = o.axis_offset;
        o.axis_offset.setZero();
        return;
      }
      o.axis_offset = o.axis_offset_saved;  // WinCNC: none set: the stored ones come back
      return;
    default:
      return;
  }
}

void GcodeExecutor::coordinate_data(const Words& w, const SourceLoc& loc) {
  ModalState& st = ctx_.state();
  GcodeOffsets& o = st.gcode;
  const Vec6 k = axis_scale();
  const double l = w.get('L'), p = w.get('P');
  if (l == 1 || l == 10 || l == 11) return tool_data(w, loc);  // gcode_tools.cpp
  if (l != 2 && l != 20)
    fail(w.at('L', loc), fmt::format("G10 L{} is not supported; use L1, L10 or L11 (tool table), "
                                     "L2 or L20 (coordinate systems)",
                                     l));
  if (p != std::round(p) || p < 0 || p > 9)
    fail(w.at('P', loc), fmt::format("G10: P{} is not a coordinate system: 1 (G54) to 9 (G59.3), "
                                     "or 0 for the one in use",
                                     p));
  if (w.has('R')) fail(w.at('R', loc), "G10: rotated coordinate systems (R) are not supported");
  const int n = p == 0 ? o.system : static_cast<int>(p) - 1;
  Vec6 origin = n == o.system ? st.zero : o.origin[static_cast<size_t>(n)];
  const Transform& tr = ctx_.transform();
  for (int a = 0; a < kAxisCount; ++a) {
    if (!w.has(kAxes[static_cast<size_t>(a)])) continue;
    const double v = w.get(kAxes[static_cast<size_t>(a)]) * k[a];
    if (l == 2) {
      origin[a] = v;
    } else {  // L20: the tool's location reads v in system n
      const double file = v + o.axis_offset[a] + (a == 2 ? o.tool_length : 0);
      origin[a] = st.position[a] + st.zero[a] - (tr.origin[a] + tr.scale[a] * file);
    }
  }
  if (n == o.system)
    set_zero(origin);
  else
    o.origin[static_cast<size_t>(n)] = origin;
}
}  // namespace gantry
