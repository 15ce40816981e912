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
#include "gantry/commands/stroke_font.hpp"    // G16's characters
#include "gantry/core/text.hpp"               // ascii::upper, ascii::lower

namespace gantry {
namespace {

constexpr double kDeg = M_PI / 180;

std::string four_decimals(double v) {
  return fmt::format("{:.4f}", v == 0 ? 0.0 : v);
}

}  // namespace

FmExecutor::FmExecutor(CommandContext& ctx, OperatorIO& io) : ctx_(ctx), io_(io) {
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
  out_path_.reset();
  out_text_.clear();
  in_text_.reset();
  in_pos_ = 0;
  laser_warned_ = analog_warned_ = false;
}

void FmExecutor::end_file(const SourceLoc& loc) {
  if (profile_) ctx_.come_to_rest(loc);
  profile_ = false;
  out_path_.reset();
  in_text_.reset();
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

// ---- outputs ----------------------------------------------------------------------------

void FmExecutor::output(int code, const SourceLoc& loc) {
  const int k = (code - 100) / 2 + 1;
  const bool on = code % 2 == 0;
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
  ctx_.set_output(k, on, loc);
}

// ---- text ---------------------------------------------------------------------------------

std::string FmExecutor::show_text(const FmCommand& c) const {
  std::string out;
  for (const FmShowItem& item : c.items) {
    if (!out.empty()) out += ' ';
    switch (item.kind) {
      case FmShowItem::Kind::Text:
        out += ascii::upper(item.text);
        break;
      case FmShowItem::Kind::Variable:
        out += four_decimals(variable(item.index));
        break;
      case FmShowItem::Kind::String:
        out += ascii::upper(strings_[static_cast<size_t>(item.index)]);
        break;
    }
  }
  return out;
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
  const size_t slash = name.find_last_of("/\\");
  if (name.find('.', slash == std::string::npos ? 0 : slash + 1) == std::string::npos)
    name += ".dat";
  return name;
}

void FmExecutor::write_output(std::string_view text, const SourceLoc& loc) {
  if (!out_path_) fail(loc, "no output file is open: G20 (create) or G21 (append) opens one");
  out_text_ += text;
  ctx_.write_file(*out_path_, out_text_, loc);
}

void FmExecutor::read_values(const FmCommand& c, const FmLine& line, const SourceLoc& loc) {
  if (!in_text_) fail(loc, "no input file is open: G23 opens one");
  const std::string& t = *in_text_;
  if (c.record >= 0) {
    const double r = value(line, c.record, loc);
    if (r != std::trunc(r) || r < 1)
      fail(loc, fmt::format("record {} does not exist: records (lines) count from 1", r));
    size_t at = 0;
    for (long k = 1; k < static_cast<long>(r); ++k) {
      const size_t nl = t.find('\n', at);
      if (nl == std::string::npos)
        fail(loc, fmt::format("{} has no record {}: it has {}", in_path_, r, k));
      at = nl + 1;
    }
    in_pos_ = at;
  }
  for (int target_expr : c.list) {
    const double idx = value(line, target_expr, loc);
    if (idx != std::trunc(idx) || idx < 0 || idx > 99)
      fail(loc, fmt::format("G27 reads into V{}, which does not exist", idx));
    while (in_pos_ < t.size() && std::string_view(" \t\r\n,").find(t[in_pos_]) != std::string::npos)
      ++in_pos_;
    if (in_pos_ >= t.size()) fail(loc, fmt::format("G27 read past the end of {}", in_path_));
    const char* begin = t.c_str() + in_pos_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) {
      const size_t stop = t.find_first_of(" \t\r\n,", in_pos_);
      fail(loc, fmt::format("G27 expected a number in {} and found \"{}\"", in_path_,
                            t.substr(in_pos_, stop == std::string::npos ? stop : stop - in_pos_)));
    }
    in_pos_ += static_cast<size_t>(end - begin);
    assign(static_cast<int>(idx), v, loc);
  }
}

// ---- scribing -----------------------------------------------------------------------------

// The text with its one variable put in (%s @0, %i %f %c V73, printf's width and precision).
std::string fm_scribe_text(std::string_view text, double v73, std::string_view s0,
                           const SourceLoc& loc) {
  const size_t pct = text.find('%');
  if (pct == std::string::npos) return std::string(text);
  if (text.find('%', pct + 1) != std::string::npos)
    fail(loc, "only one variable can be put in a G16 text; use one G16 for each");
  size_t k = pct + 1;
  const size_t flags = k;
  while (k < text.size() && std::string_view("-+ 0#").find(text[k]) != std::string_view::npos) ++k;
  while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) ++k;
  if (k < text.size() && text[k] == '.') {
    ++k;
    while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) ++k;
  }
  if (k >= text.size())
    fail(loc, "% in a G16 text is followed by s, i, f or c (with printf's width and precision)");
  const std::string spec(text.substr(flags, k - flags));
  const char conv = ascii::lower(text[k]);
  std::string value;
  char buf[256];
  switch (conv) {
    case 's':
      value = s0;
      if (!spec.empty()) {
        std::snprintf(buf, sizeof buf, ("%" + spec + "s").c_str(), value.c_str());
        value = buf;
      }
      break;
    case 'i':
    case 'd':
      std::snprintf(buf, sizeof buf, ("%" + spec + "lld").c_str(),
                    static_cast<long long>(std::trunc(v73)));
      value = buf;
      break;
    case 'f':
      if (spec.empty()) {
        value = fmt::format("{}", v73);  // the manual's %f prints 66.55, not 66.550000
      } else {
        std::snprintf(buf, sizeof buf, ("%" + spec + "f").c_str(), v73);
        value = buf;
      }
      break;
    case 'c': {
      const double code = std::trunc(v73);
      if (code < 32 || code > 126)
        fail(loc, fmt::format("%c prints the character whose code is V73, {}: not a printable "
                              "character (32 to 126)",
                              code));
      value = std::string(1, static_cast<char>(code));
      break;
    }
    default:
      fail(loc, fmt::format("%{} is not a G16 variable: %s (@0), %i, %f or %c (V73)", text[k]));
  }
  return std::string(text.substr(0, pct)) + value + std::string(text.substr(k + 1));
}

