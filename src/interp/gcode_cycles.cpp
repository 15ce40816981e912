// G-code's canned cycles G73, G81-G83 and G85-G89 in the XY, ZX and YZ planes, with
// LinuxCNC's semantics (docs/gcode.md, "Canned cycles"); G84 is refused by name.
//
// A cycle drills along the axis normal to the selected plane (the cycle axis: Z in G17, Y in
// G18, X in G19); its word is the hole's bottom and R is the retract level on that axis; the
// plane's two axis words place the hole. In LinuxCNC's order: if the level where the series
// began is below R, the tool first rises to R; per hole it rapids across at its level (the
// first hole) or the clearance level (the next ones), down to R, runs the cycle's body and
// ends at the clearance level: R with G99, else the series' first level if above R (G98).
// In G91 the plane words and R are increments (R from the series' first level) and the
// bottom is measured from R; L repeats the increment.
#include "gantry/interp/gcode_executor.hpp"

#include <fmt/format.h>  // messages

#include <cmath>  // round

#include "gantry/canon/arc_geometry.hpp"  // plane_axes

#include "gcode_cutter_comp.hpp"
#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;
namespace {

std::string too_many_moves(double moves) {
  return fmt::format(
      "this cycle would make {} moves; a block may make at most {}: give fewer "
      "repeats (L) or deeper pecks (Q)",
      format_number(moves), format_number(kMaxBlockMoves));
}

// How far G73 backs off after each peck and how far above the last depth G83 comes back
// down at rapid, in inches (LinuxCNC's defaults). The WinCNC dialect has its own values.
constexpr double kG73Backoff = 0.010;
constexpr double kG83Clearance = 0.010;
// Relative to the hole's depth: far below any real peck, far above unit rounding.
constexpr double kPeckTolerance = 1e-9;

ArcPlane plane_of(int g2_code, ArcPlane current) {
  return g2_code == 180   ? ArcPlane::ZX
         : g2_code == 190 ? ArcPlane::YZ
         : g2_code == 170 ? ArcPlane::XY
                          : current;
}

std::string plane_label(ArcPlane p) {
  return p == ArcPlane::XY ? "XY (G17)" : p == ArcPlane::ZX ? "ZX (G18)" : "YZ (G19)";
}

}  // namespace

