// Friendly Motion's commands through CommandContext (docs/friendlymotion.md): moves, arcs,
// feeds, modes, the user coordinate system and scaling, variables and strings, outputs, the
// data files and character scribing.
#include "gantry/interp/fm_executor.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // max
#include <cctype>     // isdigit
#include <cmath>      // atan2, hypot, trunc
#include <cstdio>     // snprintf
#include <cstdlib>    // strtod
#include <string>
#include <utility>  // exchange
#include <vector>

#include "gantry/commands/command_table.hpp"  // home_on_switches: M99
#include "gantry/core/text.hpp"               // ascii::upper, ascii::lower
#include "gantry/interp/fm_display.hpp"       // G58, G25
#include "gantry/interp/fm_scribe.hpp"        // G10, G16, G19

namespace gantry {
namespace {

constexpr double kDeg = M_PI / 180;

}  // namespace

FmExecutor::FmExecutor(CommandContext& ctx, OperatorIO& io)
    : ctx_(ctx),
      io_(io),
      // A data file's name is found as OPEN's are: in the parts folder, within the reach.
      data_([&ctx](const std::string& name, FileAccess access, const SourceLoc& loc) {
        return ctx.reachable_path(name, loc, access);
      }) {
  reset();
}

void FmExecutor::begin_file() {
  reset();
  // What a preview draws the file's numbers in (only a Friendly Motion file says).
  ctx_.set_file_units(metric_ ? Units::Millimetres : Units::Inches);
}

void FmExecutor::reset() {
  incremental_ = true;  // "G91 is the default mode on power up"
  clockwise_ = true;
  metric_ = ctx_.settings().units == Units::Millimetres;
  profile_ = dry_run_ = ucs_ = false;
  scale_ = {1, 1};
  origin_ = {0, 0};
  theta_ = 0;
  char_size_ = metric_ ? 25.4 : 1;  // characters 1" high at start
  v_.fill(0);
  for (std::string& s : strings_) s.clear();
  v_[75] = 1;  // trim: samples averaged, 1 at load
  // The jog values USL.PRM would load: the keypad's step and the profile's speeds.
  const double u = 1 / unit();
  v_[86] = (metric_ ? 0.01 * 25.4 : 0.01);
  v_[87] = (metric_ ? 0.1 * 25.4 : 0.1);
  v_[88] = ctx_.settings().speeds.move.xy * u;
  v_[89] = ctx_.settings().speeds.jog.xy * u;
  data_.close_all();
  laser_warned_ = analog_warned_ = false;
}

void FmExecutor::end_file(const SourceLoc& loc) {
  if (profile_) ctx_.come_to_rest(loc);
  profile_ = false;
  data_.close_all();
}

double FmExecutor::unit() const {
  return units_factor(metric_ ? Units::Millimetres : Units::Inches, ctx_.settings().units);
}

// ---- values -------------------------------------------------------------------------------

double FmExecutor::variable(int n) const {
  const double u = unit();
  const ModalState& st = ctx_.state();
  switch (n) {
    case 91:
      return user_xy()[0] / u;
    case 92:
      return user_xy()[1] / u;
    case 93:
      return ctx_.position()[3] / u;
    case 94:
      return ctx_.position()[4] / u;
    case 95:
    case 96:
      return st.speeds.move.xy / u;
    case 97:
      return st.speeds.move.a / u;
    case 98:
      return st.speeds.move.b / u;
    default:
      return v_[static_cast<size_t>(n)];
  }
}

double FmExecutor::value(const FmLine& line, int expr, const SourceLoc& line_loc) const {
  const FmExpr& e = line.exprs.at(static_cast<size_t>(expr));
  if (const std::optional<double> lit = e.literal()) return *lit;
  double stack[64];
  size_t top = 0;
  auto at = [&](const FmStep& s) { return SourceLoc{line_loc.file, line_loc.line, s.column}; };
  for (const FmStep& s : e.steps) {
    if (top + 1 >= std::size(stack)) fail(at(s), "the expression is too deeply nested");
    using Op = FmStep::Op;
    switch (s.op) {
      case Op::Number:
        stack[top++] = s.number;
        continue;
      case Op::Var:
        stack[top++] = variable(s.index);
        continue;
      case Op::Neg:
        stack[top - 1] = -stack[top - 1];
        continue;
      case Op::Sin:
      case Op::Cos:
      case Op::Tan:
      case Op::Asin:
      case Op::Acos:
      case Op::Atan: {
        double& x = stack[top - 1];
        if ((s.op == Op::Asin || s.op == Op::Acos) && (x < -1 || x > 1))
          fail(at(s), fmt::format("{} of {} is undefined: its value must be -1 to 1",
                                  s.op == Op::Asin ? "ASIN" : "ACOS", x));
        if (s.op == Op::Tan && std::abs(std::fmod(std::abs(x), 180.0) - 90) < 1e-12)
          fail(at(s), fmt::format("TAN of {} degrees is infinite", x));
        x = s.op == Op::Sin    ? std::sin(x * kDeg)
            : s.op == Op::Cos  ? std::cos(x * kDeg)
            : s.op == Op::Tan  ? std::tan(x * kDeg)
            : s.op == Op::Asin ? std::asin(x) / kDeg
            : s.op == Op::Acos ? std::acos(x) / kDeg
                               : std::atan(x) / kDeg;
        // sin 30 is 0.5, cos 90 is 0: the degree's rounding is not the program's.
        if (std::abs(x - std::round(x * 1e12) / 1e12) < 1e-15) x = std::round(x * 1e12) / 1e12;
        continue;
      }
      default:
        break;
    }
    const double b = stack[--top];
    double& a = stack[top - 1];
    switch (s.op) {
      case Op::Add:
        a += b;
        break;
      case Op::Sub:
        a -= b;
        break;
      case Op::Mul:
        a *= b;
        break;
      case Op::Div:
        if (b == 0) fail(at(s), "division by zero");
        a /= b;
        break;
      default: {  // Pow
        const double r = std::pow(a, b);
        if (!std::isfinite(r))
          fail(at(s), fmt::format("{}^{} has no value (a negative number to a fractional power, "
                                  "or too large)",
                                  a, b));
        a = r;
        break;
      }
    }
  }
  return stack[0];
}

void FmExecutor::assign(int n, double v, const SourceLoc& loc) {
  if (n >= 91 && n <= 98)
    fail(loc, fmt::format("V{} is read-only: V91-V94 are the machine's position and V95-V98 its "
                          "speeds (F sets those)",
                          n));
  if (n == 99) fail(loc, "V99 is reserved; use V0 to V90");
  if (!std::isfinite(v)) fail(loc, fmt::format("V{} cannot hold {}", n, v));
  v_[static_cast<size_t>(n)] = v;
}

// ---- coordinates ------------------------------------------------------------------------

std::array<double, 2> FmExecutor::rotate(double x, double y) const {
  if (theta_ == 0) return {x, y};
  const double c = std::cos(theta_), s = std::sin(theta_);
  return {c * x - s * y, s * x + c * y};
}

std::array<double, 2> FmExecutor::to_machine(double x, double y) const {
  const std::array<double, 2> r = rotate(x * scale_[0], y * scale_[1]);
  return {origin_[0] + r[0], origin_[1] + r[1]};
}

std::array<double, 2> FmExecutor::user_xy() const {
  const Vec6 p = ctx_.position();
  const double dx = p[0] - origin_[0], dy = p[1] - origin_[1];
  const double c = std::cos(-theta_), s = std::sin(-theta_);
  const double rx = theta_ == 0 ? dx : c * dx - s * dy, ry = theta_ == 0 ? dy : s * dx + c * dy;
  return {rx / scale_[0], ry / scale_[1]};
}

void FmExecutor::line_to(const Vec6& target, const SourceLoc& loc) {
  ctx_.line_to(target, SpeedClass::Move, loc);
}

void FmExecutor::after_move(const SourceLoc& loc) {
  if (!profile_) ctx_.come_to_rest(loc);
}

void FmExecutor::move(const FmCommand& c, const FmLine& line, const SourceLoc& loc) {
  if (c.i >= 0) return arc(c, line, loc);
  const double u = unit();
  Vec6 target = ctx_.position();
  if (c.axes[0] >= 0 || c.axes[1] >= 0) {
    std::array<double, 2> p = user_xy();
    for (int a = 0; a < 2; ++a)
      if (c.axes[static_cast<size_t>(a)] >= 0) {
        const double v = value(line, c.axes[static_cast<size_t>(a)], loc) * u;
        p[static_cast<size_t>(a)] = incremental_ ? p[static_cast<size_t>(a)] + v : v;
      }
    const std::array<double, 2> m = to_machine(p[0], p[1]);
    // An axis not given stays exactly where it is when nothing turns or scales it.
    target[0] = (c.axes[0] < 0 && !ucs_ && scale_[0] == 1) ? target[0] : m[0];
    target[1] = (c.axes[1] < 0 && !ucs_ && scale_[1] == 1) ? target[1] : m[1];
  }
  for (int a = 2; a < 6; ++a)
    if (c.axes[static_cast<size_t>(a)] >= 0) {
      const double v = value(line, c.axes[static_cast<size_t>(a)], loc) * (a == 5 ? 1 : u);
      target[a] = incremental_ ? target[a] + v : v;
    }
  line_to(target, loc);
  after_move(loc);
}

void FmExecutor::arc(const FmCommand& c, const FmLine& line, const SourceLoc& loc) {
  const double u = unit();
  if (std::abs(std::abs(scale_[0]) - std::abs(scale_[1])) > 1e-12)
    fail(loc, fmt::format("under G68 with X scaled by {} and Y by {} this arc would be an "
                          "ellipse; Gantry's arcs are circular: scale X and Y alike for arcs",
                          scale_[0], scale_[1]));
  const std::array<double, 2> p = user_xy();
  const double ex = value(line, c.axes[0], loc) * u, ey = value(line, c.axes[1], loc) * u;
  const double ix = value(line, c.i, loc) * u, jy = value(line, c.j, loc) * u;
  const std::array<double, 2> end =
      incremental_ ? std::array<double, 2>{p[0] + ex, p[1] + ey} : std::array<double, 2>{ex, ey};
  const std::array<double, 2> centre =
      incremental_ ? std::array<double, 2>{p[0] + ix, p[1] + jy} : std::array<double, 2>{ix, jy};
  const Vec6 start = ctx_.position();
  const std::array<double, 2> e = to_machine(end[0], end[1]);
  const std::array<double, 2> ctr = to_machine(centre[0], centre[1]);
  // A mirror in one axis turns the arc the other way.
  const bool cw = (scale_[0] * scale_[1] < 0) ? !clockwise_ : clockwise_;
  const double r0 = std::hypot(start[0] - ctr[0], start[1] - ctr[1]);
  const double r1 = std::hypot(e[0] - ctr[0], e[1] - ctr[1]);
  const double inch = units_factor(Units::Inches, ctx_.settings().units);
  if (r0 < 1e-6 * inch) fail(loc, "the arc's centre is its start point: check I and J");
  const double tolerance = std::max(0.002 * inch, 0.001 * std::max(r0, r1));
  if (std::abs(r1 - r0) > tolerance)
    fail(loc, fmt::format("the arc's end is {:.4f} from its centre but its start is {:.4f}: "
                          "check X, Y, I and J ({} measures the centre {})",
                          r1 / u, r0 / u, incremental_ ? "G91" : "G90",
                          incremental_ ? "from the start point" : "from ZERO"));
  const bool full = std::hypot(e[0] - start[0], e[1] - start[1]) < 1e-9 * std::max(1.0, inch);
  double sweep =
      std::atan2(e[1] - ctr[1], e[0] - ctr[0]) - std::atan2(start[1] - ctr[1], start[0] - ctr[0]);
  if (full)
    sweep = cw ? -2 * M_PI : 2 * M_PI;
  else if (cw && sweep >= 0)
    sweep -= 2 * M_PI;
  else if (!cw && sweep <= 0)
    sweep += 2 * M_PI;
  int times = 1;
  if (c.repeat >= 0) {
    const double r = value(line, c.repeat, loc);
    if (r != std::trunc(r) || r < 1 || r > 69)
      fail(loc, fmt::format("R{} is not a repeat count: the circle runs R times, 1 to 69 "
                            "(the manual's limit)",
                            r));
    if (!full)
      fail(loc,
           "R repeats circles: this arc does not end where it starts, so running it again "
           "would not follow it");
    times = static_cast<int>(r);
  }
  Vec6 target = start;
  target[0] = full ? start[0] : e[0];
  target[1] = full ? start[1] : e[1];
  for (int k = 0; k < times; ++k) ctx_.arc_to(target, ctr[0], ctr[1], sweep, SpeedClass::Move, loc);
  after_move(loc);
}

void FmExecutor::user_system(char form, const SourceLoc& loc) {
  if (form == 'C') {
    ucs_ = false;
    origin_ = {0, 0};
    theta_ = 0;
    return;
  }
  const double u = unit();
  const std::array<double, 2> o{v_[81] * u, v_[82] * u};
  double theta = v_[85] * kDeg;
  if (form == 'X') {
    const double dx = v_[83] * u - o[0], dy = v_[84] * u - o[1];
    if (std::hypot(dx, dy) < 1e-9)
      fail(loc,
           "G60X: the point on the +X axis (V83, V84) is the origin (V81, V82); teach a "
           "point away from it");
    theta = std::atan2(dy, dx);
  }
  ucs_ = true;
  origin_ = o;
  theta_ = theta;
}

void FmExecutor::units(bool metric) {
  if (metric == metric_) return;
  const double k = units_factor(metric_ ? Units::Millimetres : Units::Inches,
                                metric ? Units::Millimetres : Units::Inches);
  for (int n = 86; n <= 89; ++n) v_[static_cast<size_t>(n)] *= k;
  char_size_ *= k;
  metric_ = metric;
  ctx_.set_file_units(metric ? Units::Millimetres : Units::Inches);
}

// The manual's X-Y feed range, 0.005 to 6 in/s, is its table's: a profile may give its own
// ([friendly_motion] feed_min, feed_max). A feed outside it is an error, as the manual's
// "Minimum/Maximum Allowable Feedrate" says, rather than a silent clamp that would change
// the marking's dose.
void FmExecutor::feed_in_range(double f, const SourceLoc& loc) const {
  const FriendlyMotionSettings& fm = ctx_.settings().friendly_motion;
  const double inch = units_factor(Units::Inches, ctx_.settings().units);
  const double lo = fm.feed_min.value_or(0.005 * inch), hi = fm.feed_max.value_or(6 * inch);
  const double v = f * unit();
  if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) return;
  const double u = unit();
  fail(loc, fmt::format("F{}: the X-Y feed must be {:g} to {:g} {}/s ({}); nothing was set", f,
                        lo / u, hi / u, metric_ ? "mm" : "in",
                        fm.feed_min || fm.feed_max
                            ? "friendly_motion.feed_min and feed_max"
                            : "the manual's range; a profile's [friendly_motion] feed_min and "
                              "feed_max give another"));
}

