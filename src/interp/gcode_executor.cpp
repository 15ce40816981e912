// G-code's modes and codes, executed through CommandContext (docs/gcode.md).
// A block runs as RS274/NGC says: its values are read, the modal groups and the words are
// checked, then it runs in a fixed order (feed mode, F, S, T, M6, spindle, coolant, dwell,
// plane, units, compensation, tool length, coordinate system, path mode, distance modes,
// retract mode, G10/G28/G30/G92, motion, then M0/M1/M2/M30).
#include "gantry/interp/gcode_executor.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // max
#include <cmath>      // lround, round, sqrt

#include "gcode_cutter_comp.hpp"  // ~unique_ptr<Comp>
#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;
namespace {

// RS274/NGC's modal groups (0: non-modal). -1: not a code Gantry knows.
int g_group(int code) {
  switch (code) {
    case 0:
    case 10:
    case 20:
    case 30:
    case 382:
    case 383:
    case 384:
    case 385:
    case 730:
    case 800:
    case 810:
    case 820:
    case 830:
    case 840:
    case 850:
    case 860:
    case 870:
    case 880:
    case 890:
      return 1;
    case 170:
    case 180:
    case 190:
      return 2;
    case 900:
    case 910:
      return 3;
    case 901:
    case 911:
      return 4;
    case 930:
    case 940:
      return 5;
    case 200:
    case 210:
    case 220:
    case 230:
      return 6;
    case 400:
    case 410:
    case 411:
    case 420:
    case 421:
      return 7;
    case 430:
    case 431:
    case 490:
      return 8;
    case 980:
    case 990:
      return 10;
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
    case 591:
    case 592:
    case 593:
      return 12;
    case 610:
    case 611:
    case 640:
      return 13;
    case 970:  // G97: spindle speed in RPM, the only mode there is
      return 14;
    case 40:
    case 100:
    case 280:
    case 281:
    case 300:
    case 301:
    case 370:  // G37: measure the tool on the tool-length sensor (Fanuc's, WinCNC's g37=)
    case 530:
    case 920:
    case 921:
    case 922:
    case 923:
      return 0;
    default:
      return -1;
  }
}

int m_group(int code) {
  switch (code) {
    case 0:
    case 10:
    case 20:
    case 300:
    case 980:  // M98, M99: the O-word flow runs them (gcode_control_flow.cpp)
    case 981:
    case 990:
      return 4;
    case 60:
    case 610:  // M61: the tool in the spindle, without a change
      return 6;
    case 30:
    case 40:
    case 50:
      return 7;
    case 70:
    case 80:
    case 90:
      return 8;
    case 620:
    case 630:
    case 640:
    case 650:
      return 5;
    default:
      return -1;
  }
}

// The parameter `#[expression] = v` sets: a whole number (within LinuxCNC's 0.0001) that is
// writable, #1 to #5000, as a plain `#n = v` must be.
int indirect_target(double n, const std::string& text, const SourceLoc& at) {
  const double whole = std::round(n);
  if (!std::isfinite(n) || std::abs(n - whole) > 0.0001 || whole < 1 || whole > 5602)
    fail(at, fmt::format("#{} sets #{}, which is not a parameter: parameters are #1 to #5602", text,
                         n));
  if (whole > 5000)
    fail(at, fmt::format("#{} sets #{}, which is read-only: it holds the machine's state; set "
                         "#1 to #5000 or a named #<parameter>",
                         text, whole));
  return static_cast<int>(whole);
}

}  // namespace

GcodeExecutor::GcodeExecutor(CommandContext& ctx, OperatorIO& io, std::function<void()> end)
    : ctx_(ctx), io_(io), end_program_(std::move(end)) {
  begin_file();
  file_g92_.clear();
  set_returned(std::nullopt);
}

