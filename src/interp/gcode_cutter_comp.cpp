// G-code's cutter radius compensation G40, G41, G42, G41.1, G42.1 with LinuxCNC 2.9's
// semantics (docs/gcode.md, "Cutter radius compensation").
//
// The geometry, in the plane's coordinates (u, v): XY with G17, ZX with G18. r is the tool
// radius; `side` is +1 for G41 (tool left of the path) and -1 for G42. A direction a turned
// by side * 90 degrees points from the path to the tool centre.
//
//  - Entry (the first move after G41/G42 from the tool's point C to the programmed P): the
//    tool ends at P + r (cos b, sin b), b = atan2(P - C) + side * 90 deg, tangent to the
//    line at P; the move must be longer than r.
//  - A line from the last programmed point O to P: the tool centre runs on the parallel
//    line at distance r, from O + n r to P + n r (n the unit normal on the tool's side). The
//    turn between the previous move's direction at O (read off the tool: theta, the
//    direction O -> tool, minus side * 90 deg) and the new direction alpha gives beta, the
//    corner's deviation. Convex (0.05 rad < beta <= pi + 0.05): the tool rolls around O on
//    an arc of radius r from its current point to O + n r (a straight jog for G0). Concave
//    (beta outside that range): the two offset lines meet before their ends, at
//    retreat = r / tan((beta + pi) / 2) back along the previous offset move, so the
//    previous move is shortened to that point (for an arc before the line, the point where
//    the line's offset cuts the arc's offset circle).
//  - An arc of radius R about centre K: the tool runs on the concentric circle of radius
//    R - r (tool inside the arc: G41 with G3, G42 with G2; R must exceed r) or R + r; its end
//    is the programmed end moved r along the radius. At a convex corner before it, the tool
//    first rolls around O to O + r (cos d, sin d), d the radius direction at the start; at a
//    concave one the previous offset move is cut where its offset path meets the arc's
//    offset circle (the law of cosines for two circles, a projection for line and circle).
//
// A move's end therefore depends on the next move: as LinuxCNC does, each offset move is
// held back (with the outputs, dwells and pauses after it) until the next one shows which
// corner follows, then moved to the intersection and sent. Moving an end point backwards
// past the move's start (a line reversed, an arc longer than programmed) means the tool
// cannot reach the corner without gouging: a located error.
#include <fmt/format.h>  // messages

#include <algorithm>  // equal
#include <cctype>     // tolower
#include <cmath>      // atan2, hypot, cos, sin, acos, asin, tan

#include "gantry/interp/gcode_executor.hpp"
#include "gantry/canon/arc_geometry.hpp"  // plane_axes

#include "gcode_cutter_comp.hpp"
#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;

namespace {

constexpr double kCornerTolerance = 0.05;  // radians: straight on, or a corner (LinuxCNC's)

// The signed sweep from `s` to `e` about `c` going `turn` times round (+ counter-clockwise,
// - clockwise): the part turn up to the end, then whole turns.
double sweep_of(double su, double sv, double cu, double cv, int turn, double eu, double ev) {
  if (turn == 0) return 0;
  double a = std::atan2(sv - cv, su - cu);
  double b = std::atan2(ev - cv, eu - cu);
  if (turn > 0) {
    if (b <= a) b += 2 * M_PI;
    return b - a + (turn - 1) * 2 * M_PI;
  }
  if (a <= b) a += 2 * M_PI;
  return b - a + (turn + 1) * 2 * M_PI;
}

bool tool_inside(int side, int turn) {
  return (side > 0 && turn > 0) || (side < 0 && turn < 0);
}

}  // namespace