// ---- outputs ----------------------------------------------------------------------------

int FmExecutor::laser_output() const {
  const int k = ctx_.settings().friendly_motion.laser_output;
  const std::vector<int>& wired = ctx_.settings().outputs.aux_bits;
  return k >= 1 && k <= static_cast<int>(wired.size()) && wired[static_cast<size_t>(k - 1)] >= 0
             ? k
             : 0;
}

void FmExecutor::switch_output(int k, bool on, const SourceLoc& loc) {
  ctx_.set_output(k, on, loc);
  if (k != laser_output()) return;
  const FriendlyMotionSettings& fm = ctx_.settings().friendly_motion;
  const double wait = on ? fm.laser_on_s : fm.laser_off_s;
  if (wait > 0) ctx_.dwell(wait, loc);
}

void FmExecutor::output(int code, const SourceLoc& loc) {
  int k = (code - 100) / 2 + 1;
  const bool on = code % 2 == 0;
  // M100/M101 gate the beam: the output the profile names for it (output 1 unless it says).
  if (k == 1) {
    k = ctx_.settings().friendly_motion.laser_output;
    if (k == 0)
      fail(loc, fmt::format("M{} gates the laser, and this profile names no laser output "
                            "(friendly_motion.laser_output = 0); nothing was switched",
                            code));
  }
  if (k > 12)
    fail(loc, fmt::format("M{} switches output {}, and Gantry has output switches 1 to 12 "
                          "(M100-M123)",
                          code, k));
  const std::vector<int>& wired = ctx_.settings().outputs.aux_bits;
  if (k > static_cast<int>(wired.size()) || wired[static_cast<size_t>(k - 1)] < 0)
    fail(loc, fmt::format("M{} switches output {}, which this profile does not wire "
                          "(outputs.aux_bits); nothing was switched",
                          code, k));
  if (dry_run_) return;  // G43: the moves run, the outputs stay as they are
  switch_output(k, on, loc);
}

