// G-code's motions: straight moves, arcs and probes (docs/gcode.md).
#include "gantry/interp/gcode_executor.hpp"

#include <fmt/format.h>  // messages

#include <cmath>  // atan2, hypot, round

#include "gantry/canon/arc_geometry.hpp"  // plane_axes

#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;

void GcodeExecutor::motion(const Words& w, const SourceLoc& loc) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  const int was = modes_.motion;
  if (w.g[1] >= 0) modes_.motion = w.g[1] == 800 ? -1 : w.g[1];
  const int m = modes_.motion;
  cycle_mode(was);
  if (wincnc && w.g53) return wincnc_g53(w, loc);  // a rapid, or alone a lift
  if (takes_axis_words(w.non_modal, wincnc) || w.wincnc_axes || w.g431_alone() || m < 0) return;
  const bool arc_mode = m == 20 || m == 30;
  if (!w.any_axis() && !(w.g[1] >= 0 && is_cycle(m)) && !(arc_mode && w.makes_arc(wincnc)))
    return;  // nothing to move
  if (w.g53) {
    const ModalState& st = ctx_.state();
    const Vec6 k = axis_scale();
    Vec6 working = st.position;
    for (int a = 0; a < kAxisCount; ++a)
      if (w.has(kAxes[static_cast<size_t>(a)]))
        working[a] = w.get(kAxes[static_cast<size_t>(a)]) * k[a] - st.zero[a];
    Vec6 program = ctx_.transform().to_file(working) - st.gcode.axis_offset;
    program[2] -= st.gcode.tool_length;
    const double len = (program - program_position()).norm();
    line(program, m == 0 ? SpeedClass::Jog : SpeedClass::Move, feed_for(w, len, loc), loc);
    return;
  }
  switch (m) {
    case 0:
    case 10: {
      const Vec6 from = motion_start();
      const Vec6 target = axis_target(w, from, modes_.incremental);
      const double len = modes_.inverse_time ? (target - from).norm() : 0;  // G93 alone uses it
      const double speed = feed_for(w, len, loc);
      if (comp_active()) return comp_line(target, m == 0, speed, loc);
      moved_straight();
      const SpeedClass cls = m == 0 ? SpeedClass::Jog : SpeedClass::Move;
      // Without compensation `from` is where the tool is: not computed twice (the hot path).
      if (!comp_) return line(from, target, cls, speed, loc);
      line(target, cls, speed, loc);
      return;
    }
    case 20:
    case 30:
      arc(w, m == 20, loc);
      if (wincnc) modes_.motion = was == 20 || was == 30 ? 10 : was;  // arcs are not modal
      return;
    case 382:
    case 383:
    case 384:
    case 385:
      return probe(w, loc);
    default:
      return canned_cycle(w, loc);
  }
}