void GcodeExecutor::begin_file(bool typed) {
  tool_note_given_ = table_read_ = false;
  file_g92_.push_back({ctx_.state().gcode.axis_offset, typed});
  skip_next_ = false;
  modes_ = Modes{};  // a file gives its own feed rate too
  comp_.reset();     // G40: nothing held back from a run that stopped
  modes_.units = modes_.previous_units = ctx_.settings().units == Units::Millimetres
                                             ? ProgramUnits::Millimetres
                                             : ProgramUnits::Inches;
  modes_.retract_to_r = true;  // G99: LinuxCNC's interpreter starts in it (docs/gcode.md)
  ctx_.set_file_units(std::nullopt);
}

void GcodeExecutor::enter_file(bool restore_g92) {
  file_g92_.push_back({ctx_.state().gcode.axis_offset, !restore_g92});
}

// ---- parameters -------------------------------------------------------------------------

double GcodeExecutor::numbered(int n, const SourceLoc* at) const {
  if (n <= kLastSettable) return params_[static_cast<size_t>(n)];  // first: loops read these
  const ModalState& st = ctx_.state();
  const GcodeOffsets& o = st.gcode;
  const Vec6 k = axis_scale();
  auto axis = [&](const Vec6& v, int base) -> std::optional<double> {
    if (n >= base && n < base + 6) return v[n - base] / k[n - base];
    return std::nullopt;
  };
  if (auto v = axis(probed_, 5061)) return *v;
  if (n == 5070) return probe_hit_ ? 1 : 0;
  if (auto v = axis(o.stored[0], 5161)) return *v;
  if (auto v = axis(o.stored[1], 5181)) return *v;
  if (auto v = axis(o.axis_offset, 5211)) return *v;
  if (n == 5220) return o.system + 1;
  for (int s = 0; s < 9; ++s)
    if (auto v = axis(s == o.system ? st.zero : o.origin[s], 5221 + 20 * s)) return *v;
  if (auto v = tool_parameter(n)) return *v;
  if (n >= 5420 && n < 5426) return axis(current_position(at), 5420).value_or(0);
  return 0;
}

const double* GcodeExecutor::named(std::string_view name) const {
  auto it = named_.find(name);
  return it == named_.end() ? nullptr : &it->second;
}

double GcodeExecutor::value(const GcodeBlock& b, double number, int expr,
                            const SourceLoc& loc) const {
  if (expr < 0) return number;
  const std::string& text = b.exprs[static_cast<size_t>(expr)];
  if (text[0] != '{') return evaluate_gcode_expression(b, expr, loc, *this);
  SourceLoc at = loc;
  at.column = b.exprs_column[static_cast<size_t>(expr)];
  if (ctx_.settings().gcode_dialect != GcodeDialect::WinCNC)
    fail(at,
         "{...} is WinCNC's substitution; it needs gcode_dialect = \"wincnc\" in the "
         "profile (standard G-code writes [expressions] and #parameters)");
  return wincnc_brace(text, at);
}

// ---- reading and checking a block -------------------------------------------------------