void GcodeExecutor::Comp::send_all(GcodeExecutor& ex) {
  start_valid = false;
  std::vector<Pending> items;
  items.swap(queue);
  const std::array<int, 3> ax = plane_axes(ex.modes_.plane);
  for (const Pending& p : items) {
    switch (p.kind) {
      case Pending::Kind::Action:
        p.action();
        break;
      case Pending::Kind::Line:
        ex.line(p.end, p.cls, p.speed, p.loc);
        break;
      case Pending::Kind::Arc: {
        const Vec6 from = ex.program_position();
        const double sweep =
            sweep_of(from[ax[0]], from[ax[1]], p.cu, p.cv, p.turn, p.end[ax[0]], p.end[ax[1]]);
        Vec6 centre = Vec6::Zero();
        centre[ax[0]] = p.cu;
        centre[ax[1]] = p.cv;
        const Vec6 centre_file = ex.to_file(centre);
        ModalState& st = ex.ctx_.state();
        const SpeedSettings saved = st.speeds;
        st.speeds.move = {p.speed, p.speed, p.speed, p.speed, p.speed};
        try {
          ex.ctx_.arc_to(ex.to_file(p.end), centre_file[ax[0]], centre_file[ax[1]], sweep,
                         SpeedClass::Move, p.loc, ex.modes_.plane);
        } catch (...) {
          st.speeds = saved;
          throw;
        }
        st.speeds = saved;
        if (ex.modes_.exact_stop) ex.ctx_.come_to_rest(p.loc);
        break;
      }
    }
  }
}

void GcodeExecutor::Comp::flush_to(GcodeExecutor& ex, double u, double v, const SourceLoc& loc) {
  const std::array<int, 3> ax = plane_axes(ex.modes_.plane);
  const double inch = units_factor(Units::Inches, ex.ctx_.settings().units);
  for (Pending& p : queue) {
    if (p.kind == Pending::Kind::Arc) {
      const double grown = std::abs(sweep_of(start_u, start_v, p.cu, p.cv, p.turn, u, v));
      if (p.programmed_sweep != 0 && start_valid &&
          grown > std::abs(p.programmed_sweep) + 0.001 * inch)
        fail(loc,
             "the arc before this move cannot reach the concave corner without gouging: "
             "the tool is too large for the corner; use a smaller tool or change the path");
    } else if (p.kind == Pending::Kind::Line) {
      const double dot = p.du * (u - start_u) + p.dv * (v - start_v);
      if (start_valid && dot < 0)
        fail(loc, fmt::format("the {} before this move cannot reach the concave corner without "
                              "gouging: the tool is too large for the corner (the offset move "
                              "would run backwards); use a smaller tool or change the path",
                              p.cls == SpeedClass::Jog ? "rapid" : "straight move"));
    } else {
      continue;
    }
    p.end[ax[0]] = u;
    p.end[ax[1]] = v;
  }
  send_all(ex);
  set_start(u, v);
}

GcodeExecutor::~GcodeExecutor() = default;

bool GcodeExecutor::comp_active() const {
  return comp_ && comp_->side != 0 && comp_->radius > 0;
}

// As LinuxCNC 2.9: with G41/G42 on, an expression may not read the position (its end points
// are not known until the next move); a (DEBUG)/(PRINT) message shows the last move's
// compensated end point before its corner is joined to the next move. After G40 it is the
// programmed end point, from which the next move leaves the offset path.
Vec6 GcodeExecutor::current_position(const SourceLoc* at) const {
  if (comp_ && comp_->side != 0 && at)
    fail(*at,
         "#5420-#5425 cannot be read while cutter radius compensation is on (G41/G42), "
         "as in LinuxCNC: the compensated position is not known until the next move; read "
         "them before G41/G42 or after G40");
  if (comp_ && comp_->exit_base) return *comp_->exit_base;
  if (comp_active()) return comp_->cur;
  return program_position();
}

Vec6 GcodeExecutor::motion_start() const {
  if (comp_active() && !comp_->first) return comp_->prog;
  if (comp_ && comp_->exit_base) return *comp_->exit_base;
  if (comp_active()) return comp_->cur;
  return program_position();
}