// The cycle's words, before anything in the block runs: a located error for what LinuxCNC
// refuses. A cycle code that was not the motion mode needs its words again.
void GcodeExecutor::check_cycle_words(const Words& w, int motion, const SourceLoc& loc) const {
  SourceLoc at_code = loc;
  if (w.g[1] >= 0) at_code.column = w.g_col[1];
  const std::string name = code_name('G', motion);
  if (motion == 840)
    fail(at_code,
         "G84 (tapping) is not supported: it needs the spindle synchronised with Z by a spindle "
         "encoder, which Gantry's machines do not have; tap by hand or on a machine with rigid "
         "tapping");
  for (char c : {'A', 'B', 'C'})
    if (w.has(c))
      fail(w.at(c, loc), fmt::format("{} cannot go with a canned cycle ({}): a cycle moves X, Y "
                                     "and Z only; turn {} in a block of its own before it",
                                     c, name, c));
  if (w.g[5] == 930 || (w.g[5] < 0 && modes_.inverse_time))
    fail(at_code, fmt::format("{} cannot use inverse time feed (G93): give G94 (units per "
                              "minute) and F first",
                              name));
  if (w.g[7] == 410 || w.g[7] == 420 || w.g[7] == 411 || w.g[7] == 421 ||
      (w.g[7] < 0 && comp_ && comp_->side != 0))
    fail(at_code,
         fmt::format("{} cannot run with cutter radius compensation on: give G40 first", name));
  const ArcPlane plane = plane_of(w.g[2], modes_.plane);
  const char axis = kAxes[static_cast<size_t>(plane_axes(plane)[2])];
  const bool starting = motion != modes_.motion;
  if (starting && !w.has(axis))
    fail(loc, fmt::format("{} needs {}, the bottom of the hole (the cycle drills along {} in "
                          "the {} plane)",
                          name, axis, axis, plane_label(plane)));
  if (starting && !w.has('R'))
    fail(loc, fmt::format("{} needs R, the retract level along {}", name, axis));
  if ((motion == 730 || motion == 830) && starting && !w.has('Q'))
    fail(loc, fmt::format("{} needs Q, the peck depth", name));
  const bool dwells = motion == 820 || motion == 860 || motion == 880 || motion == 890;
  if (dwells && starting && !w.has('P'))
    fail(loc, fmt::format("{} needs P, the dwell at the bottom in seconds (P0 for none)", name));
  if (w.has('P') && w.get('P') < 0) fail(w.at('P', loc), "P, the dwell, cannot be negative");
  if (motion == 870 && starting)
    for (char c : {'I', 'J', 'K'})
      if (!w.has(c))
        fail(loc, fmt::format("G87 needs I, J and K: the offset across the plane where the tool "
                              "enters the hole, and the top of the back bore along {}",
                              axis));
  if (w.has('L')) {
    const double l = w.get('L');
    if (l != std::round(l) || l < 1)
      fail(w.at('L', loc), fmt::format("L{} is not a number of repeats: give a whole number, 1 "
                                       "or more",
                                       format_number(l)));
  }
  if (motion == 860 || motion == 870 || motion == 880) {
    const bool spindle =
        w.m[7] >= 0 ? w.m[7] == 30 : ((ctx_.state().outputs >> (kSpindleOutput - 1)) & 1u) != 0;
    if (!spindle)
      fail(at_code, fmt::format("{} needs the spindle on (M3): the cycle stops it and starts it "
                                "again",
                                name));
  }
}

// Cycle words are kept while the cycle code stays the motion mode; the series' first level
// is kept until a motion that is not a cycle.
void GcodeExecutor::cycle_mode(int was) {
  const int m = modes_.motion;
  if (m == was) return;
  modes_.cycle_depth.reset();
  modes_.cycle_r.reset();
  modes_.cycle_q.reset();
  modes_.cycle_p.reset();
  modes_.cycle_ijk.reset();
  if (!is_cycle(m)) modes_.cycle_initial.reset();
}