void GcodeExecutor::read_words(const GcodeBlock& b, const SourceLoc& loc, Words& w) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  w.g.fill(-1);
  w.m.fill(-1);
  auto value_of = [&](double number, int expr) { return value(b, number, expr, loc); };
  for (const GcodeWord& word : b.words) {
    // The word's location, made only for an error: copying `loc` (its file's shared name)
    // for every word was a tenth of a plain block's time.
    const auto at = [&] {
      SourceLoc l = loc;
      l.column = word.column;
      return l;
    };
    if (word.bare && !wincnc)
      fail(at(), fmt::format("{} needs a value, as in {}1.5 (a bare letter means 0 only in the "
                             "WinCNC dialect)",
                             word.letter, word.letter));
    const double v = word.bare ? 0 : value_of(word.number, word.expr);
    if (!std::isfinite(v))
      fail(at(), fmt::format("the value of {} is not a finite number", word.letter));
    if (word.letter == 'G' || word.letter == 'M') {
      const double tenths = v * 10;
      const int code = static_cast<int>(std::lround(tenths));
      if (std::abs(tenths - code) > 1e-6 || code < 0)
        fail(at(), fmt::format("{}{} is not a code: codes are whole numbers or have one decimal, "
                               "as G38.2",
                               word.letter, v));
      if (wincnc && (word.letter == 'G' ? wincnc_own_g(code) : wincnc_own_m(code))) {
        int& slot = word.letter == 'G' ? w.wg : w.wm;
        if (slot >= 0)
          fail(at(), fmt::format("{} and {} in one block: WinCNC runs one command a line",
                                 code_name(word.letter, slot), code_name(word.letter, code)));
        slot = code;
        (word.letter == 'G' ? w.wg_col : w.wm_col) = word.column;
        continue;
      }
      const int group = word.letter == 'G' ? g_group(code) : m_group(code);
      if (group < 0) fail(at(), unknown_code_message(word.letter, code, wincnc));
      if (word.letter == 'G' && code == 530) {
        w.g53 = true;
        continue;
      }
      int& slot = word.letter == 'G' ? (group == 0 ? w.non_modal : w.g[group]) : w.m[group];
      int& slot_col = word.letter == 'G' ? w.g_col[group] : w.m_col[group];
      // G80 beside a motion (`G00 G17 G20 G40 G49 G80 G90`, a common safety line): LinuxCNC
      // runs the motion, which ends any canned cycle anyway.
      if (word.letter == 'G' && group == 1 && slot >= 0 && (slot == 800) != (code == 800)) {
        if (code != 800) {
          slot = code;
          slot_col = word.column;
        }
        continue;
      }
      if (slot >= 0)
        fail(at(), fmt::format("{} and {} are in the same modal group: a block takes one of them",
                               code_name(word.letter, slot), code_name(word.letter, code)));
      slot = code;
      slot_col = word.column;
      continue;
    }
    // W moves the axis the profile names W (display.w_axis), as its own letter does.
    char letter = word.letter;
    if (letter == 'W') {
      const int w_axis = ctx_.settings().display.w_axis;
      if (w_axis < 0)
        fail(at(),
             "W is the axis of a second vertical head (WinCNC's W), and this machine's "
             "profile names none (display.w_axis): program the cut on Z, or name the W "
             "axis in the profile");
      letter = gcode::kAxes[static_cast<size_t>(w_axis)];
      if (w.has(letter))
        fail(at(), fmt::format("W and {} both name the W axis (display.w_axis); give one of them",
                               letter));
    } else if (w.has(letter) && ctx_.settings().display.w_axis >= 0 &&
               letter == gcode::kAxes[static_cast<size_t>(ctx_.settings().display.w_axis)]) {
      fail(at(),
           fmt::format("W and {} both name the W axis (display.w_axis); give one of them", letter));
    }
    const int i = letter - 'A';
    if (w.has(letter))
      fail(at(), fmt::format("{} appears twice in this block; give each word once", letter));
    w.present |= 1u << i;
    w.value[i] = v;
    w.column[i] = word.column;
  }
  if (wincnc) wincnc_words(w, loc);
  set_parameters(b, loc);
}

void GcodeExecutor::set_parameters(const GcodeBlock& b, const SourceLoc& loc) {
  // Parameters are set once every value of the block has been read (`#1 = 2 #2 = #1` reads
  // the old #1): first every target and value, then the settings.
  if (b.assigns.empty()) return;
  auto value_of = [&](double number, int expr) { return value(b, number, expr, loc); };
  assigned_.clear();
  for (const GcodeAssign& a : b.assigns) {
    const auto at = [&] {
      SourceLoc l = loc;
      l.column = a.column;
      return l;
    };
    const int n =
        a.target_expr >= 0 ? indirect_target(value_of(0, a.target_expr), a.target, at()) : a.param;
    const double v = value_of(a.number, a.expr);
    if (!std::isfinite(v))
      fail(at(), fmt::format("the value given to #{} is not a finite number", a.target));
    assigned_.emplace_back(n, v);
  }
  for (size_t i = 0; i < b.assigns.size(); ++i) {
    const auto [n, v] = assigned_[i];
    if (n > 0) {
      params_[static_cast<size_t>(n)] = v;
      continue;
    }
    const std::string& t = b.assigns[i].target;  // "<name>"
    const std::string_view name = std::string_view(t).substr(1, t.size() - 2);
    if (auto it = named_.find(name); it != named_.end())
      it->second = v;
    else
      named_.emplace(name, v);
  }
}