// P: the relay matrix wired to output switches ([friendly_motion] relay_a, relay_b). A probe
// is on one bus at a time (on both it would join them), so PA# lets it go from bus B first;
// PD opens every relay. Like M100-M131, the relays switch at rest and stay as they are in G43.
void FmExecutor::relay(const FmCommand& c, const FmLine& line, const SourceLoc& loc) {
  const FriendlyMotionSettings& fm = ctx_.settings().friendly_motion;
  if (fm.relay_a.empty() && fm.relay_b.empty())
    fail(loc,
         "P switches the resistor trimmer's relay matrix (test probes to bus A or B); this "
         "machine's profile wires none ([friendly_motion] relay_a, relay_b), so it cannot be "
         "run");
  auto on = [&](int k) { return k > 0 && ((ctx_.state().outputs >> (k - 1)) & 1u) != 0; };
  if (c.axis == 'D') {
    if (dry_run_) return;
    for (const std::vector<int>* bus : {&fm.relay_a, &fm.relay_b})
      for (int k : *bus)
        if (on(k)) switch_output(k, false, loc);
    return;
  }
  const double p = value(line, c.expr, loc);
  const std::vector<int>& mine = c.axis == 'A' ? fm.relay_a : fm.relay_b;
  const std::vector<int>& other = c.axis == 'A' ? fm.relay_b : fm.relay_a;
  const char* key = c.axis == 'A' ? "relay_a" : "relay_b";
  if (p != std::trunc(p) || p < 1 || p > static_cast<double>(mine.size()) ||
      mine[static_cast<size_t>(p) - 1] == 0)
    fail(loc, fmt::format("P{}{}: test probe {} has no relay to bus {} (friendly_motion.{} "
                          "wires {}); nothing was switched",
                          c.axis, p, p, c.axis, key,
                          mine.empty() ? std::string("no probe")
                                       : fmt::format("probes 1 to {} where not 0", mine.size())));
  const auto n = static_cast<size_t>(p);
  if (dry_run_) return;
  if (n <= other.size() && on(other[n - 1])) switch_output(other[n - 1], false, loc);
  switch_output(mine[n - 1], true, loc);
}