void GcodeExecutor::arc(const Words& w, bool clockwise, const SourceLoc& loc) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  const std::array<int, 3> ax = plane_axes(modes_.plane);
  const int u = ax[0], v = ax[1];
  check_arc_allowed(loc);
  const Vec6 start = motion_start();
  const Vec6 end = axis_target(w, start, modes_.incremental);
  const double lin = length_scale();
  const char normal_offset = "IJK"[ax[2]];
  if (ax[2] < 3 && w.has(normal_offset))
    fail(w.at(normal_offset, loc),
         fmt::format("{} is not a centre offset in this plane; the plane's are {} and {}",
                     normal_offset, "IJK"[u], "IJK"[v]));
  const char iu = "IJK"[u], iv = "IJK"[v];
  const bool offsets = w.has(iu) || w.has(iv);
  const double du = end[u] - start[u], dv = end[v] - start[v];
  const double chord = std::hypot(du, dv);
  const bool full = chord < 1e-9 * std::max(1.0, lin);
  // LinuxCNC's arc tolerances, in the program's units (inches for G20, else millimetres): a
  // radius below 0.00005 in (0.00127 mm) is no arc, and R may fall short of half the chord
  // by as much; the end's radius may differ from the start's by up to 0.002*sqrt(2) in
  // (0.02*sqrt(2) mm), or by up to 0.1 % of the larger radius if that is more, but never by
  // more than 100 times the absolute tolerance.
  const bool inch_units = modes_.units == ProgramUnits::Inches;
  const double unit =
      units_factor(inch_units ? Units::Inches : Units::Millimetres, ctx_.settings().units);
  const double radius_tolerance = (inch_units ? 0.00005 : 0.00005 * 25.4) * unit;
  const double spiral_tolerance = (inch_units ? 0.002 : 0.02) * M_SQRT2 * unit;
  double cu = 0, cv = 0;
  if (w.has('R')) {
    if (offsets) fail(w.at('R', loc), "an arc takes either a radius R or centre offsets, not both");
    if (full) fail(w.at('R', loc), "a full circle cannot be given by its radius: use I, J or K");
    const double r = w.get('R') * lin;
    if (chord / 2 - std::abs(r) > radius_tolerance)
      fail(w.at('R', loc), fmt::format("radius {} is too small: the end point is {} from the "
                                       "start",
                                       std::abs(w.get('R')), chord / lin));
    const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4));
    // The short arc (R > 0) has its centre on the right of the travel going clockwise.
    const double side = (clockwise ? 1 : -1) * (r > 0 ? 1 : -1);
    cu = start[u] + du / 2 + side * h * dv / chord;
    cv = start[v] + dv / 2 - side * h * du / chord;
  } else {
    if (!offsets && !wincnc)
      fail(loc, fmt::format("{} needs its centre: offsets {} and {}, or a radius R",
                            clockwise ? "G2" : "G3", iu, iv));
    std::array<double, 3>& last = modes_.last_ijk;
    const double ou = w.has(iu) ? w.get(iu) * lin : wincnc ? last[static_cast<size_t>(u)] : 0;
    const double ov = w.has(iv) ? w.get(iv) * lin : wincnc ? last[static_cast<size_t>(v)] : 0;
    last[static_cast<size_t>(u)] = ou;
    last[static_cast<size_t>(v)] = ov;
    const bool absolute = modes_.arc_absolute && !wincnc;
    cu = absolute ? ou : start[u] + ou;
    cv = absolute ? ov : start[v] + ov;
    const double r0 = std::hypot(start[u] - cu, start[v] - cv);
    const double r1 = std::hypot(end[u] - cu, end[v] - cv);
    if (r0 < radius_tolerance) fail(loc, "the arc's centre is its start point: check I, J and K");
    if (r1 < radius_tolerance)
      fail(loc, "the arc's centre is its end point: check the end point and I, J and K");
    const double differ = std::abs(r1 - r0);
    const double tolerance =
        std::min(100 * spiral_tolerance, std::max(spiral_tolerance, 0.001 * std::max(r0, r1)));
    if (differ > tolerance)
      fail(loc, fmt::format("the arc's end is {:.4f} from its centre but its start is {:.4f}: "
                            "the radii differ by more than {:.4f}; check the end point and I, J, "
                            "K (and G90.1/G91.1)",
                            r1 / lin, r0 / lin, tolerance / lin));
  }
  const double a0 = std::atan2(start[v] - cv, start[u] - cu);
  const double a1 = std::atan2(end[v] - cv, end[u] - cu);
  double sweep = a1 - a0;
  if (clockwise) {
    if (full || sweep >= 0) sweep -= 2 * M_PI;
    if (full && sweep < -2 * M_PI) sweep += 2 * M_PI;
  } else {
    if (full || sweep <= 0) sweep += 2 * M_PI;
    if (full && sweep > 2 * M_PI) sweep -= 2 * M_PI;
  }
  if (full) sweep = clockwise ? -2 * M_PI : 2 * M_PI;
  if (w.has('P')) {
    const double turns = w.get('P');
    if (turns != std::round(turns) || turns < 1)
      fail(w.at('P', loc), fmt::format("P{} is not a number of turns (1 or more)", turns));
    // Every turn is at least four chords: refused here, before any arithmetic on the sweep.
    if (turns > kMaxArcChords / 4)
      fail(w.at('P', loc), fmt::format("P{} turns: an arc may have at most {} chords; give fewer "
                                       "turns",
                                       format_number(turns), format_number(kMaxArcChords)));
    sweep += (clockwise ? -2 : 2) * M_PI * (turns - 1);
  }
  const double r = std::hypot(start[u] - cu, start[v] - cv);
  Vec6 rest = end - start;
  rest[u] = rest[v] = 0;
  const double length = std::hypot(r * sweep, rest.norm());
  const double speed = feed_for(w, length, loc);
  if (comp_active()) {
    const int turns = w.has('P') ? static_cast<int>(w.get('P')) : 1;
    return comp_arc(end, cu, cv, clockwise ? -turns : turns, speed, loc);
  }
  Vec6 centre = Vec6::Zero();
  centre[u] = cu;
  centre[v] = cv;
  const Vec6 centre_file = to_file(centre);
  ModalState& st = ctx_.state();
  const SpeedSettings saved = st.speeds;
  st.speeds.move = {speed, speed, speed, speed, speed};
  try {
    ctx_.arc_to(to_file(end), centre_file[u], centre_file[v], sweep, SpeedClass::Move, loc,
                modes_.plane);
  } catch (...) {
    st.speeds = saved;
    throw;
  }
  st.speeds = saved;
  if (modes_.exact_stop) ctx_.come_to_rest(loc);
}

void GcodeExecutor::probe(const Words& w, const SourceLoc& loc) {
  const int code = modes_.motion;
  const Vec6 start = program_position();
  const Vec6 target = axis_target(w, start, modes_.incremental);
  if (target == start) fail(loc, "the probe's target is where the tool is: nothing to probe");
  const bool closing = code == 382 || code == 383;
  const double speed = feed_for(w, (target - start).norm(), loc);
  probe_hit_ =
      ctx_.probe(to_file(target), speed, kProbeInput, loc, MachineLink::Watching::Probe, closing);
  probed_ = program_position();
  if (!probe_hit_ && (code == 382 || code == 384) && ctx_.input_switches())
    fail(loc,
         fmt::format("{}: the probe reached its target without the switch {}; nothing was "
                     "measured (G38.{} goes on without an error)",
                     code_name('G', code), closing ? "closing" : "opening", code == 382 ? 3 : 5));
}
}  // namespace gantry