void GcodeExecutor::check_words(const Words& w, const SourceLoc& loc) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  const int motion = w.g[1] >= 0 ? w.g[1] : modes_.motion;
  auto code_at = [&](int group) {
    SourceLoc l = loc;
    l.column = w.g_col[group];
    return l;
  };
  check_comp_words(w, motion, loc);
  if (w.non_modal == 370)  // G37: the sensor's place and descent are the profile's
    for (char c : kAxes)
      if (w.has(c))
        fail(w.at(c, loc), fmt::format("G37 takes no axis words ({}): the sensor's place and its "
                                       "descent are the profile's [toolchanger]; put a move on "
                                       "a line of its own",
                                       c));
  const bool uses_axes = takes_axis_words(w.non_modal, wincnc) || w.wincnc_axes;
  const bool own_letters = w.own_letters();
  if (w.g[8] == 431 && w.g[1] >= 0 && w.any_axis())
    fail(code_at(8), fmt::format("G43.1 and {} both use the axis words; put G43.1 in a block of "
                                 "its own",
                                 code_name('G', w.g[1])));
  if (w.g[8] == 431)
    for (char c : {'X', 'Y', 'A', 'B', 'C'})
      if (w.has(c))
        fail(w.at(c, loc), fmt::format("G43.1 {}: Gantry's tool length offset is along Z only; "
                                       "give G43.1 Z",
                                       c));
  if (uses_axes && w.g[1] >= 0 && w.any_axis())
    fail(code_at(1), fmt::format("{} and {} both use the axis words; put them in separate "
                                 "blocks",
                                 w.non_modal >= 0 ? code_name('G', w.non_modal)
                                                  : std::string("the WinCNC code"),
                                 code_name('G', w.g[1])));
  if (w.any_axis() && !uses_axes && !w.g431_alone()) {
    if (w.g[1] == 800) fail(code_at(1), "G80 cancels the canned cycle and takes no axis words");
    if (motion < 0) fail(loc, "axis words without a motion mode: give G0, G1, G2 or G3 first");
  }
  const bool arc = (motion == 20 || motion == 30) && w.makes_arc(wincnc);
  const bool moving =
      (w.any_axis() && !uses_axes && !w.g431_alone()) || (w.g[1] >= 0 && is_cycle(w.g[1])) || arc;
  if (is_cycle(motion) && moving) check_cycle_words(w, motion, loc);
  for (char c : {'I', 'J', 'K'})
    if (w.has(c) && !arc && motion != 870 && !own_letters)
      fail(w.at(c, loc),
           fmt::format("{} is an arc's centre offset (or G87's back bore): it needs G2, G3 or "
                       "G87",
                       c));
  if (w.has('R') && !arc && !is_cycle(motion) && w.non_modal != 100 && !own_letters)
    fail(w.at('R', loc),
         "R is an arc's radius or a canned cycle's retract plane: it needs G2, "
         "G3 or G73, G81-G89");
  if (w.has('Q') && !(motion == 730 || motion == 830) && w.m[6] != 610 && w.g[13] != 640 &&
      !own_letters)
    fail(w.at('Q', loc), "Q is the peck depth of G73 and G83");
  if (w.has('H') && w.g[8] != 430 && !own_letters)
    fail(w.at('H', loc), "H names the tool whose length G43 applies");
  const bool m98 = w.m[4] == 980;
  if (w.has('L') && w.non_modal != 100 && !is_cycle(motion) && !m98)
    fail(w.at('L', loc), "L goes with G10, a canned cycle's repeats or M98");
  const bool p_used = w.non_modal == 40 || w.non_modal == 100 || motion == 820 || motion == 860 ||
                      motion == 880 || motion == 890 || arc || w.g[13] == 640 || w.m[5] >= 0 ||
                      own_letters || m98;
  if (w.has('P') && !p_used)
    fail(w.at('P', loc),
         "P goes with G4, G10, G82, G86, G88, G89, G2/G3 (turns), G64, M62-M65 or M98");
  if (m98 && !w.has('P')) fail(loc, "M98 needs P, the number of the O subprogram it calls");
  if (w.non_modal == 40 && !w.has('P') && !wincnc) fail(loc, "G4 needs its time: G4 P seconds");
  if (w.non_modal == 100 && (!w.has('L') || !w.has('P')))
    fail(loc, "G10 needs L (1, 10 or 11 tool table, 2 or 20 coordinate system) and P");
  // G53 moves: with G0 or G1 given, or with axis words in G0 or G1 (LinuxCNC refuses a G53
  // that moves nothing, as `G53 G90 G40`). WinCNC's bare G53 is its own command.
  const int g53_motion = w.g[1] >= 0 ? w.g[1] : (w.any_axis() ? modes_.motion : -1);
  if (w.g53 && (g53_motion > 10 || (g53_motion < 0 && !wincnc)))
    fail(loc,
         "G53 goes with G0 or G1 only: give G0 or G1 and the machine coordinates, as "
         "G53 G0 Z0");
  if (w.g53 && w.any_axis() && (w.g[3] == 910 || (w.g[3] < 0 && modes_.incremental)))
    fail(loc, "G53 takes machine coordinates: it cannot be incremental (G91)");
  if (w.m[5] >= 0 && !w.has('P'))
    fail(loc, fmt::format("{} needs P, the output switch number", code_name('M', w.m[5])));
  if (w.has('F') && w.get('F') < 0)  // a value out of range, not a missing one
    fail(w.at('F', loc), fmt::format("F{} is out of range: a feed rate cannot be negative; give "
                                     "F above 0 (units per minute)",
                                     format_number(w.get('F'))));
  // A feed rate for every feeding move: G1 G2 G3, probes, canned cycles.
  if (moving && motion > 0) {
    const bool inverse = w.g[5] == 930 || (w.g[5] < 0 && modes_.inverse_time);
    const double feed = w.has('F') ? w.get('F') : inverse ? 0 : modes_.feed;
    if (!(feed > 0)) {
      SourceLoc at = code_at(1);
      if (w.g[1] < 0) at = loc;
      fail(at,
           fmt::format("{} needs a feed rate: give F (units per minute){}", code_name('G', motion),
                       inverse ? "; in inverse time (G93) every feeding block needs F" : ""));
    }
  }
}