// ---- text ---------------------------------------------------------------------------------

std::string FmExecutor::show_text(const FmCommand& c) const {
  std::vector<FmDisplayItem> items;
  for (const FmShowItem& item : c.items) {
    switch (item.kind) {
      case FmShowItem::Kind::Text:
        items.push_back(FmDisplayItem::quoted(item.text));
        break;
      case FmShowItem::Kind::Variable:
        items.push_back(FmDisplayItem::value(variable(item.index)));
        break;
      case FmShowItem::Kind::String:
        items.push_back(FmDisplayItem::string(strings_[static_cast<size_t>(item.index)]));
        break;
    }
  }
  return fm_display_line(items);
}

// ---- data files ---------------------------------------------------------------------------

std::string FmExecutor::file_name(const FmCommand& c, const SourceLoc& loc) {
  std::string name;
  if (c.string_index >= 0) {
    name = strings_[static_cast<size_t>(c.string_index)];
    if (name.empty())
      fail(loc, fmt::format("@{} is empty: it was to hold the data file's name", c.string_index));
  } else if (c.has_text) {
    name = c.text;
  } else {
    const std::optional<std::string> a = io_.ask(fmt::format("G{}: the data file's name", c.code),
                                                 "&G" + std::to_string(c.code), "", loc);
    if (!a) throw OperatorStop({loc, Severity::Error, "stopped by the operator"});
    name = *a;
    if (name.empty()) fail(loc, "no data file name was given");
  }
  return name;
}