void GcodeExecutor::moved_straight() {
  if (!comp_) return;
  comp_->arc_not_allowed = false;
  comp_->exit_base.reset();
}

void GcodeExecutor::check_arc_allowed(const SourceLoc& loc) const {
  if (comp_ && comp_->arc_not_allowed)
    fail(loc,
         "the move just after G40 must be straight, not an arc: the tool is still off the "
         "programmed path by the tool radius; give a G1 (or G0) first");
}

void GcodeExecutor::deferred(std::function<void()> action) {
  if (!comp_ || comp_->queue.empty()) return action();
  Comp::Pending p;
  p.kind = Comp::Pending::Kind::Action;
  p.action = std::move(action);
  comp_->queue.push_back(std::move(p));
}

// ---- checking and switching ------------------------------------------------------------

void GcodeExecutor::check_comp_words(const Words& w, int motion, const SourceLoc& loc) const {
  const int g7 = w.g[7];
  SourceLoc at7 = loc;
  at7.column = w.g_col[7];
  const bool turning_on = g7 == 410 || g7 == 420 || g7 == 411 || g7 == 421;
  if (w.has('D') && !turning_on && !w.own_letters())
    fail(w.at('D', loc),
         "D goes with G41/G42 (the tool whose radius compensates) or G41.1/G42.1 "
         "(the tool's diameter)");
  if (turning_on) {
    const std::string name = code_name('G', g7);
    if (loc.file && loc.file->size() >= 4 &&
        std::equal(loc.file->end() - 4, loc.file->end(), ".sbp",
                   [](char a, char b) { return std::tolower(a) == b; }))
      fail(at7, fmt::format("{}: cutter radius compensation works in G-code files (.nc, .ngc, "
                            "...), not in G-code lines of an OpenSBP file",
                            name));
    if (comp_ && comp_->side != 0)
      fail(at7, fmt::format("{}: cutter radius compensation is already on; give G40 first", name));
    const ArcPlane plane = w.g[2] == 170   ? ArcPlane::XY
                           : w.g[2] == 180 ? ArcPlane::ZX
                           : w.g[2] == 190 ? ArcPlane::YZ
                                           : modes_.plane;
    if (plane == ArcPlane::YZ)
      fail(at7, fmt::format("{}: cutter radius compensation works in the XY (G17) and ZX (G18) "
                            "planes only, not in YZ (G19)",
                            name));
    if ((g7 == 411 || g7 == 421) && !w.has('D'))
      fail(at7, fmt::format("{} needs D, the tool's diameter", name));
    if (w.has('L') && (g7 == 411 || g7 == 421))
      // LinuxCNC refuses L outside G18 too ("plane is not G18"); in G18 it is a lathe's.
      fail(w.at('L', loc),
           fmt::format("{}: L is a lathe tool's orientation, which LinuxCNC takes only in the "
                       "ZX plane (G18) of a lathe; Gantry drives routers and mills, whose tools "
                       "have none: leave L out",
                       name));
    if ((g7 == 410 || g7 == 420) && w.has('D')) {
      const double d = w.get('D');
      if (d != std::round(d) || d < 0)
        fail(w.at('D', loc), fmt::format("{} D{}: D is a tool number, a whole number 0 or more",
                                         name, format_number(d)));
    }
  }
  const bool on = (comp_ && comp_->side != 0) || turning_on;
  if (!on || g7 == 400) return;
  // What LinuxCNC refuses while compensation is on.
  auto refuse = [&](const SourceLoc& at, const std::string& what) {
    fail(at, fmt::format("{} with cutter radius compensation on: give G40 first", what));
  };
  auto at_group = [&](int group) {
    SourceLoc l = loc;
    l.column = w.g_col[group];
    return l;
  };
  if (comp_ && comp_->side != 0) {
    const ArcPlane plane = w.g[2] == 170   ? ArcPlane::XY
                           : w.g[2] == 180 ? ArcPlane::ZX
                           : w.g[2] == 190 ? ArcPlane::YZ
                                           : modes_.plane;
    if (plane != modes_.plane) refuse(at_group(2), "cannot change the plane");
  }
  if (w.g[12] >= 0) refuse(at_group(12), "cannot change the coordinate system");
  if (w.g[8] >= 0) refuse(at_group(8), "cannot change the tool length offset");
  if (w.g53) refuse(loc, "G53 cannot be used");
  switch (w.non_modal) {
    case 280:
    case 300:
      refuse(loc, fmt::format("{} cannot be used", code_name('G', w.non_modal)));
      break;
    case 920:
    case 921:
    case 922:
    case 923:
      refuse(loc, fmt::format("{}: cannot change the axis offsets", code_name('G', w.non_modal)));
      break;
    case 100:
      if (w.has('L') && w.get('L') != 1) refuse(loc, "G10: cannot change a coordinate system");
      break;
    default:
      break;
  }
  if (motion >= 382 && motion <= 385 && (w.g[1] >= 0 || w.any_axis()))
    refuse(loc, fmt::format("{}: cannot probe", code_name('G', motion)));
  if (w.m[6] == 60) refuse(loc, "M6: cannot change tools");
}