// ---- units and coordinates --------------------------------------------------------------

double GcodeExecutor::length_scale() const {
  const Units machine = ctx_.settings().units;
  switch (modes_.units) {
    case ProgramUnits::Inches:
      return units_factor(Units::Inches, machine);
    case ProgramUnits::Millimetres:
      return units_factor(Units::Millimetres, machine);
    case ProgramUnits::Centimetres:
      break;
  }
  return 10 * units_factor(Units::Millimetres, machine);
}

Vec6 GcodeExecutor::axis_scale() const {
  const double lin = length_scale();
  Vec6 k;
  k << lin, lin, lin, 1, 1, 1;
  for (int i = 0; i < 3; ++i)
    if (ctx_.settings().display.rotary_units[i] != AxisUnit::Degrees) k[3 + i] = lin;
  return k;
}

Vec6 GcodeExecutor::program_position() const {
  Vec6 p = ctx_.position() - ctx_.state().gcode.axis_offset;
  p[2] -= ctx_.state().gcode.tool_length;
  return p;
}

Vec6 GcodeExecutor::to_file(const Vec6& program) const {
  Vec6 f = program + ctx_.state().gcode.axis_offset;
  f[2] += ctx_.state().gcode.tool_length;
  return f;
}

Vec6 GcodeExecutor::axis_target(const Words& w, const Vec6& from, bool incremental) const {
  const Vec6 k = axis_scale();
  Vec6 t = from;
  for (int a = 0; a < kAxisCount; ++a)
    if (w.has(kAxes[static_cast<size_t>(a)]))
      t[a] = (incremental ? from[a] : 0) + w.get(kAxes[static_cast<size_t>(a)]) * k[a];
  return t;
}

