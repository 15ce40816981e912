// CommandContext: what a command handler may touch (command_context.hpp).
#include "gantry/interp/command_context.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>   // any_of, sort
#include <cctype>      // toupper
#include <cmath>       // isfinite, hypot
#include <filesystem>  // weakly_canonical
#include <sstream>     // read_file
#include <utility>     // exchange

#include "gantry/canon/arc_geometry.hpp"      // arc_to under an uneven FP scale
#include "gantry/core/bounded.hpp"            // kMaxCoordinate
#include "gantry/core/file_problem.hpp"       // shown_path
#include "gantry/core/text_file.hpp"          // write_file_atomically
#include "gantry/cuts/passes.hpp"             // tabs on plain moves
#include "gantry/settings/profiles.hpp"       // shipped_profiles_holding
#include "interp_private.hpp"                 // Interpreter's frames, GatedSink

namespace gantry {

// ---- CommandContext -------------------------------------------------------------------

namespace {

// "; it is outside the table of profile 'shopbot-desktop' (24 x 18 x 5.5 in); it fits:
// prsalpha-48x96, ..." for a soft-limit message (the table: X by Y by Z's height above 0): the
// shipped profiles in the same units whose soft limits hold the point's X, Y and Z. "" when no
// profile is named.
std::string other_tables(const std::string& profile, const Settings& s, const Vec6& table) {
  if (profile.empty()) return "";
  auto span = [&](int i) { return s.axes[i].max - s.axes[i].min; };
  std::string fits;
  for (const std::string& name : shipped_profiles_holding(table, s.units))
    if (name != profile) fits += (fits.empty() ? "" : ", ") + name;
  return fmt::format("; it is outside the table of profile '{}' ({:g} x {:g} x {:g} {}); {}",
                     profile, span(0), span(1), s.axes[2].max, units_name(s.units),
                     fits.empty() ? "no shipped profile's table holds it"
                                  : "it fits: " + fits + " (--profile NAME)");
}

// An arc runs as chords within the profile's chord tolerance: an absurd one (G2 ... P1e12, a
// circle beyond any table) would need more than memory holds, or time allows.
void check_chords(const CanonMove& arc, double tolerance, const SourceLoc& loc) {
  const double n = arc_chord_count(arc, tolerance);
  if (n > kMaxArcChords)
    fail(loc, fmt::format("this arc would run as {} chords within planner.chord_tolerance; an arc "
                          "may have at most {}: give fewer turns or a smaller radius",
                          format_number(n), format_number(kMaxArcChords)));
}

}  // namespace

void CommandContext::check_reach(const Vec6& point, const SourceLoc& loc) const {
  check_working(transform_.to_machine(point), loc);
}

void CommandContext::check_working(const Vec6& target, const SourceLoc& loc) const {
  // Soft limits are the table's envelope, in table base coordinates (VO's offset included:
  // it is where the tool really goes).
  const Vec6 table = target + state_.zero + state_.tool_offset;
  const Vec6 now = state_.position + state_.zero + state_.applied_offset;
  // homing.require's flags; C3's macro (the shipped C3.sbp homes with probes and moves) is
  // how they are cleared, so its moves are not refused.
  std::uint32_t to_home = interp_ ? interp_->gated_sink_->axes_to_home() : 0;
  if (to_home && std::any_of(interp_->frames_.begin(), interp_->frames_.end(),
                             [](const auto& f) { return f.call.homing; }))
    to_home = 0;
  // Nearly every move passes: one pass over the axes says so, with a bound stricter than the
  // checks below (every axis finite and within kMaxCoordinate, moving or not), which then
  // find the first problem, in their order, only when there may be one.
  bool pass = to_home == 0;
  for (int i = 0; pass && i < kAxisCount; ++i)
    pass = std::abs(table[i]) <= kMaxCoordinate &&
           (table[i] == now[i] || !settings_.machine.limit_checking ||
            (table[i] >= settings_.axes[i].min && table[i] <= settings_.axes[i].max));
  if (pass) return;
  const char* unit = units_name(settings_.units);
  for (int i = 0; i < kAxisCount; ++i)
    if ((to_home >> i & 1u) && table[i] != now[i])
      fail(loc, fmt::format("{} must be homed before it moves again: an E-stop or a card fault "
                            "stopped the machine mid-motion (homing.require in the profile); "
                            "home it (C3, or G28 {}), or type `confirm` if the tool is where the "
                            "readout says; nothing was moved",
                            static_cast<char>(std::toupper(kAxisLetters[i])),
                            static_cast<char>(std::toupper(kAxisLetters[i]))));
  for (int i = 0; settings_.machine.limit_checking && i < kAxisCount; ++i) {
    if (table[i] == now[i]) continue;  // only axes that move are checked
    const AxisSettings& ax = settings_.axes[i];
    if (!std::isfinite(table[i]) || table[i] < ax.min || table[i] > ax.max) {
      const char letter = axis_name(settings_, i);
      const std::string base =
          table[i] == target[i] ? "" : fmt::format(" (table base {}={:.4f})", letter, table[i]);
      fail(loc,
           fmt::format(
               "move to {}={:.4f}{} is outside the soft limits {:.4f} to {:.4f} {} "
               "(axes.{}.min/max in the profile); nothing was moved{}",
               letter, target[i], base, ax.min, ax.max, unit, kAxisLetters[i],
               interp_ ? other_tables(interp_->options().profile_name, settings_, table) : ""));
    }
  }
  if (!std::isfinite(table.sum()))
    fail(loc, "a move target is not a finite number; nothing was moved");
  for (int i = 0; i < kAxisCount; ++i)  // soft limits or not: a sane bound
    if (std::abs(table[i]) > kMaxCoordinate && table[i] != now[i])
      fail(loc,
           fmt::format("move to {}={} is out of range: no axis may go beyond {} {} from "
                       "the table base; nothing was moved",
                       static_cast<char>(std::toupper(kAxisLetters[i])), format_number(target[i]),
                       format_number(kMaxCoordinate), units_name(settings_.units)));
}

// WinCNC's softlim B1 (every axis: "adjust the target position to the boundary") and V1
// (vertical axes: adjusted "and no error message is generated"). Only straight moves are
// clamped (an arc cut short is no longer an arc: it is refused as before); the file's
// location is then the clamped point, so the moves after it go on from where the tool is.
void CommandContext::clamp_to_soft_limits(Vec6& target, const SourceLoc& loc) {
  const SoftClamp mode = settings_.limits.soft_clamp;
  if (mode == SoftClamp::Off || !settings_.machine.limit_checking) return;
  const Vec6 shift = state_.zero + state_.tool_offset;  // machine target -> table base
  const Vec6 now = state_.position + state_.zero + state_.applied_offset;
  std::string clamped;
  for (int i = 0; i < kAxisCount; ++i) {
    if (mode == SoftClamp::Vertical && i != 2) continue;
    const double table = target[i] + shift[i];
    if (!std::isfinite(table) || table == now[i]) continue;
    const AxisSettings& ax = settings_.axes[i];
    const double at = std::clamp(table, ax.min, ax.max);
    if (at == table) continue;
    clamped +=
        fmt::format("{}{}={:.4f} to {:.4f}", clamped.empty() ? "" : ", ",
                    static_cast<char>(std::toupper(kAxisLetters[i])), target[i], at - shift[i]);
    target[i] = at - shift[i];
  }
  if (!clamped.empty() && mode == SoftClamp::All && !std::exchange(soft_clamp_warned_, true))
    warn(loc, fmt::format("move clamped to the soft limits ({}; limits.soft_clamp = \"all\"); "
                          "later clamps in this run are not told",
                          clamped));
}

void CommandContext::line_to(const Vec6& file_target, SpeedClass cls, const SourceLoc& loc) {
  try {
    Vec6 target = transform_.to_machine(file_target);
    clamp_to_soft_limits(target, loc);
    check_working(target, loc);
    if (tab_move(target, nullptr, cls, loc)) return;
    send_line(target, cls, loc);
  } catch (const GantryError&) {
    assume_reached(file_target);
    throw;
  }
}

void CommandContext::assume_reached(const Vec6& file_target) {
  const Vec6 target = transform_.to_machine(file_target);
  if (!checking_ || !target.allFinite()) return;
  state_.position = target;
  state_.applied_offset = state_.tool_offset;
  end_tab_path();
}

void CommandContext::send_line(const Vec6& target, SpeedClass cls, const SourceLoc& loc) {
  const Vec6 table = target + state_.zero + state_.tool_offset;
  const Vec6 now = state_.position + state_.zero + state_.applied_offset;
  if (table == now) return;  // no motion, no move
  // Only this function writes line_ (and emit, what it sets on every move), so every field a
  // line's move has is set below; kept from move to move, its location takes the same file's
  // name again without a reference count's atomic increment and decrement (a twentieth of
  // checking a file of moves).
  CanonMove& m = line_;
  m.speed_class = cls;
  m.from = now + state_.machine_origin;
  m.to = table + state_.machine_origin;
  state_.applied_offset = state_.tool_offset;
  m.speeds = cls == SpeedClass::Move ? state_.speeds.move : state_.speeds.jog;
  if (const int n = settings_.calibration.step_divider; n > 1)  // VU 15: 1/n of every speed
    for (double* v : {&m.speeds.xy, &m.speeds.z, &m.speeds.a, &m.speeds.b, &m.speeds.c}) *v /= n;
  m.loc = loc;
  if (!state_.preview) emit(m);  // SP: the location changes, no motor moves
  if (target[0] != state_.position[0] || target[1] != state_.position[1])  // for MD's R and L
    state_.last_xy_move = {target[0] - state_.position[0], target[1] - state_.position[1]};
  state_.position = target;
  ++moves_;
}

void CommandContext::arc_to(const Vec6& file_target, double cx, double cy, double sweep,
                            SpeedClass cls, const SourceLoc& loc, ArcPlane plane) {
  try {
    make_arc(file_target, cx, cy, sweep, cls, loc, plane);
  } catch (const GantryError&) {
    assume_reached(file_target);
    throw;
  }
}

void CommandContext::make_arc(const Vec6& file_target, double cx, double cy, double sweep,
                              SpeedClass cls, const SourceLoc& loc, ArcPlane plane) {
  const std::array<int, 3> ax = plane_axes(plane);
  const int u = ax[0], v = ax[1];
  const Vec6 from = position();
  CanonMove arc;  // in file coordinates, for its chords and extreme points
  arc.kind = MoveKind::Arc;
  arc.plane = plane;
  arc.from = from;
  arc.to = file_target;
  arc.center_x = cx;
  arc.center_y = cy;
  arc.sweep = sweep;
  check_chords(arc, settings_.planner.chord_tolerance, loc);
  if (transform_.scale[u] != transform_.scale[v] ||
      (plane != ArcPlane::XY && (state_.tabs_on || file_tabs_))) {
    // Scaling maps a chord of the circle to the chord of its image, and the chord's gap to
    // the arc grows by at most the larger scale: chords within tolerance / that scale.
    const double scale = std::max({transform_.scale[u], transform_.scale[v], 1.0});
    const std::vector<Vec6> chords = arc_chords(arc, settings_.planner.chord_tolerance / scale);
    for (const Vec6& p : chords) check_reach(p, loc);
    for (const Vec6& p : chords) line_to(p, cls, loc);
    return;
  }
  check_reach(file_target, loc);
  const double r = std::hypot(from[u] - cx, from[v] - cy);
  const double a0 = std::atan2(from[v] - cy, from[u] - cx);
  for (double k = std::floor(std::min(a0, a0 + sweep) / (M_PI / 2)) + 1;
       k * M_PI / 2 < std::max(a0, a0 + sweep); ++k) {  // where an axis of the plane is extreme
    Vec6 p = from;
    p[u] = cx + r * std::cos(k * M_PI / 2);
    p[v] = cy + r * std::sin(k * M_PI / 2);
    check_reach(p, loc);
  }
  if (state_.applied_offset != state_.tool_offset) line_to(from, cls, loc);  // VO changed
  const Vec6 target = transform_.to_machine(file_target);
  const std::array<double, 3> working = {transform_.origin[u] + transform_.scale[u] * cx,
                                         transform_.origin[v] + transform_.scale[v] * cy, sweep};
  if (plane == ArcPlane::XY && tab_move(target, &working, cls, loc)) return;
  send_arc(target, working[0], working[1], sweep, cls, loc, plane);
}

void CommandContext::send_arc(const Vec6& target, double cx, double cy, double sweep,
                              SpeedClass cls, const SourceLoc& loc, ArcPlane plane) {
  const std::array<int, 3> ax = plane_axes(plane);
  const Vec6 shift = state_.zero + state_.tool_offset + state_.machine_origin;
  CanonMove m;
  m.kind = MoveKind::Arc;
  m.plane = plane;
  m.speed_class = cls;
  m.from = state_.position + shift;
  m.to = target + shift;
  m.center_x = cx + shift[ax[0]];
  m.center_y = cy + shift[ax[1]];
  m.sweep = sweep;
  m.speeds = cls == SpeedClass::Move ? state_.speeds.move : state_.speeds.jog;
  if (const int n = settings_.calibration.step_divider; n > 1)  // VU 15, as line_to
    for (double* v : {&m.speeds.xy, &m.speeds.z, &m.speeds.a, &m.speeds.b, &m.speeds.c}) *v /= n;
  m.loc = loc;
  check_chords(m, settings_.planner.chord_tolerance, loc);
  if (!state_.preview) emit(m);
  // MD's R and L turn from the direction of travel at the end: the tangent there.
  const double ex = m.to[0] - m.center_x, ey = m.to[1] - m.center_y;
  if (plane == ArcPlane::XY)
    state_.last_xy_move =
        sweep > 0 ? std::array<double, 2>{-ey, ex} : std::array<double, 2>{ey, -ex};
  else if (target[0] != state_.position[0] || target[1] != state_.position[1])
    state_.last_xy_move = {target[0] - state_.position[0], target[1] - state_.position[1]};
  state_.position = target;
  ++moves_;
}

// Tabs on plain moves (docs/cuts.md, "Tabs on plain moves"): while VB's tabbing or FP's tab
// feature is on, every move at move speed that ends below Safe-Z follows the tab profile
// (VB's sizes) along the distance travelled in XY since the path began. A jog, or a move that
// reaches Safe-Z, ends the path; the next cutting move starts a new series of tabs.
bool CommandContext::tab_move(const Vec6& target, const std::array<double, 3>* arc, SpeedClass cls,
                              const SourceLoc& loc) {
  ModalState& st = state_;
  const CutterSettings& cutter = settings_.cutter;
  const double up = cutter.plunge_negative ? 1.0 : -1.0;
  if (own_tabs_ || !(st.tabs_on || file_tabs_) || cls == SpeedClass::Jog ||
      up * (target[2] - cutter.safe_z) >= 0) {
    if (st.tab_travel != 0 || st.tab_lift != 0) end_tab_path();
    return false;
  }
  const double lift_now = st.tab_lift;
  Vec6 from = st.position;  // where the file has the tool: below the tab it may be on
  from[2] -= lift_now;
  cuts::Piece piece;
  piece.from = cuts::V2(from[0], from[1]);
  piece.to = cuts::V2(target[0], target[1]);
  if (arc) {
    piece.arc = true;
    piece.centre = cuts::V2((*arc)[0], (*arc)[1]);
    piece.sweep = (*arc)[2];
  }
  const double length = piece.length();
  if (!(length > 1e-9)) {  // no travel along the path: the tab's height carries over
    Vec6 lifted = target;
    lifted[2] += lift_now;
    check_working(lifted, loc);
    send_line(lifted, cls, loc);
    return true;
  }
  cuts::TabPlan plan;
  plan.on = true;
  plan.sizes = settings_.tabs;
  plan.first = st.tabs_on && st.first_tab > 0 ? st.first_tab : settings_.tabs.spacing;
  plan.most = st.tabs_on && st.tab_count > 0 ? st.tabs_passed + st.tab_count : 0;
  int ended = 0;
  const cuts::CutPath path =
      cuts::tab_stretch(cuts::V3(st.position[0], st.position[1], st.position[2]), lift_now, piece,
                        target[2], st.tab_travel, plan, up * settings_.tabs.pull_up, &ended);
  // Each part's end: X, Y, Z from the path, the other axes in proportion to the distance.
  std::vector<Vec6> ends;
  cuts::V2 at = piece.from;
  double along = 0;
  for (const cuts::CutMove& m : path.moves) {
    const cuts::V2 to = m.to.head<2>();
    along += m.arc ? (at - m.centre).norm() * std::abs(m.sweep) : (to - at).norm();
    at = to;
    Vec6 p = from + (target - from) * std::min(1.0, along / length);
    p.head<3>() = m.to;
    ends.push_back(p);
  }
  if (!ends.empty()) ends.back().tail<3>() = target.tail<3>();
  for (const Vec6& p : ends) check_working(p, loc);
  for (size_t i = 0; i < ends.size(); ++i) {
    const cuts::CutMove& m = path.moves[i];
    if (m.arc)
      send_arc(ends[i], m.centre.x(), m.centre.y(), m.sweep, cls, loc);
    else
      send_line(ends[i], cls, loc);
  }
  st.tab_travel += length;
  st.tab_lift = std::abs(path.end().z() - target[2]) > 1e-12 ? path.end().z() - target[2] : 0;
  // VB's count: tabs after an ON; a tab counts once the tool is past it.
  if (plan.most > 0 && ended > st.tabs_passed) {
    st.tab_count = std::max(0, st.tab_count - (ended - st.tabs_passed));
    st.tabs_passed = ended;
    if (st.tab_count == 0) st.tabs_on = false;
  }
  return true;
}

void CommandContext::end_tab_path() {
  state_.tab_travel = 0;
  state_.tab_lift = 0;
  state_.tabs_passed = 0;
}

void CommandContext::dwell(double seconds, const SourceLoc& loc) {
  // Checked before anything runs (the check makes the same call): a wait beyond the
  // profile's maximum is a mistake (PAUSE 1e12 would never end), as is a negative one.
  const double most = settings_.machine.max_dwell_s;
  if (!(seconds >= 0 && seconds <= most))
    fail(loc, fmt::format("a wait of {} s is out of range: a part file may wait 0 to {} s "
                          "(machine.max_dwell_s in the profile); give a shorter time, or raise "
                          "the profile's maximum",
                          format_number(seconds), format_number(most)));
  if (seconds == 0 || state_.preview) return;
  CanonMove m = here(MoveKind::Dwell, loc);
  m.dwell_s = seconds;
  emit(m);
  ++moves_;
}

void CommandContext::note_drawing(const SourceLoc& loc) {
  DrawingState d;
  d.cutter_diameter = settings_.cutter.diameter;
  d.tool = state_.gcode.tool;
  d.units = settings_.units;
  d.file_units = file_units_.value_or(settings_.units);
  d.spindle_rpm = state_.spindle_rpm;
  // Told at the top-level file's line: inside a called file (C9's macro, FP), the line that
  // called it, so a preview's report names lines of the file previewed.
  d.line = interp_ && interp_->frames_.size() > 1 ? interp_->frames_[1].called_from.line
                                                  : loc.line;
  if (drawn_ && drawn_->same(d)) return;
  drawn_ = d;
  sink_.drawing_changed(d);
}

void CommandContext::emit(CanonMove& m) {
  note_drawing(m.loc);
  m.resting_channels = resting_channels_;
  m.count = {interp_ ? interp_->statements_executed() : 0, moves_ + 1};
  if (!warned_ && m.kind != MoveKind::Dwell) warn_before_motion(m.loc);
  if (const std::optional<IndependentMotion>& mi = state_.independent) {
    const int i = mi->axis;
    if (m.from[i] != m.to[i] || (m.kind == MoveKind::Arc && plane_axes(m.plane)[2] != i))
      fail(m.loc, fmt::format("this move would move {0}, which MI moves on its own (line {1}); "
                              "nothing was moved. Stop it first with MI, {0}",
                              static_cast<char>(std::toupper(kAxisLetters[i])),
                              state_.independent_loc.line));
    if (std::exchange(independent_resting_, false)) {
      CanonMove start = here(MoveKind::Independent, state_.independent_loc);
      start.independent = *mi;
      sink_.move(start);
    }
  }
  sink_.move(m);
}

void CommandContext::start_independent(const IndependentMotion& m, const SourceLoc& loc) {
  if (state_.preview) return;  // SP: no motor moves
  if (!warned_) warn_before_motion(loc);
  CanonMove start = here(MoveKind::Independent, loc);
  start.independent = m;
  sink_.move(start);
  state_.independent = m;
  state_.independent_loc = loc;
  independent_resting_ = false;
}

void CommandContext::end_independent(const SourceLoc& loc) {
  if (!state_.independent) return;
  sink_.move(here(MoveKind::Independent, loc));  // not running: it comes to rest
  sync();
  state_.independent.reset();
  independent_resting_ = false;
}

// SB3 warns before the tool moves: a flashing light, a beep and switch 4, which drives a
// "machine moving" light on many machines. The tool stays "in motion" until the run ends, so
// only the run's first motion is warned of (a part file once, a typed line each time).
void CommandContext::warn_before_motion(const SourceLoc& loc) {
  warned_ = true;
  if (!options().warn_before_motion) return;
  const int mode = settings_.machine.switch4_mode;
  const std::vector<int>& wired = settings_.outputs.aux_bits;
  if (mode != -4 && !(state_.outputs & 8u) && wired.size() >= 4 && wired[3] >= 0) {
    set_output(4, true, loc);
    switch4_auto_ = true;
  }
  if (settings_.machine.warning_s > 0) {
    CanonMove wait = here(MoveKind::Dwell, loc);
    wait.dwell_s = settings_.machine.warning_s;
    wait.warning = true;
    sink_.move(wait);
  }
}

void CommandContext::end_motion_warning() {
  if (std::exchange(switch4_auto_, false) && (state_.outputs & 8u))
    set_output(4, false, SourceLoc{});
  warned_ = false;
}

std::optional<MotionReport> CommandContext::sync() {
  std::optional<MotionReport> r = interp_->gated_sink_->sync();
  if (state_.independent) {
    independent_resting_ = true;
    if (r) {  // it moved on its own: it is where the pulses left it
      const int i = state_.independent->axis;
      state_.position[i] =
          r->machine[i] - state_.machine_origin[i] - state_.zero[i] - state_.applied_offset[i];
    }
  }
  return r;
}

void CommandContext::zero_axes(unsigned axes) {
  for (int i = 0; i < kAxisCount; ++i)
    if (axes & (1u << i)) {
      state_.zero[i] += state_.position[i];
      state_.position[i] = 0;
    }
}

void CommandContext::set_output(int n, bool on, const SourceLoc& loc) {
  if (state_.preview) return;  // a preview switches nothing
  const int was = spindle_direction();
  const SpindleSettings& sp = settings_.spindle;
  if (on && sp.reverse_wiring == SpindleSettings::ReverseWiring::Run && sp.reverse_output != 0 &&
      spindle_output(n) && was != 0 && spindle_direction() == (n == 1 ? -1 : 1))
    fail(loc, fmt::format("output switch {} would run the spindle {} while it runs {} (the "
                          "profile's spindle.reverse_wiring is \"run\"): stop it first (M5, or "
                          "switch output {} off)",
                          n, n == 1 ? "forward" : "in reverse", n == 1 ? "in reverse" : "forward",
                          n == 1 ? sp.reverse_output : 1));
  // A spindle starting runs at the RPM held (spindle.initial_rpm, or TR's before a run's end
  // set the output to 0): the speed output carries it first.
  if (on && spindle_output(n) && settings_.spindle.speed_output() &&
      speed_sent_ != state_.spindle_rpm) {
    CanonMove speed = here(MoveKind::SpindleSpeed, loc);
    speed.spindle_rpm = state_.spindle_rpm;
    sink_.move(speed);
    speed_sent_ = state_.spindle_rpm;
  }
  CanonMove m = here(MoveKind::Output, loc);
  m.output = n;
  m.output_on = on;
  sink_.move(m);
  const std::uint32_t bit = 1u << (n - 1);
  state_.outputs = on ? state_.outputs | bit : state_.outputs & ~bit;
  if (spindle_output(n)) spindle_settle(was, loc);
}

void CommandContext::set_spindle_speed(double rpm, const SourceLoc& loc, bool quiet) {
  const double was = state_.spindle_rpm;
  state_.spindle_rpm = rpm;
  if (state_.preview) return;  // a preview switches nothing
  note_drawing(loc);
  if (!settings_.spindle.speed_output()) {
    if (!quiet && !std::exchange(spindle_speed_warned_, true))
      warn(loc,
           "TR: this machine's profile has no spindle speed output ([spindle] pwm_bit), so "
           "the spindle runs at the speed set on it; the RPM is only recorded (%(161)). "
           "Said once a run");
    return;
  }
  CanonMove m = here(MoveKind::SpindleSpeed, loc);
  m.spindle_rpm = rpm;
  sink_.move(m);
  speed_sent_ = rpm;
  if (rpm != was && spindle_direction() != 0) wait_at_speed(loc);
}

void CommandContext::come_to_rest(const SourceLoc& loc) {
  if (state_.preview) return;
  sink_.move(here(MoveKind::Stop, loc));
}

CanonMove CommandContext::here(MoveKind kind, const SourceLoc& loc) const {
  CanonMove m;
  m.kind = kind;
  m.from = m.to = state_.machine_origin + state_.zero + state_.position + state_.applied_offset;
  m.loc = loc;
  return m;
}

Settings& CommandContext::change_values(ValueScope scope) {
  if (scope == ValueScope::File && in_file()) {
    Interpreter::Frame& f = interp_->frames_.back();
    if (!f.saved_values) f.saved_values = settings_;
  }
  return settings_;
}

void CommandContext::values_reach_motion(const SourceLoc& loc) {
  come_to_rest(loc);
  sink_.settings_changed(settings_);
  independent_resting_ = state_.independent.has_value();  // the stream came to rest
}

void CommandContext::make_values_permanent() {
  for (Interpreter::Frame& f : interp_->frames_) {
    f.saved_values.reset();
    f.vs_owned.fill(false);
  }
}

void CommandContext::call_macro(int number, const SourceLoc& loc) {
  interp_->call_macro(number, loc);
}

void CommandContext::change_units(Units to, ValueScope scope, const SourceLoc& loc) {
  if (to == settings_.units) return;
  if (scope == ValueScope::File && in_file()) {
    Interpreter::Frame& f = interp_->frames_.back();
    if (!f.saved_units) f.saved_units = settings_.units;
  }
  const std::array<double, kAxisCount> factors = units_scale(settings_, to);
  const Vec6 scale = to_vec6(factors);
  convert_units(settings_, to);
  ModalState& st = state_;
  for (Vec6* v : {&st.position, &st.zero, &st.machine_origin, &st.tool_offset, &st.applied_offset,
                  &st.tool_offset_values})
    *v = v->cwiseProduct(scale);
  st.gcode.scale(scale);
  scale_speeds(st.speeds.move, factors);
  scale_speeds(st.speeds.jog, factors);
  if (st.last_xy_move) {
    (*st.last_xy_move)[0] *= scale[0];
    (*st.last_xy_move)[1] *= scale[1];
  }
  st.tab_travel *= scale[0];
  st.tab_lift *= scale[2];
  if (interp_->start_) interp_->start_->machine = interp_->start_->machine.cwiseProduct(scale);
  // What running files will restore is in the new units too.
  for (Interpreter::Frame& fr : interp_->frames_) {
    scale_speeds(fr.saved_speeds.move, factors);
    scale_speeds(fr.saved_speeds.jog, factors);
    if (fr.saved_values) convert_units(*fr.saved_values, to);
  }
  // The tool stays where it is: the planner and the step generator take the new values.
  values_reach_motion(loc);
}

void CommandContext::end_preview() {
  if (!state_.preview) return;
  const PreviewReturn r = *state_.preview;
  state_.preview.reset();
  state_.position = r.position;
  state_.zero = r.zero;
  state_.machine_origin = r.machine_origin;
  state_.applied_offset = r.applied_offset;
  state_.tool_offset = r.tool_offset;
}

void CommandContext::clear_variables() {
  interp_->vars_.clear();
}

bool CommandContext::in_file() const {
  return !interp_->frames_.empty() && !interp_->frames_.back().call.lines;
}

void CommandContext::set_table_base(unsigned axes, const Vec6& location) {
  for (int i = 0; i < kAxisCount; ++i)
    if (axes & (1u << i)) {
      // The tool stays where it is in the machine's frame; only the numbers change.
      const double machine = state_.machine_origin[i] + state_.zero[i] + state_.position[i];
      state_.zero[i] = location[i] - state_.position[i];
      state_.machine_origin[i] = machine - location[i];
      if (interp_) interp_->gated_sink_->homed(i);  // C3.sbp sets it with VA: homed
    }
}

void CommandContext::home_axis(int axis, double table_base) {
  const double machine = state_.machine_origin[axis] + state_.zero[axis] + state_.position[axis];
  state_.machine_origin[axis] = machine - table_base;
  state_.position[axis] = table_base - state_.zero[axis];
  if (interp_) interp_->gated_sink_->homed(axis);
}

void CommandContext::homing_line(const Vec6& file_target, double speed, const SourceLoc& loc) {
  const SpeedSettings speeds = state_.speeds;
  state_.speeds.move = {speed, speed, speed, speed, speed};
  send_line(transform_.to_machine(file_target), SpeedClass::Move, loc);
  state_.speeds = speeds;
}

std::optional<std::array<bool, 12>> CommandContext::input_switches() {
  sync();
  return interp_->gated_sink_->input_switches();
}

bool CommandContext::probe(const Vec6& file_target, double speed, int input, const SourceLoc& loc,
                           MachineLink::Watching why, bool closing) {
  if (input < 1 || input > 12)
    fail(loc, fmt::format("input switch {} does not exist; inputs are 1 to 12", input));
  if (settings_.inputs.switch_bits[input - 1] < 0)
    fail(loc, fmt::format("input switch {} is not wired in this profile (inputs.switch_bits): a "
                          "probe on it would never stop; nothing moved",
                          input));
  if (!(speed > 0) || !std::isfinite(speed))
    fail(loc, fmt::format("the probing speed must be above 0, not {}", speed));
  if (why == MachineLink::Watching::Probe) check_reach(file_target, loc);
  const Vec6 target = transform_.to_machine(file_target);
  if (state_.preview) {
    send_line(target, SpeedClass::Move, loc);
    return false;
  }
  sync();
  if (const std::optional<std::array<bool, 12>> in = interp_->gated_sink_->input_switches();
      in && (*in)[input - 1] == closing)
    fail(loc, fmt::format("input switch {} is {} already ({}): nothing moved", input,
                          closing ? "closed" : "open",
                          closing ? "the probe is touching: move it clear first"
                                  : "the probe is not touching"));
  // Homing's switch counts once it has read closed in homing.debounce samples in a row
  // (WinCNC's g28_lim_cnt); a probe stops on its first closing.
  const int debounce = why == MachineLink::Watching::Home ? settings_.homing.debounce : 1;
  const std::array<InputTrigger, 1> watch{{{input, closing, false, debounce}}};
  interp_->gated_sink_->watch_inputs(watch, why);
  const Vec6 start = state_.position;
  const SpeedSettings speeds = state_.speeds;
  state_.speeds.move = {speed, speed, speed, speed, speed};
  send_line(target, SpeedClass::Move, loc);
  state_.speeds = speeds;
  const std::optional<MotionReport> r = sync();
  const bool hit = r && r->fired;
  if (!r) interp_->gated_sink_->touched = {{input, closing}};
  if (hit) {
    // It came to rest a little past the point where the switch closed: back there. The
    // axes the probe did not move keep their exact locations.
    auto working = [&](const Vec6& machine) {
      interp_->set_machine_position(machine);
      for (int i = 0; i < kAxisCount; ++i)
        if (target[i] == start[i]) state_.position[i] = start[i];
      return state_.position;
    };
    const Vec6 back = working(r->latched);
    working(r->machine);
    homing_line(transform_.to_file(back), speed, loc);
    sync();
  }
  interp_->arm_inputs();  // the file's ON INPUT handlers again
  return hit;
}

void CommandContext::keypad(std::string_view message, const SourceLoc& loc) {
  if (interp_->io_.keypad(message, loc) == KeypadAnswer::GoOn) return;
  independent_resting_ = state_.independent.has_value();  // it rests while the keypad is open
  if (const std::optional<MotionReport> r = interp_->gated_sink_->keypad(loc))
    interp_->set_machine_position(r->machine);
}

void CommandContext::call_file(const FileCall& call, const SourceLoc& loc) {
  interp_->pending_call_ = call;
  interp_->pending_call_loc_ = loc;
}

void CommandContext::run_typed(std::shared_ptr<const Script> lines, int repetitions,
                               const SourceLoc& loc) {
  FileCall call;
  call.path = *lines->name();
  call.resolved = true;  // not a file FE should open next
  call.repetitions = repetitions;
  call.lines = std::move(lines);
  call_file(call, loc);
}

SourceLoc& CommandContext::last_stop() {
  return interp_->last_stop_;
}

CommandRecorder& CommandContext::recorder() {
  return interp_->recorder_;
}

void CommandContext::speed_set(SpeedClass cls, int group, bool by_values) {
  const int i = (cls == SpeedClass::Jog ? 5 : 0) + group;
  if (!in_file()) {  // typed lines (RP, RR, SI) set speeds for good: no file end undoes them
    for (Interpreter::Frame& f : interp_->frames_) f.vs_owned[i] = false;
    return;
  }
  interp_->frames_.back().vs_owned[i] = by_values;
}

void CommandContext::print(std::string_view text) {
  interp_->io_.print(text);
}

void CommandContext::warn(const SourceLoc& loc, std::string message) {
  interp_->io_.warn({loc, Severity::Warning, std::move(message)});
}

std::string CommandContext::write_file(const std::string& name, std::string_view text,
                                       const SourceLoc& loc) {
  const std::string path = interp_->writable_path(name, loc);
  auto canonical = [](const std::string& p) {  // "" when it cannot be resolved
    std::error_code ec;
    std::filesystem::path c = std::filesystem::weakly_canonical(p, ec);
    return ec ? std::filesystem::path() : c;
  };
  const std::filesystem::path target = canonical(path);
  for (const Interpreter::Frame& f : interp_->frames_)
    if (f.script->name() && !target.empty() && canonical(*f.script->name()) == target)
      fail(loc, fmt::format("{} is running; a command cannot rewrite a running part file", path));
  interp_->forget_called(path);
  if (dynamic_cast<DiskFileSystem*>(interp_->files_system_)) {
    if (std::string why; !write_file_atomically(path, text, &why))
      fail(loc, fmt::format("could not write {} ({}); the previous file is kept", path, why));
    return path;
  }
  std::shared_ptr<std::ostream> out = interp_->files_system_->open_write(path, false);
  if (!out) fail(loc, fmt::format("cannot open {} for writing", path));
  out->write(text.data(), static_cast<std::streamsize>(text.size()));
  out->flush();
  if (!*out) fail(loc, fmt::format("could not write {}", path));
  return path;
}

FileSystem& CommandContext::file_system() {
  return *interp_->files_system_;
}

bool CommandContext::writes_to_disk() const {
  return dynamic_cast<DiskFileSystem*>(interp_->files_system_) != nullptr;
}

std::optional<std::string> CommandContext::read_file(const std::string& name, const SourceLoc& loc,
                                                     std::string* path) {
  const std::string p = interp_->existing_file(name, loc);
  if (path) *path = p;
  // A missing file is the caller's to explain; a folder, a FIFO, a path too long are not.
  if (const std::string why = interp_->files_system_->read_problem(p); why == kNoSuchFile)
    return std::nullopt;
  else if (!why.empty())
    fail(loc, fmt::format("cannot read {}: {}", shown_path(p), why));
  std::shared_ptr<std::istream> in = interp_->files_system_->open_read(p);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in->rdbuf();
  return text.str();
}

std::vector<std::pair<std::string, Value>> CommandContext::variables() const {
  std::vector<std::pair<std::string, Value>> out(interp_->vars_.begin(), interp_->vars_.end());
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

void CommandContext::set_variable(const std::string& upper_name, Value v) {
  interp_->vars_[upper_name] = std::move(v);
}

const std::string& CommandContext::parts_folder() const {
  return interp_->parts_dir_;
}

const std::string& CommandContext::parts_mask() const {
  return interp_->parts_mask_;
}

void CommandContext::set_parts_folder(std::string folder, std::string mask) {
  interp_->parts_dir_ = std::move(folder);
  interp_->parts_mask_ = std::move(mask);
}

std::string CommandContext::top_folder() const {
  const auto& frames = interp_->frames_;
  if (frames.empty() || !frames.front().script->name()) return "";
  return std::filesystem::path(*frames.front().script->name()).parent_path().string();
}

std::string CommandContext::file_path(const std::string& name, const SourceLoc& loc) const {
  return interp_->file_path(name, loc);
}

std::string CommandContext::reachable_path(const std::string& name, const SourceLoc& loc,
                                           FileAccess access) const {
  const std::string path = interp_->file_path(name, loc);
  interp_->check_reach(path, access, loc);
  return path;
}

bool CommandContext::part_file_running() const {
  const auto& frames = interp_->frames_;
  return std::any_of(frames.begin(), frames.end(), [](const auto& f) { return !f.call.lines; });
}

const std::string& CommandContext::last_file() const {
  return interp_->last_file_;
}

void CommandContext::set_last_file(std::string path) {
  interp_->last_file_ = std::move(path);
}

const InterpreterOptions& CommandContext::options() const {
  return interp_->options_;
}

}  // namespace gantry