// G27: the record and the values from the file, then each destination's index (V1, VV3,
// V1+2) evaluated in turn, so an index may use a value this G27 has just read.
void FmExecutor::read_values(const FmCommand& c, const FmLine& line, const SourceLoc& loc) {
  std::optional<double> record;
  if (c.record >= 0) record = value(line, c.record, loc);
  const std::vector<double> got = data_.read_values(record, c.list.size(), loc);
  for (size_t k = 0; k < got.size(); ++k) {
    const double idx = value(line, c.list[k], loc);
    if (idx != std::trunc(idx) || idx < 0 || idx > 99)
      fail(loc, fmt::format("G27 reads into V{}, which does not exist", idx));
    assign(static_cast<int>(idx), got[k], loc);
  }
}

// ---- scribing -----------------------------------------------------------------------------

void FmExecutor::scribe(const FmCommand& c, const SourceLoc& loc) {
  std::string text;
  SourceLoc text_loc = loc;
  if (c.has_text) {
    text = c.text;
    if (text_loc.column > 0) text_loc.column += 4;  // after G16"
  } else {
    const std::optional<std::string> a = io_.ask("G16: the text to scribe", "&G16", "", loc);
    if (!a) throw OperatorStop({loc, Severity::Error, "stopped by the operator"});
    text = *a;
    text_loc.column = 0;  // the operator's answer: no column of the file
  }
  // char_size_ is the height in program units; the path is worked in machine units.
  const FmScribePath path =
      fm_scribe(text, v_[73], strings_[0], {char_size_ * unit(), 0.5}, text_loc);
  const Vec6 start = ctx_.position();
  const int beam = laser_output();
  const bool laser = !dry_run_ && beam > 0;
  if (!laser && !dry_run_ && !std::exchange(laser_warned_, true))
    ctx_.warn(loc,
              "G16: this profile wires no laser output (friendly_motion.laser_output, M100's "
              "Q-switch gate), so the characters are traced with the laser off");
  auto point = [&](const FmPoint& d) {
    const std::array<double, 2> r = rotate(d[0], d[1]);
    Vec6 p = start;
    p[0] += r[0];
    p[1] += r[1];
    return p;
  };
  for (const std::vector<FmPoint>& stroke : path.strokes) {
    line_to(point(stroke.front()), loc);
    after_move(loc);
    if (laser) switch_output(beam, true, loc);
    for (size_t k = 1; k < stroke.size(); ++k) {
      line_to(point(stroke[k]), loc);
      after_move(loc);
    }
    if (laser) switch_output(beam, false, loc);
  }
  line_to(point(path.end), loc);  // where the next character would start
  after_move(loc);
}