// The path speed of a feeding move, machine units per second.
double GcodeExecutor::feed_for(const Words& w, double length, const SourceLoc& loc) const {
  if (!modes_.inverse_time) return modes_.feed;
  if (!(length > 0)) return modes_.feed > 0 ? modes_.feed : 1;
  (void)loc;
  return length * w.get('F') / 60;  // F: moves per minute
}

// A straight move at `speed` (feed, units/s) or at jog speed; G61 stops after it.
void GcodeExecutor::line(const Vec6& target, SpeedClass cls, double speed, const SourceLoc& loc) {
  line(program_position(), target, cls, speed, loc);
}

void GcodeExecutor::line(const Vec6& from, const Vec6& target, SpeedClass cls, double speed,
                         const SourceLoc& loc) {
  ModalState& st = ctx_.state();
  if (cls == SpeedClass::Jog) {
    ctx_.line_to(to_file(target), cls, loc);
  } else {
    // F is the speed along the path: the groups' speeds are scaled so that the move's
    // nominal path speed (the planner's) is exactly F. With every group at speed 1 that path
    // speed is the length over the largest group's travel (nominal_path_speed), so the groups
    // go at F times that travel over the length.
    const Vec6 d = target - from;
    const double length = d.norm();
    const double largest = std::max({std::sqrt(d[0] * d[0] + d[1] * d[1]), std::abs(d[2]),
                                     std::abs(d[3]), std::abs(d[4]), std::abs(d[5])});
    const double g = length > 0 && largest > 1e-12 * length ? speed * largest / length : speed;
    const GroupSpeeds saved = st.speeds.move;
    st.speeds.move = {g, g, g, g, g};
    try {
      ctx_.line_to(to_file(target), cls, loc);
    } catch (...) {
      st.speeds.move = saved;
      throw;
    }
    st.speeds.move = saved;
  }
  if (modes_.exact_stop) ctx_.come_to_rest(loc);
}

// ---- running a block --------------------------------------------------------------------

void GcodeExecutor::execute(const GcodeBlock& block, const SourceLoc& loc) {
  if (skip_next_ && !block.empty()) {  // WinCNC's M17.1 ... L112 said to skip this one
    skip_next_ = false;
    return;
  }
  if (block.words.empty() && !block.message && !block.bracket)  // `#1 = [#1 + 1]`: the hot path
    return set_parameters(block, loc);
  Words w;
  read_words(block, loc, w);
  check_words(w, loc);
  if (block.message) message(block, loc);
  prompt_ = block.bracket ? &*block.bracket : nullptr;
  run(w, loc);
}

void GcodeExecutor::message(const GcodeBlock& b, const SourceLoc& loc) {
  // (MSG,...) prints its text as written; the others substitute parameters, as LinuxCNC does.
  const std::string text = b.message_kind == GcodeMessage::Msg
                               ? *b.message
                               : substitute_gcode_parameters(*b.message, *this);
  if (b.message_kind == GcodeMessage::Abort) {
    SourceLoc at = loc;
    at.column = b.message_column;
    fail(at, fmt::format("the program stopped itself (ABORT): {}", text));
  }
  ctx_.print(text + "\n");
}