void GcodeExecutor::cutter_comp(const Words& w, const SourceLoc& loc) {
  if (!comp_) comp_ = std::make_unique<Comp>();
  Comp& c = *comp_;
  const int g7 = w.g[7];
  if (g7 == 400) {
    if (comp_active() && !c.first) {
      // The last offset move ends where it is; the tool leaves the path on the next move,
      // which starts from the programmed point (and must be straight).
      const std::array<int, 3> ax = plane_axes(modes_.plane);
      c.flush_to(*this, c.cur[ax[0]], c.cur[ax[1]], loc);
      c.exit_base = c.prog;
      c.arc_not_allowed = true;
    }
    c.side = 0;
    c.first = true;
    return;
  }
  const GcodeOffsets& o = ctx_.state().gcode;
  int side = g7 == 410 || g7 == 411 ? 1 : -1;
  double radius = 0;
  if (g7 == 411 || g7 == 421) {
    radius = w.get('D') * length_scale() / 2;
  } else {
    const int tool = w.has('D') && w.get('D') != 0 ? static_cast<int>(w.get('D')) : o.tool;
    const double d = tool_entry(tool, w.has('D') ? w.at('D', loc) : loc).diameter;
    // With no tool table file every tool's diameter is 0: the cutter is SB3's (VC's), so that
    // G41 never runs uncompensated without a word.
    radius = (d == 0 && tool != 0 && o.tools.implicit() ? ctx_.settings().cutter.diameter : d) / 2;
  }
  if (radius < 0) {  // a negative radius (a worn tool's table entry): the other side
    radius = -radius;
    side = -side;
  }
  c.side = side;
  c.radius = radius;
  c.first = true;
  c.cur = c.exit_base ? *c.exit_base : program_position();
}

void GcodeExecutor::end_file(const SourceLoc& loc) {
  if (!comp_) return;
  if (comp_active() && !comp_->first) {
    const std::array<int, 3> ax = plane_axes(modes_.plane);
    comp_->flush_to(*this, comp_->cur[ax[0]], comp_->cur[ax[1]], loc);
  }
  comp_->queue.clear();
  comp_->side = 0;
  comp_->first = true;
  comp_->exit_base.reset();
  comp_->arc_not_allowed = false;
}

// ---- straight moves ---------------------------------------------------------------------