void FmExecutor::scribe(const FmCommand& c, const SourceLoc& loc) {
  std::string text;
  if (c.has_text) {
    text = c.text;
  } else {
    const std::optional<std::string> a = io_.ask("G16: the text to scribe", "&G16", "", loc);
    if (!a) throw OperatorStop({loc, Severity::Error, "stopped by the operator"});
    text = *a;
  }
  text = fm_scribe_text(text, v_[73], strings_[0], loc);
  for (char& ch : text) {
    if (ch == '_') ch = ' ';
    if (ch == ')') ch = '\n';
    if (ch != '\n' && !StrokeFont::glyph(ch))
      fail(loc, fmt::format("G16 cannot scribe '{}': the font has the printable ASCII "
                            "characters",
                            ch));
  }
  // 1 (G19) high: capitals are the font's kCapHeight tall, and an H is half as wide as it is
  // high (the manual's 2:1); lines are 1.5 heights apart.
  const double h = char_size_ * unit();
  const double ky = h / StrokeFont::kCapHeight;
  const double kx = (h / 2) / StrokeFont::glyph('H')->width;
  const Vec6 start = ctx_.position();
  const std::vector<int>& wired = ctx_.settings().outputs.aux_bits;
  const bool laser = !dry_run_ && !wired.empty() && wired[0] >= 0;
  if (!laser && !dry_run_ && !std::exchange(laser_warned_, true))
    ctx_.warn(loc,
              "G16: this profile wires no output 1 (M100, the Q-switch gate), so the "
              "characters are traced with the laser off");
  auto point = [&](double dx, double dy) {
    const std::array<double, 2> r = rotate(dx, dy);
    Vec6 p = start;
    p[0] += r[0];
    p[1] += r[1];
    return p;
  };
  double pen_x = 0, pen_y = 0;
  for (char ch : text) {
    if (ch == '\n') {
      pen_x = 0;
      pen_y -= 1.5 * h;
      continue;
    }
    const StrokeGlyph* g = StrokeFont::glyph(ch);
    for (const auto& stroke : g->strokes) {
      line_to(point(pen_x + stroke.front()[0] * kx, pen_y + stroke.front()[1] * ky), loc);
      after_move(loc);
      if (laser) ctx_.set_output(1, true, loc);
      for (size_t k = 1; k < stroke.size(); ++k) {
        line_to(point(pen_x + stroke[k][0] * kx, pen_y + stroke[k][1] * ky), loc);
        after_move(loc);
      }
      if (laser) ctx_.set_output(1, false, loc);
    }
    pen_x += StrokeFont::advance(ch) * kx;
  }
  // The stage ends where the next character would start.
  line_to(point(pen_x, pen_y), loc);
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
    case 10: {
      const std::string name = ascii::lower(c.text);
      if (name != "fontfile.txt" && name != "fontfile")
        fail(loc, fmt::format("G10\"{}\": the manual does not give the font file's format, so "
                              "Gantry scribes with its own stroke font (the default "
                              "fontfile.txt) only",
                              c.text));
      return;
    }
    case 16:
      return scribe(c, loc);
    case 19: {
      const double s = value(line, c.expr, loc);
      if (!(s > 0)) fail(loc, fmt::format("G19{}: the character size must be above 0", s));
      char_size_ = s * (metric_ ? 25.4 : 1);
      return;
    }
    case 20:
    case 21: {
      if (out_path_)
        fail(loc, fmt::format("an output file is open already ({}); G22 closes it: one output "
                              "file at a time",
                              *out_path_));
      const std::string name = file_name(c, loc);
      std::string text;
      if (c.code == 21)
        if (std::optional<std::string> old = ctx_.read_file(name, loc)) text = std::move(*old);
      out_text_ = std::move(text);
      out_path_ = name;
      ctx_.write_file(name, out_text_, loc);  // created now (G20: emptied)
      return;
    }
    case 22:
      if (!out_path_) fail(loc, "G22 closes the output file, and none is open");
      out_path_.reset();
      return;
    case 23: {
      if (in_text_)
        fail(loc, fmt::format("an input file is open already ({}); G24 closes it: one input "
                              "file at a time",
                              in_path_));
      const std::string name = file_name(c, loc);
      std::string path;
      std::optional<std::string> text = ctx_.read_file(name, loc, &path);
      if (!text) fail(loc, fmt::format("G23: there is no file {}", path));
      in_text_ = std::move(text);
      in_path_ = name;
      in_pos_ = 0;
      return;
    }
    case 24:
      if (!in_text_) fail(loc, "G24 closes the input file, and none is open");
      in_text_.reset();
      return;
    case 25:
      return write_output(show_text(c) + "\r\n", loc);
    case 26: {
      std::string text;
      for (int e : c.list) text += (text.empty() ? "" : ",") + four_decimals(value(line, e, loc));
      return write_output(text + "\r\n", loc);
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
          io_.ask(prompt, name, str ? "" : four_decimals(variable(c.code)), loc);
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
      io_.print(fmt::format("V{}={}\n", c.code, four_decimals(variable(c.code))));
      return;
    case FmOp::SetString:
      strings_[static_cast<size_t>(c.code)] = c.text;
      return;
    case FmOp::ShowString:
      io_.print(fmt::format("@{}={}\n", c.code, strings_[static_cast<size_t>(c.code)]));
      return;
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