void GcodeExecutor::canned_cycle(const Words& w, const SourceLoc& loc) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  const int code = modes_.motion;
  const double lin = length_scale();
  const std::array<int, 3> ax = plane_axes(modes_.plane);
  const int ua = ax[0], va = ax[1], ca = ax[2];  // the plane's axes and the cycle axis
  const char u_letter = kAxes[static_cast<size_t>(ua)], v_letter = kAxes[static_cast<size_t>(va)];
  const char c_letter = kAxes[static_cast<size_t>(ca)];
  if (w.has(c_letter)) modes_.cycle_depth = w.get(c_letter) * lin;
  if (w.has('R')) modes_.cycle_r = w.get('R') * lin;
  if (w.has('Q')) {
    if (!(w.get('Q') > 0)) fail(w.at('Q', loc), "Q, the peck depth, must be above 0");
    modes_.cycle_q = w.get('Q') * lin;
  }
  if (w.has('P')) modes_.cycle_p = wincnc ? w.get('P') / 1000 : w.get('P');  // WinCNC: ms
  if (code == 870) {
    std::array<double, 3> ijk = modes_.cycle_ijk.value_or(std::array<double, 3>{0, 0, 0});
    for (int i = 0; i < 3; ++i)
      if (w.has("IJK"[i])) ijk[static_cast<size_t>(i)] = w.get("IJK"[i]) * lin;
    modes_.cycle_ijk = ijk;
  }
  if (w.has('L') && w.get('L') > kMaxBlockMoves) fail(w.at('L', loc), too_many_moves(w.get('L')));
  const int repeats = w.has('L') ? static_cast<int>(w.get('L')) : 1;
  const double feed = feed_for(w, 1, loc);
  const double inch = units_factor(Units::Inches, ctx_.settings().units);
  const Vec6 start = program_position();
  if (!modes_.cycle_initial) modes_.cycle_initial = start[ca];
  const double initial = *modes_.cycle_initial;
  const double r = modes_.incremental ? initial + *modes_.cycle_r : *modes_.cycle_r;
  const double bottom = modes_.incremental ? r + *modes_.cycle_depth : *modes_.cycle_depth;
  if (bottom > r)
    fail(loc, fmt::format("the hole's bottom {} is above the retract level R; check {} and R "
                          "(and G90/G91)",
                          c_letter, c_letter));
  // Bounded before any move is made: a hole is at most 8 moves (G87's), a pecking one at most
  // 3 a peck and 3 more.
  const bool pecking = code == 730 || code == 830;
  const double pecks =
      pecking ? std::ceil((r - bottom) / *modes_.cycle_q * (1 - kPeckTolerance)) : 0;
  if (const double moves = repeats * (pecking ? 3 * pecks + 3 : 8); moves > kMaxBlockMoves)
    fail(pecking && w.has('Q') && !(w.has('L') && repeats > 1) ? w.at('Q', loc)
         : w.has('L')                                          ? w.at('L', loc)
                                                               : loc,
         too_many_moves(moves));
  double middle = 0;  // G87: the top of the back bore, absolute
  if (code == 870) {
    const double k = (*modes_.cycle_ijk)[static_cast<size_t>(ca)];
    middle = modes_.incremental ? bottom + k : k;
  }
  const Vec6 k = axis_scale();
  double first_level = start[ca];
  double level0 = initial;
  if (level0 < r) {  // below R: straight up to R first
    Vec6 t = start;
    t[ca] = r;
    line(t, SpeedClass::Jog, 0, loc);
    level0 = first_level = r;
  }
  // WinCNC's cycles always end at R (manual, G73-G83: "moves back to R at Rapid velocity").
  const double clear = modes_.retract_to_r || wincnc ? r : level0;
  double hole_u = start[ua], hole_v = start[va];
  const double step_u = modes_.incremental && w.has(u_letter) ? w.get(u_letter) * k[ua] : 0;
  const double step_v = modes_.incremental && w.has(v_letter) ? w.get(v_letter) * k[va] : 0;
  if (!modes_.incremental) {
    if (w.has(u_letter)) hole_u = w.get(u_letter) * k[ua];
    if (w.has(v_letter)) hole_v = w.get(v_letter) * k[va];
  }
  // A straight move to (u, v) across the plane and `level` along the cycle axis.
  auto go = [&](double u, double v, double level, SpeedClass cls) {
    Vec6 t = program_position();
    t[ua] = u;
    t[va] = v;
    t[ca] = level;
    line(t, cls, feed, loc);
  };
  auto spindle = [&](bool on) {
    if (((ctx_.state().outputs >> (kSpindleOutput - 1)) & 1u) != static_cast<unsigned>(on))
      ctx_.set_output(kSpindleOutput, on, loc);
  };
  auto pause = [&](const std::string& question) {
    ctx_.come_to_rest(loc);
    if (!io_.confirm(question, loc))
      throw OperatorStop({loc, Severity::Error,
                          fmt::format("stopped by the operator at {}", code_name('G', code))});
  };
  auto dwell = [&] {
    if (modes_.cycle_p && *modes_.cycle_p > 0) ctx_.dwell(*modes_.cycle_p, loc);
  };
  for (int hole = 0; hole < repeats; ++hole) {
    hole_u += step_u;
    hole_v += step_v;
    const double u = hole_u, v = hole_v;
    if (hole == 0 && first_level > r) {
      go(u, v, first_level, SpeedClass::Jog);
      go(u, v, r, SpeedClass::Jog);
    } else {
      go(u, v, clear, SpeedClass::Jog);
      if (clear > r) go(u, v, r, SpeedClass::Jog);
    }
    switch (code) {
      case 810:
      case 820:
        go(u, v, bottom, SpeedClass::Move);
        if (code == 820) dwell();
        go(u, v, clear, SpeedClass::Jog);
        break;
      case 730:
      case 830: {
        // Peck: feed Q deeper each time; G73 backs off a little, G83 goes back to R and
        // comes down at rapid to a little above the last depth.
        // A depth within a rounding error of the bottom is the bottom: a depth that is a
        // whole number of pecks in the program's units is not one in the machine's, and
        // must not end in a sliver of a peck.
        const double q = *modes_.cycle_q;
        const double eps = kPeckTolerance * (r - bottom);
        for (double depth = r - q; depth > bottom + eps; depth -= q) {
          go(u, v, depth, SpeedClass::Move);
          if (code == 730) {
            go(u, v, depth + (wincnc ? kWinCncPeckClearanceIn : kG73Backoff) * inch,
               SpeedClass::Jog);
          } else {
            go(u, v, r, SpeedClass::Jog);
            go(u, v, depth + (wincnc ? kWinCncPeckClearanceIn : kG83Clearance) * inch,
               SpeedClass::Jog);
          }
        }
        go(u, v, bottom, SpeedClass::Move);
        go(u, v, clear, SpeedClass::Jog);
        break;
      }
      case 850:  // bore: feed in, feed out to R
        go(u, v, bottom, SpeedClass::Move);
        go(u, v, r, SpeedClass::Move);
        go(u, v, clear, SpeedClass::Jog);
        break;
      case 860:  // bore: dwell, spindle stops, rapid out, spindle starts again
        go(u, v, bottom, SpeedClass::Move);
        dwell();
        spindle(false);
        go(u, v, clear, SpeedClass::Jog);
        spindle(true);
        break;
      case 870: {  // back bore: in through the hole off-centre with the spindle stopped
        const std::array<double, 3>& ijk = *modes_.cycle_ijk;
        const double off_u = u + ijk[static_cast<size_t>(ua)];
        const double off_v = v + ijk[static_cast<size_t>(va)];
        go(off_u, off_v, r, SpeedClass::Jog);
        spindle(false);
        // LinuxCNC orients the spindle here; Gantry's spindle has no orientation.
        pause(
            "G87: the spindle is stopped; turn the tool so that it passes through the hole, "
            "then continue");
        go(off_u, off_v, bottom, SpeedClass::Jog);
        go(u, v, bottom, SpeedClass::Jog);
        spindle(true);
        go(u, v, middle, SpeedClass::Move);
        go(u, v, bottom, SpeedClass::Move);
        spindle(false);
        pause(
            "G87: the spindle is stopped; turn the tool so that it passes back through the "
            "hole, then continue");
        go(off_u, off_v, bottom, SpeedClass::Jog);
        go(off_u, off_v, clear, SpeedClass::Jog);
        go(u, v, clear, SpeedClass::Jog);
        spindle(true);
        break;
      }
      case 880:  // bore: dwell, spindle stops, the operator takes over
        go(u, v, bottom, SpeedClass::Move);
        dwell();
        spindle(false);
        // LinuxCNC stops the program for the operator to retract by hand and then carries on
        // as if the tool were at the clearance level; Gantry cannot be jogged in a pause, so
        // it makes that retract itself once the operator continues.
        pause(
            fmt::format("G88: the spindle is stopped at the bottom of the hole; continue to "
                        "retract {} at rapid",
                        c_letter));
        go(u, v, clear, SpeedClass::Jog);
        spindle(true);
        break;
      case 890:  // bore: dwell, feed out
        go(u, v, bottom, SpeedClass::Move);
        dwell();
        go(u, v, clear, SpeedClass::Move);
        break;
      default:
        break;
    }
  }
}

}  // namespace gantry