void GcodeExecutor::run(const Words& w, const SourceLoc& loc) {
  const bool wincnc = ctx_.settings().gcode_dialect == GcodeDialect::WinCNC;
  ModalState& st = ctx_.state();
  GcodeOffsets& o = st.gcode;
  if (w.g[5] >= 0) modes_.inverse_time = w.g[5] == 930;
  if (w.has('F') && !modes_.inverse_time) {
    modes_.feed = w.get('F') * length_scale() / 60;
  }
  if (w.has('S') && w.get('S') < 0)
    fail(w.at('S', loc), "S, the spindle speed, cannot be negative");
  tool_change(w, loc);  // T, M6, M61
  if (w.m[7] == 40 && ctx_.settings().spindle.reverse_output == 0)
    ctx_.spindle(-1, loc);  // refused, before anything of the block runs
  // Outputs, dwells and pauses wait for the moves cutter compensation holds back.
  auto output = [&](int n, bool on) {
    deferred([this, n, on, loc] {
      if (((ctx_.state().outputs >> (n - 1)) & 1u) != static_cast<unsigned>(on))
        ctx_.set_output(n, on, loc);
    });
  };
  if (w.has('S')) {  // the speed first, then the spindle starts at it (LinuxCNC's order)
    const double rpm = w.get('S');
    const SpindleSettings& sp = ctx_.settings().spindle;
    if (sp.speed_output() && rpm > sp.max_rpm)
      fail(w.at('S', loc), fmt::format("S{} is faster than this spindle runs ({} RPM, "
                                       "spindle.max_rpm); nothing was changed",
                                       format_number(rpm), format_number(sp.max_rpm)));
    deferred([this, rpm, loc] {
      if (rpm != ctx_.state().spindle_rpm) ctx_.set_spindle_speed(rpm, loc, true);
    });
  }
  if (w.m[7] >= 0) {  // M3 +1, M4 -1, M5 0
    const int direction = w.m[7] == 30 ? 1 : w.m[7] == 40 ? -1 : 0;
    deferred([this, direction, loc] { ctx_.spindle(direction, loc); });
  }
  if (w.m[8] == 70) output(kMistOutput, true);
  if (w.m[8] == 80) output(kFloodOutput, true);
  if (w.m[8] == 90) {
    output(kMistOutput, false);
    output(kFloodOutput, false);
  }
  if (w.m[5] >= 0) {  // M62-M65: output switch P on or off
    const double p = w.get('P');
    if (p != std::round(p) || p < 1 || p > 12)
      fail(w.at('P', loc), fmt::format("output switch {} does not exist; switches are 1 to 12", p));
    const bool on = w.m[5] == 620 || w.m[5] == 640;
    deferred([this, p, on, loc] { ctx_.set_output(static_cast<int>(p), on, loc); });  // as SO
  }
  if (w.non_modal == 40) {  // G4
    if (wincnc) {
      if (!w.has('X')) {
        deferred([this, loc, prompt = prompt_ ? *prompt_ : std::string()] {
          ctx_.come_to_rest(loc);
          // "Place a comment after the dwell to prompt the operator" (manual, G4).
          if (!io_.confirm(!prompt.empty() ? prompt : "G4: press Enter to continue", loc))
            throw OperatorStop({loc, Severity::Error, "stopped by the operator at G4"});
        });
      } else {
        const double x = w.get('X');
        deferred([this, x, loc] { ctx_.dwell(x, loc); });
      }
    } else {
      const double p = w.get('P');
      if (p < 0) fail(w.at('P', loc), "G4's time P cannot be negative");
      deferred([this, p, loc] {
        if (p == 0)
          ctx_.come_to_rest(loc);
        else
          ctx_.dwell(p, loc);
      });
    }
  }
  if (w.g[2] >= 0)
    modes_.plane = w.g[2] == 170 ? ArcPlane::XY : w.g[2] == 180 ? ArcPlane::ZX : ArcPlane::YZ;
  if (w.g[6] >= 0) {
    const ProgramUnits was = modes_.units;
    if (w.g[6] == 200) modes_.units = ProgramUnits::Inches;
    if (w.g[6] == 210)
      modes_.units = wincnc ? ProgramUnits::Centimetres : ProgramUnits::Millimetres;
    if (w.g[6] == 220) {
      if (!wincnc) fail(loc, "G22 is WinCNC's millimetres; in standard G-code G21 is millimetres");
      modes_.units = ProgramUnits::Millimetres;
    }
    if (w.g[6] == 230) {
      if (!wincnc) fail(loc, "G23 (WinCNC: the previous units) is not standard G-code");
      modes_.units = modes_.previous_units;
    }
    if (modes_.units != was) modes_.previous_units = was;
    ctx_.set_file_units(modes_.units == ProgramUnits::Inches ? Units::Inches
                                                             : Units::Millimetres);
  }
  if (w.g[7] >= 0) cutter_comp(w, loc);
  if (w.g[8] == 430 && wincnc) {  // WinCNC: the length the last M37 measured
    o.tool_length = o.measured_length;
  } else if (w.g[8] == 430) {
    tool_length(w, loc);
  } else if (w.g[8] == 431) {
    // Only the offset changes (no motion): the next move reads Z from the new offset. Without
    // Z the offset stays, as in LinuxCNC.
    if (w.has('Z')) o.tool_length = w.get('Z') * length_scale();
  } else if (w.g[8] == 490) {
    o.tool_length = 0;
  }
  if (w.g[12] >= 0) {
    const int code = w.g[12];
    if (wincnc && code != 540)
      fail(SourceLoc{loc.file, loc.line, w.g_col[12]},
           fmt::format("{} selects another head in WinCNC (its g{}= workspace); this machine has "
                       "one head, Z: use G54, and G92 or G92.1 for a local zero",
                       code_name('G', code), code / 10));
    select_system(code <= 590 ? (code - 540) / 10 : 6 + (code - 591));
  }
  if (w.g[13] >= 0) modes_.exact_stop = w.g[13] != 640;
  if (w.g[3] >= 0) modes_.incremental = w.g[3] == 910;
  if (w.g[4] >= 0) modes_.arc_absolute = w.g[4] == 901;
  if (w.g[10] >= 0) modes_.retract_to_r = w.g[10] == 990;
  if (w.non_modal > 40) non_modal(w, w.non_modal, loc);
  // WinCNC's L90/L91: absolute or incremental for this block only.
  const bool incremental = modes_.incremental;
  if (w.wl == 900 || w.wl == 910) modes_.incremental = w.wl == 910;
  if (wincnc) wincnc_codes(w, loc);
  motion(w, loc);
  modes_.incremental = incremental;
  if (w.m[4] == 0) {  // M0
    deferred([this, loc] {
      ctx_.come_to_rest(loc);
      if (!io_.confirm("Paused (M0): continue?", loc))
        throw OperatorStop({loc, Severity::Error, "stopped by the operator at M0"});
    });
  }
  if (w.m[4] == 20 || w.m[4] == 300) end_program(loc);
}

void GcodeExecutor::leave_file() {
  if (file_g92_.empty()) return;
  const FileG92 f = file_g92_.back();
  file_g92_.pop_back();
  // WinCNC restores the G92 offsets a file began with unless it gave L92 (manual, G92, L92).
  if (ctx_.settings().gcode_dialect == GcodeDialect::WinCNC && !f.keep)
    ctx_.state().gcode.axis_offset = f.offset;
}

void GcodeExecutor::end_program(const SourceLoc& loc) {
  end_file(loc);  // compensation ends: its held-back moves go out
  ModalState& st = ctx_.state();
  ctx_.spindle(0, loc);
  for (int n : {kFloodOutput, kMistOutput})
    if ((st.outputs >> (n - 1)) & 1u) ctx_.set_output(n, false, loc);
  select_system(0);
  const ProgramUnits units = modes_.units;
  const double feed = modes_.feed;
  modes_ = Modes{};
  modes_.motion = 10;
  modes_.units = modes_.previous_units = units;
  modes_.feed = feed;
  end_program_();
}

}  // namespace gantry