// ---- commands -----------------------------------------------------------------------------

void FmExecutor::g_code(const FmCommand& c, const FmLine& line, const SourceLoc& loc) {
  switch (c.code) {
    case 0:
      profile_ = false;
      ctx_.come_to_rest(loc);
      return;
    case 2:
    case 3:
      clockwise_ = c.code == 2;
      return;
    case 4: {
      const double s = value(line, c.expr, loc);
      if (s < 0.001) fail(loc, fmt::format("G4X{}: the shortest delay is 0.001 s", s));
      if (c.quick && profile_)
        fail(loc,
             "G4...Q counts the delay while the axes still move; Gantry's motion stream "
             "times a delay only at rest, so it cannot start one mid-motion (leave out Q "
             "to wait at rest)");
      ctx_.dwell(s, loc);
      return;
    }
    case 9:
      profile_ = true;
      return;
    case 10:
      fm_select_font(c.text, loc);
      return;
    case 16:
      return scribe(c, loc);
    case 19: {
      char_size_ = fm_character_height(value(line, c.expr, loc), metric_, loc);
      return;
    }
    case 20:
      data_.create_output(ctx_.file_system(), file_name(c, loc), loc);
      return;
    case 21:
      data_.append_output(ctx_.file_system(), file_name(c, loc), loc);
      return;
    case 22:
      data_.close_output(loc);
      return;
    case 23:
      data_.open_input(ctx_.file_system(), file_name(c, loc), loc);
      return;
    case 24:
      data_.close_input(loc);
      return;
    case 25:
      return data_.write_text(show_text(c), loc);
    case 26: {
      std::vector<double> values;
      for (int e : c.list) values.push_back(value(line, e, loc));
      return data_.write_values(values, loc);
    }
    case 27:
      return read_values(c, line, loc);
    case 43:
    case 44:
      dry_run_ = c.code == 43;
      return;
    case 58:
      io_.print(show_text(c) + "\n");
      return;
    case 60:
      return user_system(c.axis, loc);
    case 68: {
      const double s = value(line, c.expr, loc);
      if (s == 0 || !std::isfinite(s))
        fail(loc, "G68's multiplier cannot be 0: every move would collapse to a point");
      if (c.axis != 'Y') scale_[0] = s;
      if (c.axis != 'X') scale_[1] = s;
      return;
    }
    case 70:
    case 71:
      return units(c.code == 71);
    case 90:
    case 91:
      incremental_ = c.code == 91;
      return;
    default:
      fail(loc, fmt::format("G{} is not run here", c.code));
  }
}