void GcodeExecutor::comp_line(const Vec6& p, bool rapid, double speed, const SourceLoc& loc) {
  Comp& c = *comp_;
  const std::array<int, 3> ax = plane_axes(modes_.plane);
  const int u = ax[0], v = ax[1];
  const double r = c.radius;
  const SpeedClass cls = rapid ? SpeedClass::Jog : SpeedClass::Move;
  c.exit_base.reset();
  c.arc_not_allowed = false;
  if (c.first) {  // the entry move
    const Vec6 from = c.cur;
    if (!(std::hypot(p[u] - from[u], p[v] - from[v]) > r))
      fail(loc, fmt::format("the entry move after G41/G42 is not longer than the tool radius "
                            "({}): start the compensated path further from its first point",
                            format_number(r / length_scale())));
    const double b = std::atan2(p[v] - from[v], p[u] - from[u]) + c.side * M_PI / 2;
    Vec6 end = p;
    end[u] += r * std::cos(b);
    end[v] += r * std::sin(b);
    c.set_start(from[u], from[v]);
    c.push_line(end, std::cos(b), std::sin(b), cls, speed, loc);
    c.first = false;
    c.cur = end;
    c.prog = p;
    return;
  }
  const Vec6 o = c.prog;
  const Vec6 cur = c.cur;
  if (p[u] == o[u] && p[v] == o[v]) {  // no motion in the plane: the tool stays offset
    Vec6 end = p;
    end[u] = cur[u];
    end[v] = cur[v];
    c.push_line(end, 0, 0, cls, speed, loc);
    c.cur = end;
    c.prog = p;
    return;
  }
  double theta = std::atan2(cur[v] - o[v], cur[u] - o[u]);  // O -> tool
  double alpha = std::atan2(p[v] - o[v], p[u] - o[u]);      // the new direction
  double beta, gamma;
  if (c.side > 0) {
    if (theta < alpha) theta += 2 * M_PI;
    beta = theta - alpha - M_PI / 2;
    gamma = M_PI / 2;
  } else {
    if (alpha < theta) alpha += 2 * M_PI;
    beta = alpha - theta - M_PI / 2;
    gamma = -M_PI / 2;
  }
  Vec6 end = p;
  end[u] = p[u] + r * std::cos(alpha + gamma);
  end[v] = p[v] + r * std::sin(alpha + gamma);
  const double mid_u = o[u] + r * std::cos(alpha + gamma);
  const double mid_v = o[v] + r * std::sin(alpha + gamma);
  const Comp::Pending* prev = c.front_move();
  const bool prev_arc = c.front_is_arc();
  bool concave = beta < -kCornerTolerance || beta > M_PI + kCornerTolerance;
  // Straight on after an arc that turned the other way (the top of an "h"): the corner is
  // taken as concave, keeping the tool on its side rather than looping round.
  if (!concave && beta > M_PI - kCornerTolerance && prev_arc &&
      ((c.side < 0 && prev->turn > 0) || (c.side > 0 && prev->turn < 0)))
    concave = true;
  if (!concave && beta > kCornerTolerance) {  // convex: round the corner about O
    c.flush_to(*this, cur[u], cur[v], loc);
    Vec6 mid = cur;
    mid[u] = mid_u;
    mid[v] = mid_v;
    for (int a = 3; a < kAxisCount; ++a) mid[a] = p[a];
    if (!rapid) {
      c.push_arc(mid, o[u], o[v], c.side > 0 ? -1 : 1, 0, speed, loc);
    } else {
      c.push_line(mid, 0, 0, SpeedClass::Jog, speed, loc);
    }
    c.send_all(*this);
    c.set_start(mid_u, mid_v);
  } else if (concave) {
    double mu = 0, mv = 0;
    if (!prev_arc) {  // line -> line: back along the previous offset line
      const double half_corner = (beta + M_PI) / 2;
      if (half_corner == 0)
        fail(loc, "a zero-degree inside corner cannot be cut with cutter radius compensation");
      const double retreat = r / std::tan(half_corner);
      mu = cur[u] + retreat * std::cos(theta + gamma);
      mv = cur[v] + retreat * std::sin(theta + gamma);
    } else {  // arc -> line: where the line's offset cuts the arc's offset circle
      const double old_r = std::hypot(prev->cv - prev->end[v], prev->cu - prev->end[u]);
      const double dir = std::atan2(p[v] - o[v], p[u] - o[u]);
      const double th = prev->turn > 0 ? dir + M_PI / 2 : dir - M_PI / 2;
      const double phi = std::atan2(prev->cv - o[v], prev->cu - o[u]);
      const bool inside = tool_inside(c.side, prev->turn);
      const double uncomp_r = inside ? old_r + r : old_r - r;
      const double d = uncomp_r * std::cos(th - phi);
      const double l = (inside ? d - r : d + r) / old_r;
      if (l > 1 || l < -1)
        fail(loc,
             "the arc before this line makes a corner the compensated tool cannot fit in "
             "without gouging; use a smaller tool or change the path");
      const double from_centre =
          (inside == (prev->turn > 0) ? -std::acos(l) : std::acos(l)) + th + M_PI;
      mu = prev->cu + old_r * std::cos(from_centre);
      mv = prev->cv + old_r * std::sin(from_centre);
    }
    c.flush_to(*this, mu, mv, loc);
  } else {  // straight on
    c.send_all(*this);
    c.set_start(cur[u], cur[v]);
  }
  c.push_line(end, p[u] - o[u], p[v] - o[v], cls, speed, loc);
  c.cur = end;
  c.prog = p;
}

