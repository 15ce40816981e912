// G-code's canned cycles (docs/gcode.md, "Canned cycles").
#include "gantry/interp/gcode_executor.hpp"

#include <fmt/format.h>  // messages

#include <cmath>  // round

#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;

// G73, G81, G82, G83 in the XY plane (docs/gcode.md, "Canned cycles").
void GcodeExecutor::canned_cycle(const Words& w, const SourceLoc& loc) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  const int code = modes_.motion;
  const double lin = length_scale();
  if (w.has('Z')) modes_.cycle_z = w.get('Z') * lin;
  if (w.has('R')) modes_.cycle_r = w.get('R') * lin;
  if (w.has('Q')) {
    if (!(w.get('Q') > 0)) fail(w.at('Q', loc), "Q, the peck depth, must be above 0");
    modes_.cycle_q = w.get('Q') * lin;
  }
  if (w.has('P')) modes_.cycle_p = wincnc ? w.get('P') / 1000 : w.get('P');
  int repeats = 1;
  if (w.has('L')) {
    const double l = w.get('L');
    if (l != std::round(l) || l < 0) fail(w.at('L', loc), "L, the repeats, is a whole number");
    repeats = static_cast<int>(l);
  }
  const double feed = feed_for(w, 1, loc);
  const double retract_gap = (wincnc ? kWinCncPeckClearanceIn : 0.010) *
                             units_factor(Units::Inches, ctx_.settings().units);
  Vec6 p = program_position();
  const double r_level = modes_.incremental ? p[2] + *modes_.cycle_r : *modes_.cycle_r;
  const double bottom = modes_.incremental ? r_level + *modes_.cycle_z : *modes_.cycle_z;
  if (bottom > r_level)
    fail(loc, "the hole's bottom Z is above the retract plane R; check Z and R (and G90/G91)");
  // WinCNC's cycles always end at R (manual, G73-G83: "moves back to R at Rapid velocity").
  const double clear_z =
      modes_.retract_to_r || wincnc ? r_level : std::max(modes_.cycle_start_z, r_level);
  auto z_move = [&](double z, SpeedClass cls) {
    Vec6 t = program_position();
    t[2] = z;
    line(t, cls, feed, loc);
  };
  if (p[2] < r_level) z_move(r_level, SpeedClass::Jog);
  const Vec6 k = axis_scale();
  for (int hole = 0; hole < repeats; ++hole) {
    Vec6 at = program_position();
    for (int a : {0, 1})
      if (w.has(kAxes[static_cast<size_t>(a)]))
        at[a] = (modes_.incremental ? at[a] : 0) + w.get(kAxes[static_cast<size_t>(a)]) * k[a];
    line(at, SpeedClass::Jog, 0, loc);
    z_move(r_level, SpeedClass::Jog);
    if (code == 810 || code == 820) {
      z_move(bottom, SpeedClass::Move);
      if (code == 820 && modes_.cycle_p > 0) ctx_.dwell(modes_.cycle_p, loc);
    } else {
      double depth = r_level;
      while (depth > bottom) {
        const double next = std::max(depth - *modes_.cycle_q, bottom);
        if (code == 830 && depth < r_level) z_move(depth + retract_gap, SpeedClass::Jog);
        z_move(next, SpeedClass::Move);
        depth = next;
        if (depth > bottom) z_move(code == 830 ? r_level : depth + retract_gap, SpeedClass::Jog);
      }
    }
    z_move(clear_z, SpeedClass::Jog);
  }
}

}  // namespace gantry