void FmExecutor::m_code(int code, const FmCommand& c, const SourceLoc& loc) {
  if (code >= 100 && code <= 131) return output(code, loc);
  switch (code) {
    case 1:  // reset the motion controller: the motion comes to rest, the profile ends
      profile_ = false;
      ctx_.come_to_rest(loc);
      return;
    case 3:
      ctx_.keypad("M3 manual positioning: jog the table, then continue", loc);
      return;
    case 94:
    case 95: {
      IndependentMotion m;
      m.axis = 5;
      const double speed = ctx_.state().speeds.move.c;
      if (!(speed > 0)) fail(loc, "the C feed (FC) is 0: set it before the free run");
      m.speed = code == 94 ? speed : -speed;
      m.accel = ctx_.settings().axes[5].max_accel;
      if (ctx_.state().independent) ctx_.end_independent(loc);
      ctx_.start_independent(m, loc);
      return;
    }
    case 96:
      if (ctx_.state().independent) ctx_.end_independent(loc);
      ctx_.zero_axes(1u << 5);
      return;
    case 97: {
      Vec6 target = ctx_.position();
      target[5] = std::round(target[5] / 360) * 360;
      line_to(target, loc);
      ctx_.come_to_rest(loc);
      ctx_.zero_axes(1u << 5);
      return;
    }
    case 98: {
      if (ucs_)
        fail(loc,
             "M98 (axis zero) is refused while the user coordinate system is on (G60); "
             "G60C turns it off");
      ctx_.come_to_rest(loc);
      ctx_.zero_axes(c.axis == 'X' ? 1u : c.axis == 'Y' ? 2u : 0x3Fu);
      return;
    }
    case 99: {  // home, and the home position is ZERO; the user coordinates end
      ucs_ = false;
      origin_ = {0, 0};
      theta_ = 0;
      const std::string& order = ctx_.settings().homing.order;
      const std::string only = c.axis == 'X' ? "x" : c.axis == 'Y' ? "y" : "";
      if (!only.empty() && order.find(only) == std::string::npos)
        fail(loc, fmt::format("M99{}: {} is not in the profile's homing order ([homing] order = "
                              "\"{}\"), so it has no switch to home on",
                              c.axis, c.axis, order));
      home_on_switches(ctx_, loc, only);
      ModalState& st = ctx_.state();
      for (char a : only.empty() ? order : only) {
        const size_t i = std::string_view("xyzabc").find(a);
        if (i == std::string_view::npos) continue;
        const int k = static_cast<int>(i);
        const double table_base = st.zero[k] + st.position[k];
        st.zero[k] = ctx_.settings().homing.at[i];
        st.position[k] = table_base - ctx_.settings().homing.at[i];
      }
      return;
    }
    default:
      fail(loc, fmt::format("M{} is not run here", code));
  }
}