// ---- arcs -------------------------------------------------------------------------------

void GcodeExecutor::comp_arc(const Vec6& end, double cu, double cv, int turn, double speed,
                             const SourceLoc& loc) {
  Comp& c = *comp_;
  const std::array<int, 3> ax = plane_axes(modes_.plane);
  const int u = ax[0], v = ax[1];
  const double r = c.radius;
  const bool inside = tool_inside(c.side, turn);
  const std::string too_small = fmt::format(
      "the tool radius ({}) is not less than the arc's radius: the tool cannot cut inside this "
      "arc; use a smaller tool",
      format_number(r / length_scale()));
  c.exit_base.reset();
  if (c.first) {  // the entry move is an arc: one arc tangent to the tool at its start
    const Vec6 from = c.cur;
    if (!(std::hypot(end[u] - from[u], end[v] - from[v]) > r))
      fail(loc, fmt::format("the entry arc after G41/G42 does not end further than the tool "
                            "radius ({}) from its start: start the compensated path further "
                            "from its first point",
                            format_number(r / length_scale())));
    if (inside && std::hypot(cu - from[u], cv - from[v]) <= r) fail(loc, too_small);
    const double gamma =
        inside ? std::atan2(cv - end[v], cu - end[u]) : std::atan2(end[v] - cv, end[u] - cu);
    c.prog = end;
    Vec6 e = end;
    e[u] += r * std::cos(gamma);
    e[v] += r * std::sin(gamma);
    // The arc through the tool's start and the offset end whose centre lies on the line
    // from that end to the programmed centre: half the chord over the cosine of the angle
    // between chord and that line.
    const double half_chord = std::hypot(from[v] - e[v], from[u] - e[u]) / 2;
    const double to_centre = std::atan2(cv - e[v], cu - e[u]);
    const double angle = std::atan2(from[v] - e[v], from[u] - e[u]) - to_centre;
    if (std::abs(std::cos(angle)) < 1e-6) fail(loc, too_small);
    const double dist = half_chord / std::cos(angle);
    const double ncu = e[u] + dist * std::cos(to_centre);
    const double ncv = e[v] + dist * std::sin(to_centre);
    c.set_start(from[u], from[v]);
    c.push_arc(e, ncu, ncv, turn, sweep_of(from[u], from[v], ncu, ncv, turn, e[u], e[v]), speed,
               loc);
    c.first = false;
    c.cur = e;
    return;
  }
  const Vec6 o = c.prog;
  const Vec6 cur = c.cur;
  const double arc_r = std::hypot(cu - end[u], cv - end[v]);
  const double theta =
      std::atan2(cur[v] - o[v], cur[u] - o[u]) + (c.side > 0 ? -M_PI / 2 : M_PI / 2);
  double delta = std::atan2(cv - o[v], cu - o[u]);
  const double alpha = turn > 0 ? delta - M_PI / 2 : delta + M_PI / 2;  // the arc's start tangent
  double beta = c.side > 0 ? theta - alpha : alpha - theta;
  if (beta > 1.5 * M_PI)
    beta -= 2 * M_PI;
  else if (beta < -M_PI / 2)
    beta += 2 * M_PI;
  double gamma;
  if (inside) {
    gamma = std::atan2(cv - end[v], cu - end[u]);
    if (arc_r <= r) fail(loc, too_small);
  } else {
    gamma = std::atan2(end[v] - cv, end[u] - cu);
    delta += M_PI;
  }
  Vec6 e = end;
  e[u] += r * std::cos(gamma);
  e[v] += r * std::sin(gamma);
  const double programmed = sweep_of(o[u], o[v], cu, cv, turn, end[u], end[v]);
  const bool concave = beta < -kCornerTolerance || beta > M_PI + kCornerTolerance ||
                       (std::abs(beta - M_PI) < kCornerTolerance && !inside);
  if (concave) {
    const std::string gouge =
        "this arc makes a concave corner the compensated tool cannot reach without gouging; use "
        "a smaller tool or change the path";
    double mu, mv;
    if (!c.front_is_arc()) {  // line -> arc: where the line's offset cuts the offset circle
      const double across = arc_r * std::sin(beta - M_PI / 2);
      const double dist = inside ? arc_r - r : arc_r + r;
      const double l = (inside ? across + r : across - r) / dist;
      if (l > 1 || l < -1) fail(loc, gouge);
      const double angle =
          inside ? (turn > 0 ? theta + std::asin(l) : theta - std::asin(l))
                 : (turn > 0 ? theta + M_PI - std::asin(l) : theta + M_PI + std::asin(l));
      mu = cu + dist * std::cos(angle);
      mv = cv + dist * std::sin(angle);
    } else {  // arc -> arc: where the two offset circles cross (law of cosines)
      const Comp::Pending& prev = c.queue.front();
      const double old_r = std::hypot(prev.cv - prev.end[v], prev.cu - prev.end[u]);
      const double new_r = inside ? arc_r - r : arc_r + r;
      const double apart = std::hypot(prev.cv - cv, prev.cu - cu);
      if (old_r == 0 || apart == 0)
        fail(loc,
             "these two arcs have the same centre: the corner between them cannot be "
             "compensated");
      const double a = (old_r * old_r + apart * apart - new_r * new_r) / (2 * old_r * apart);
      if (a > 1 || a < -1) fail(loc, gouge);
      const double pullback = std::acos(a);
      const double towards = std::atan2(cv - prev.cv, cu - prev.cu);
      const bool plus = tool_inside(c.side, prev.turn) == (turn > 0);
      const double dir = plus ? towards + pullback : towards - pullback;
      mu = prev.cu + old_r * std::cos(dir);
      mv = prev.cv + old_r * std::sin(dir);
    }
    c.flush_to(*this, mu, mv, loc);
  } else if (beta > kCornerTolerance) {  // convex: round the corner about O first
    const double mu = o[u] + r * std::cos(delta), mv = o[v] + r * std::sin(delta);
    c.send_all(*this);
    Vec6 mid = cur;
    mid[u] = mu;
    mid[v] = mv;
    for (int a = 3; a < kAxisCount; ++a) mid[a] = end[a];
    c.push_arc(mid, o[u], o[v], c.side > 0 ? -1 : 1, 0, speed, loc);
    c.send_all(*this);
    c.set_start(mu, mv);
  } else {  // tangent
    c.send_all(*this);
    c.set_start(cur[u], cur[v]);
  }
  c.push_arc(e, cu, cv, turn, programmed, speed, loc);
  c.cur = e;
  c.prog = end;
}

}  // namespace gantry