void FmExecutor::execute(const FmCommand& c, const FmLine& line, const SourceLoc& loc) {
  switch (c.op) {
    case FmOp::Move:
      return move(c, line, loc);
    case FmOp::Feed: {
      const double f = value(line, c.expr, loc);
      if (!(f > 0)) fail(loc, fmt::format("a feed rate must be above 0, not {}", f));
      if (c.axis != 'C') feed_in_range(f, loc);
      if (c.axis == 'C')
        ctx_.state().speeds.move.c = f;
      else
        ctx_.state().speeds.move.xy = f * unit();
      return;
    }
    case FmOp::G:
      return g_code(c, line, loc);
    case FmOp::M: {
      if (c.expr < 0) return m_code(c.code, c, loc);
      const double m = value(line, c.expr, loc);
      if (m != std::trunc(m) || m < 100 || m > 131)
        fail(loc, fmt::format("M{} is not an output M-function: MV# names M100 to M131", m));
      return output(static_cast<int>(m), loc);
    }
    case FmOp::Assign:
      return assign(c.code, value(line, c.expr, loc), loc);
    case FmOp::Prompt: {
      const bool str = c.axis == '@';
      const std::string name = fmt::format("&{}{}", str ? "@" : "V", c.code);
      const std::string prompt = c.has_text ? c.text : fmt::format("{}{}", str ? "@" : "V", c.code);
      const std::optional<std::string> a =
          io_.ask(prompt, name, str ? "" : fm_number_text(variable(c.code)), loc);
      if (!a) throw OperatorStop({loc, Severity::Error, "stopped by the operator"});
      if (str) {
        strings_[static_cast<size_t>(c.code)] = *a;
        return;
      }
      const std::string t(ascii::trim(*a));
      char* end = nullptr;
      const double v = std::strtod(t.c_str(), &end);
      if (t.empty() || *end != '\0')
        fail(loc, fmt::format("V{} needs a number, and \"{}\" was given", c.code, *a));
      return assign(c.code, v, loc);
    }
    case FmOp::ShowVariable:
      io_.print(fmt::format("V{}={}\n", c.code, fm_number_text(variable(c.code))));
      return;
    case FmOp::SetString:
      strings_[static_cast<size_t>(c.code)] = c.text;
      return;
    case FmOp::ShowString:
      io_.print(fmt::format("@{}={}\n", c.code, strings_[static_cast<size_t>(c.code)]));
      return;
    case FmOp::Relay:
      return relay(c, line, loc);
    case FmOp::Analog:
      value(line, c.expr, loc);
      if (!std::exchange(analog_warned_, true))
        ctx_.warn(loc,
                  "Sf (Q-switch frequency) and SC (lamp current): this machine's profile "
                  "has no analog output for the laser, so the values are only checked");
      return;
    default:
      fail(loc, "this command is run by the interpreter");
  }
}

}  // namespace gantry
