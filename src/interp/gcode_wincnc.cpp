// The WinCNC dialect's own codes (gcode_dialect = "wincnc"; docs/gcode.md, "The WinCNC
// dialect"), from the WinCNC Users Guide (shared seed 003): the head lift of G53 and G0.1,
// G28 of named axes, the M codes for outputs, inputs, run-next/skip-next and tool measuring,
// the L codes, and `{}` substitutions. Every other code the manual lists is refused by name.
#include <fmt/format.h>  // messages

#include <cmath>  // lround, round
#include <string>

#include "gantry/commands/command_table.hpp"  // home_on_switches
#include "gantry/interp/gcode_executor.hpp"
#include "gantry/interp/tool_changer.hpp"  // M37 on a rack, the sensor
#include "gantry/lang/wincnc.hpp"          // evaluate_wincnc_braces
#include "gcode_words.hpp"

namespace gantry {
using namespace gcode;

namespace gcode {

bool wincnc_own_g(int code) {
  switch (code) {
    case 1:    // G0.1 rapid with the heads lifted
    case 50:   // G5 message box
    case 90:   // G9 smoothing
    case 310:  // G31 stop file parsing
    case 500:  // G50-G52.1 scaling and rotation
    case 510:
    case 520:
    case 521:
    case 924:  // G92.4 G92 at two lines' intersection
    case 950:  // G95 rotary feed mode
      return true;
    default:
      return false;
  }
}

bool wincnc_own_m(int code) {
  switch (code) {
    case 110:  // M11-M14 outputs
    case 120:
    case 130:
    case 140:
    case 170:  // M17, M17.1-M17.4: wait for / test an input on
    case 171:
    case 172:
    case 173:
    case 174:
    case 180:  // M18, M18.1-M18.4: off
    case 181:
    case 182:
    case 183:
    case 184:
    case 280:  // M28, M29 limit switches as stops
    case 290:
    case 370:  // M37, M37.1-M37.3 tool measure
    case 371:
    case 372:
    case 373:
    case 991:  // M99.1 abort
      return true;
    default:
      return false;
  }
}

}  // namespace gcode

namespace {

// Why each code the manual lists and Gantry does not run is refused: "TITLE: REASON".
struct Refusal {
  char letter;
  int code;  // x10
  const char* what;
};

constexpr const char* kNoSecondHead = "this machine has one head and one tool changer";
constexpr Refusal kRefused[] = {
    {'G', 50, "G5 (message box) is not supported; use (MSG, text) for a message and M0 to pause"},
    {'G', 90,
     "G9 (smoothing) is not supported; the planner's cornering is the profile's [planner]"},
    {'G', 310,
     "G31 (stop parsing, for homing with M28) is not supported; home with G28 (the profile's "
     "[homing])"},
    {'G', 500, "G50 (scaling/rotation off) is not supported: Gantry has no G-code scaling"},
    {'G', 510, "G51 (scaling) is not supported; scale with OpenSBP's FP proportions"},
    {'G', 520, "G52 (rotation) is not supported; rotate the toolpath in the CAM program"},
    {'G', 521, "G52.1 (rotation to a line) is not supported: Gantry has no stored positions"},
    {'G', 924,
     "G92.4 (G92 at two lines' intersection) is not supported: Gantry has no stored "
     "positions"},
    {'G', 950, "G95 (rotary feed mode) is not supported; give rotary moves their feed in F"},
    {'M', 280,
     "M28 (stop the axis at a limit, for custom homing) is not supported; home with "
     "G28 (the profile's [homing])"},
    {'M', 290,
     "M29 (end the line at a limit, for custom homing) is not supported; home with "
     "G28 (the profile's [homing])"},
    {'M', 372,
     "M37.2 (the second tool measure switch's height, TM2) is not supported: Gantry has one "
     "tool-length sensor (the profile's [toolchanger]); calibrate it with M37.1"},
    {'M', 373,
     "M37.3 (shift the stored tool measures) is not supported: Gantry keeps one "
     "measure per tool; measure again with M37"},
    {'L', 10, "L1 (save an H register) is not supported; use #parameters"},
    {'L', 11, "L1.1 (save the H registers) is not supported; use #parameters"},
    {'L', 12, "L1.2 (load the H registers) is not supported; use #parameters"},
    {'L', 50, "L5 (contouring velocity) is not supported; give F, or set the speeds with VS"},
    {'L', 60, "L6 (acceleration) is not supported: the ramps are the profile's (VR)"},
    {'L', 70, "L7 (acceleration percentage) is not supported: the ramps are the profile's (VR)"},
    {'L', 80, "L8 (backlash compensation on) is not supported: Gantry has none"},
    {'L', 90, "L9 (backlash compensation off) is not supported: Gantry has none"},
    {'L', 100,
     "L10 (cut array) is not supported; repeat the part with OpenSBP's FP, or in the "
     "CAM program"},
    {'L', 110, "L11 (axis mapping) is not supported: the axes are the profile's"},
    {'L', 120, "L12 (head mapping) is not supported: this machine has one head, Z"},
    {'L', 130, "L13 (slaved axes) is not supported: the axes are the profile's"},
    {'L', 200,
     "L20 (soft limits on) is not supported from a file: soft limits are the "
     "profile's (VL, SF)"},
    {'L', 210,
     "L21 (soft limits off) is not supported from a file: soft limits are the "
     "profile's (VL, SF)"},
    {'L', 220, "L22 (low boundaries) is not supported: the soft limits are the profile's"},
    {'L', 221,
     "L22.1 (restore low boundaries) is not supported: the soft limits are the "
     "profile's"},
    {'L', 230, "L23 (high boundaries) is not supported: the soft limits are the profile's"},
    {'L', 231,
     "L23.1 (restore high boundaries) is not supported: the soft limits are the "
     "profile's"},
    {'L', 281, "L28.1 (rotary axis back to 0-360) is not supported"},
    {'L', 300, "L30 (knife mode) is not supported: Gantry drives no tangential knife"},
    {'L', 301, "L30.1 (knife parameters) is not supported: Gantry drives no tangential knife"},
    {'L', 310, "L31 (knife mode off) is not supported: Gantry drives no tangential knife"},
    {'L', 320, "L32 (saw mode) is not supported: Gantry drives no rotating saw"},
    {'L', 330, "L33 (saw mode off) is not supported: Gantry drives no rotating saw"},
    {'L', 340, "L34 (automatic output on feeds) is not supported; switch it with M11/M12"},
    {'L', 350, "L35 (automatic output off) is not supported; switch it with M11/M12"},
    {'L', 360, "L36 (torch height control) is not supported"},
    {'L', 361, "L36.1 (torch auto voltage) is not supported"},
    {'L', 362, "L36.2 (torch auto voltage reset) is not supported"},
    {'L', 370, "L37 (torch height control off) is not supported"},
    {'L', 371, "L37.1 (torch auto voltage off) is not supported"},
    {'L', 380, "L38 (torch on) is not supported; switch the torch's output with M11"},
    {'L', 390, "L39 (torch off) is not supported; switch the torch's output with M12"},
    {'L', 400,
     "L40 (feed override) is not supported from a file: the override is the "
     "operator's"},
    {'L', 410,
     "L41 (run a program) is refused: a part file does not start programs "
     "(docs/security.md)"},
    {'L', 480, "L48 (laser height control) is not supported"},
    {'L', 510, "L51 (D/A output) is not supported; set the spindle speed with S"},
    {'L', 550, "L55 (pump velocity mode) is not supported: Gantry drives no pump"},
    {'L', 560, "L56 (pump purge) is not supported: Gantry drives no pump"},
    {'L', 570, "L57 (pump off) is not supported: Gantry drives no pump"},
    {'L', 580, "L58 (pump off, reverse) is not supported: Gantry drives no pump"},
    {'L', 590, "L59 (pump maximum) is not supported: Gantry drives no pump"},
    {'L', 820, "L82 (probe the surface) is not supported; probe with G38.2 and set Z with G92"},
    {'L', 821, "L82.1 (digitizing surface) is not supported: Gantry does not digitize"},
    {'L', 822, "L82.2 (move the digitizing surface) is not supported: Gantry does not digitize"},
    {'L', 823,
     "L82.3 (calibrate the digitizing probe) is not supported: Gantry does not "
     "digitize"},
    {'L', 830, "L83 (probe depth to SCAN.CSV) is not supported: Gantry does not digitize"},
    {'L', 1010, "L101 (ATC1 tool and register) is not supported; use L110 T or M37 T"},
    {'L', 1020,
     "L102 (ATC2 tool and register) is not supported: this machine has one head and "
     "one tool changer"},
    {'L', 1111,
     "L111.1 (both tool changers) is not supported: this machine has one head and "
     "one tool changer"},
    {'L', 1130, "L113 (spindle speed test) is not supported"},
    {'L', 1200,
     "L120 (ATC2 tool) is not supported: this machine has one head and one tool "
     "changer"},
    {'L', 2010, "L201 (signal 201 command) is not supported: Gantry's inputs are the profile's"},
    {'L', 2020, "L202 (signal 202 command) is not supported: Gantry's inputs are the profile's"},
    {'L', 2040, "L204 (activate signals) is not supported: Gantry's inputs are the profile's"},
    {'L', 2050, "L205 (deactivate signals) is not supported: Gantry's inputs are the profile's"},
    {'L', 2100,
     "L210 (alternate low limits) is not supported: the limit switches are the "
     "profile's"},
    {'L', 2101,
     "L210.1 (alternate low limit pin) is not supported: the limit switches are the "
     "profile's"},
    {'L', 2110,
     "L211 (alternate high limits) is not supported: the limit switches are the "
     "profile's"},
    {'L', 2111,
     "L211.1 (alternate high limit pin) is not supported: the limit switches are the "
     "profile's"},
    {'L', 2120, "L212 (primary limits) is not supported: the limit switches are the profile's"},
    {'L', 2130, "L213 (dual axis, main motor) is not supported: the motors are the profile's"},
    {'L', 2140, "L214 (dual axis, second motor) is not supported: the motors are the profile's"},
    {'L', 2150, "L215 (dual axis, both motors) is not supported: the motors are the profile's"},
    {'L', 2490, "L249 (laser power) is not supported: Gantry drives no laser"},
    {'L', 2500, "L250 (vector laser off) is not supported: Gantry drives no laser"},
    {'L', 2510, "L251 (vector laser on) is not supported: Gantry drives no laser"},
    {'L', 2511, "L251.1 (laser dwell) is not supported: Gantry drives no laser"},
    {'L', 2520, "L252 (bitmap engraving) is not supported: Gantry drives no laser"},
    {'L', 2521, "L252.1 (bitmap rotation) is not supported: Gantry drives no laser"},
    {'L', 2530, "L253 (bitmap engraving, 90) is not supported: Gantry drives no laser"},
    {'L', 2531, "L253.1 (bitmap rotation) is not supported: Gantry drives no laser"},
    {'L', 2540, "L254 (bitmap engraving, 180) is not supported: Gantry drives no laser"},
    {'L', 2541, "L254.1 (bitmap rotation) is not supported: Gantry drives no laser"},
    {'L', 2550, "L255 (bitmap engraving, 270) is not supported: Gantry drives no laser"},
    {'L', 2551, "L255.1 (bitmap rotation) is not supported: Gantry drives no laser"},
    {'L', 2560, "L256 (bitmap row offset) is not supported: Gantry drives no laser"},
    {'L', 3000, "L300 (lock an axis) is not supported: a locked axis would silently not move"},
    {'L', 3010, "L301 (unlock an axis) is not supported: Gantry locks no axis"},
    {'L', 4000, "L400 (create a home file) is not supported: Gantry has no home files"},
    {'L', 4010, "L401 (recall positions) is not supported: Gantry has no stored positions"},
    {'L', 4020,
     "L402 (save positions to a file) is not supported: Gantry has no stored "
     "positions"},
    {'L', 5000,
     "L500 (store absolute positions) is not supported: Gantry has no stored "
     "positions"},
    {'L', 5002, "L500.2 (tool library) is not supported; give lengths with G10 L1 or M37"},
    {'L', 5010, "L501 (store local positions) is not supported: Gantry has no stored positions"},
    {'L', 5020, "L502 (viewer material) is not supported; the preview shows the table"},
    {'L', 6000, "L600 (mapping off) is not supported: Gantry has no axis mapping"},
    {'L', 6010, "L601 (mapping on) is not supported: Gantry has no axis mapping"},
    {'L', 6020, "L602 (mapping setup) is not supported: Gantry has no axis mapping"},
    {'L', 6030, "L603 (store a mapping adjustment) is not supported: Gantry has no axis mapping"},
    {'L', 6040, "L604 (move the map axis) is not supported: Gantry has no axis mapping"},
    {'L', 6050, "L605 (store a mapping adjustment) is not supported: Gantry has no axis mapping"},
    {'L', 6060, "L606 (store a mapping point) is not supported: Gantry has no axis mapping"},
    {'L', 8000, "L800 (probe off) is not supported; probe with G38.2"},
    {'L', 8010, "L801 (probe on as a limit) is not supported; probe with G38.2"},
    {'L', 8020, "L802 (scan a rectangle) is not supported: Gantry does not digitize"},
    {'L', 8030, "L803 (scan a rectangle) is not supported: Gantry does not digitize"},
    {'L', 8100, "L810 (scan a slice) is not supported: Gantry does not digitize"},
    {'L', 8200, "L820 (height adjust off) is not supported: Gantry has no height adjustment"},
    {'L', 8210, "L821 (height adjust on) is not supported: Gantry has no height adjustment"},
    {'L', 9010, "L901 (limit debounce) is not supported: the inputs are the profile's"},
};

const char* refusal(char letter, int code) {
  for (const Refusal& r : kRefused)
    if (r.letter == letter && r.code == code) return r.what;
  return nullptr;
}

// `v` as a whole number from `lo` to `hi`, or a located error naming `what`.
int whole(double v, int lo, int hi, const SourceLoc& at, const std::string& what) {
  if (v != std::round(v) || v < lo || v > hi)
    fail(at, fmt::format("{} is {}: it must be a whole number from {} to {}", what,
                         format_number(v), lo, hi));
  return static_cast<int>(v);
}

}  // namespace

// Program coordinates of a table base location given for `axes` (bit 0 X .. 5 C); the other
// axes stay where they are.
Vec6 GcodeExecutor::program_from_table_base(const Vec6& table_base, unsigned axes) const {
  const ModalState& st = ctx_.state();
  Vec6 working = st.position;
  for (int a = 0; a < kAxisCount; ++a)
    if (axes & (1u << a)) working[a] = table_base[a] - st.zero[a];
  Vec6 program = ctx_.transform().to_file(working) - st.gcode.axis_offset;
  program[2] -= st.gcode.tool_length;
  return program;
}

// WinCNC lifts "all vertical heads" (G53 alone, G0.1, L53). Its lift goes up to the top of
// the vertical axis's travel (its soft limit sits 0.1 in below the high limit switch, manual
// "Soft Limit / Boundaries"; L53 raises the heads "as high as possible"): here the top of Z's
// travel, the profile's axes.z.max (table base). A tool already there or higher stays.
void GcodeExecutor::wincnc_lift(const SourceLoc& loc) {
  Vec6 top = Vec6::Zero();
  top[2] = ctx_.settings().axes[2].max;
  const double z = program_from_table_base(top, 1u << 2)[2];
  Vec6 t = program_position();
  if (t[2] >= z) return;
  t[2] = z;
  line(t, SpeedClass::Jog, 0, loc);
}

// G53 X Y Z: a rapid to table base coordinates, no local zero (G92) or tool measure, whatever
// the motion mode (manual, G53); G53 alone lifts the head.
void GcodeExecutor::wincnc_g53(const Words& w, const SourceLoc& loc) {
  if (!w.any_axis()) return wincnc_lift(loc);
  const Vec6 k = axis_scale();
  Vec6 tb = Vec6::Zero();
  unsigned axes = 0;
  for (int a = 0; a < kAxisCount; ++a)
    if (w.has(kAxes[static_cast<size_t>(a)])) {
      tb[a] = w.get(kAxes[static_cast<size_t>(a)]) * k[a];
      axes |= 1u << a;
    }
  line(program_from_table_base(tb, axes), SpeedClass::Jog, 0, loc);
}

// G28 homes the axes named, or every axis when none is (manual, G28 and "Homing": "G28Z homes
// only the Z axis"), in the profile's homing order, as C3 does.
void GcodeExecutor::wincnc_home(const Words& w, const SourceLoc& loc) {
  const std::string& order = ctx_.settings().homing.order;
  std::string only;
  for (char c : kAxes) {
    if (!w.has(c)) continue;
    const char lower = static_cast<char>(c - 'A' + 'a');
    if (order.find(lower) == std::string::npos)  // W: its axis's letter is in the order
      fail(w.at(c, loc),
           fmt::format("G28 {0}: {0} is not in the profile's homing order ([homing] order = "
                       "\"{1}\"{2}), so it has no switch to home on",
                       axis_name(ctx_.settings(), static_cast<int>(kAxes.find(c))), order,
                       axis_name(ctx_.settings(), static_cast<int>(kAxes.find(c))) == 'W'
                           ? fmt::format(", where W is {}", lower)
                           : ""));
    only += lower;
  }
  home_on_switches(ctx_, loc, only);
}

// Which letters are an L code's and which axis words a WinCNC code takes.
void GcodeExecutor::wincnc_words(Words& w, const SourceLoc& loc) {
  if (w.has('L') && w.non_modal != 100) {  // an L code (G10's L stays G10's)
    const double tenths = w.get('L') * 10;
    const int code = static_cast<int>(std::lround(tenths));
    if (std::abs(tenths - code) > 1e-6 || code < 0)
      fail(w.at('L', loc), fmt::format("L{} is not an L code: L codes are whole numbers or have "
                                       "one decimal, as L82.1",
                                       format_number(w.get('L'))));
    w.wl = code;
    w.wl_col = w.column['L' - 'A'];
    w.present &= ~(1u << ('L' - 'A'));
  }
  const bool modifier = w.wl == 900 || w.wl == 910;  // L90/L91 go with the line's motion
  if (w.wl >= 0 && !modifier && w.g[1] >= 0) {
    SourceLoc at = loc;
    at.column = w.wl_col;
    fail(at, w.g[1] == 10 || w.g[1] == 20 || w.g[1] == 30
                 ? fmt::format("L on a G1/G2/G3 line is WinCNC's laser power, and Gantry drives "
                               "no laser; remove L{}",
                               format_number(w.wl / 10.0))
                 : fmt::format("{} and {} in one block: WinCNC runs one command a line",
                               code_name('L', w.wl), code_name('G', w.g[1])));
  }
  if (w.g[8] == 430 && w.has('H'))
    fail(w.at('H', loc), "WinCNC's G43 turns on the length M37 measured; it takes no H");
  if (w.non_modal == 923 && w.any_axis())
    fail(loc, "G92.3 takes no axes: it stores and clears the G92 offsets, or restores them");
  w.wincnc_axes = w.g53 || w.wg >= 0 || w.wm >= 0 || (w.wl >= 0 && !modifier) || w.g[8] >= 0;
  if (w.wincnc_axes && !w.g53 && w.g[1] >= 0 && w.any_axis()) {
    const std::string code = w.wg >= 0   ? code_name('G', w.wg)
                             : w.wm >= 0 ? code_name('M', w.wm)
                             : w.wl >= 0 ? code_name('L', w.wl)
                                         : code_name('G', w.g[8]);
    fail(loc, fmt::format("{} and {} both use the axis words; put them in separate blocks", code,
                          code_name('G', w.g[1])));
  }
}

// {TH1+2}: the manual's variables for this machine; the others are refused by name.
double GcodeExecutor::wincnc_brace(std::string_view text, const SourceLoc& at) const {
  const WinCncVariable lookup = [this](std::string_view name, const SourceLoc& l) -> double {
    const GcodeOffsets& o = ctx_.state().gcode;
    const Vec6 k = axis_scale();
    if (name.size() == 1) {
      const size_t a = kAxes.find(name[0]);
      if (a != std::string_view::npos) {
        const int i = static_cast<int>(a);
        return program_position()[i] / k[i];
      }
    }
    if (name == "TP1") return o.tool;
    if (name == "TN1") return o.tool + 10;
    if (name == "TH1") return o.measured_length / length_scale();
    if (name.size() == 3 && name.substr(0, 2) == "LZ" && name[2] >= '0' && name[2] <= '5') {
      const int i = name[2] - '0';
      return o.axis_offset[i] / k[i];
    }
    if (name == "TP2" || name == "TN2" || name == "TS2" || name == "TH2")
      fail(l, fmt::format("{{{}}} is the second tool changer's: {}", name, kNoSecondHead));
    if (name == "TS1")
      fail(l,
           "{TS1} needs the tool changer's offset (atc1= in WINCNC.INI), which Gantry does "
           "not have; use {TP1}");
    // The tool-length sensor (the profile's [toolchanger]; WinCNC's g37= and M37.1).
    const ToolChangerSettings& tc = ctx_.settings().toolchanger;
    if (name == "TM2" || name == "TMI" || name == "TMJ")
      fail(l, fmt::format("{{{}}} is the second tool measure switch's (g37 I J, M37.2): Gantry "
                          "has one tool-length sensor",
                          name));
    if (name.size() == 3 && name.substr(0, 2) == "TM" && tc.sensor_input == 0)
      fail(l, fmt::format("{{{}}} is the tool measure switch's (g37=, M37.1), and this "
                          "machine's profile has no tool-length sensor (toolchanger.sensor_input)",
                          name));
    const ModalState& st = ctx_.state();
    if (name == "TM1") return (tc.sensor_zero_z - st.zero[2]) / k[2];  // M37.1's height
    if (name == "TMX") return tc.sensor_x / k[0];
    if (name == "TMY") return tc.sensor_y / k[1];
    if (name == "TMD") return (tc.clear_z - tc.sensor_start_z) / k[2];
    if (name == "TMF") return tc.sensor_speed * 60 / length_scale();
    if (name.size() == 3 && name.substr(0, 2) == "TH")
      fail(l, fmt::format("{{{}}} is torch height control's: Gantry has none", name));
    fail(l, fmt::format("{{{}}} is not a variable Gantry knows: it has X Y Z A B C, TP1, TN1, TH1, "
                        "the sensor's TM1 TMX TMY TMD TMF "
                        "and LZ0-LZ5 (WinCNC's CNC.MAC variables are not read)",
                        name));
  };
  return evaluate_wincnc_braces(text, at, &lookup);
}

// G0.1, the M codes M11-M37 and M99.1, and the L codes, in the block (one each at most).
void GcodeExecutor::wincnc_codes(const Words& w, const SourceLoc& loc) {
  ModalState& st = ctx_.state();
  GcodeOffsets& o = st.gcode;
  const Vec6 k = axis_scale();
  auto at_col = [&](int col) {
    SourceLoc l = loc;
    l.column = col;
    return l;
  };
  auto required = [&](char c, const std::string& code, const char* what) {
    if (!w.has(c)) fail(loc, fmt::format("{} needs {}, {}", code, c, what));
    return w.get(c);
  };
  // Axes named by an L code (values ignored): bit 0 X .. 5 C.
  auto named_axes = [&] {
    unsigned axes = 0;
    for (int a = 0; a < kAxisCount; ++a)
      if (w.has(kAxes[static_cast<size_t>(a)])) axes |= 1u << a;
    return axes;
  };

  // A code's axis words are its own: any other one would be a move silently dropped.
  auto only_axes = [&](const std::string& code, std::string_view allowed) {
    for (char c : kAxes)
      if (w.has(c) && allowed.find(c) == std::string_view::npos)
        fail(w.at(c, loc),
             fmt::format("{} does not take {}; put a move on a line of its own", code, c));
  };
  if (w.g[8] >= 0) only_axes(code_name('G', w.g[8]), "Z");

  if (w.wg >= 0) {
    if (const char* why = refusal('G', w.wg)) fail(at_col(w.wg_col), why);
    // G0.1 [X] [Y]: lift the head, rapid in XY, drop it back (manual, G0.1).
    for (char c : std::string_view("ZABC"))
      if (w.has(c)) fail(w.at(c, loc), fmt::format("G0.1 takes X and Y only, not {}", c));
    const double z = program_position()[2];
    wincnc_lift(loc);
    Vec6 t = axis_target(w, program_position(), modes_.incremental);
    line(t, SpeedClass::Jog, 0, loc);
    t[2] = z;
    line(t, SpeedClass::Jog, 0, loc);
  }

  if (w.wm >= 0) {
    const std::string code = code_name('M', w.wm);
    if (const char* why = refusal('M', w.wm)) fail(at_col(w.wm_col), why);
    only_axes(code, w.wm == 370 || w.wm == 371 ? "Z" : "C");
    auto channel = [&](int hi, const char* what) {
      const double c =
          required('C', code, fmt::format("the {} channel, as {} C2", what, code).c_str());
      return whole(c, 1, hi, w.at('C', loc), fmt::format("{} C", code));
    };
    // D: what a check (WinCNC's simulate) takes the input to be (D0 off, the default; D1 on).
    auto simulated = [&] {
      return w.has('D') ? whole(w.get('D'), 0, 1, w.at('D', loc), code + " D") == 1 : false;
    };
    auto input_on = [&](int c) {
      const auto in = ctx_.input_switches();
      return in ? (*in)[static_cast<size_t>(c - 1)] : simulated();
    };
    auto output_on = [&](int c) { return ((st.outputs >> (c - 1)) & 1u) != 0; };
    auto virtual_on = [&](int c) { return ((virtual_inputs_ >> (c - 1)) & 1u) != 0; };
    switch (w.wm) {
      case 110:  // M11 C: output on, M12 off; M13/M14 the same without a stop in WinCNC.
      case 120:  // Gantry switches outputs at rest between moves, as SO does.
      case 130:
      case 140: {
        if (w.has('D'))
          fail(w.at('D', loc), fmt::format("{} D (a drill bank, drillbank= in WINCNC.INI) is not "
                                           "supported; switch each output with C",
                                           code));
        const int c = channel(12, "output");
        ctx_.set_output(c, w.wm == 110 || w.wm == 130, loc);
        break;
      }
      case 170:  // M17 C: wait for input C on; M18 off
      case 180: {
        const int c = channel(12, "input");
        const bool closed = w.wm == 170;
        ctx_.come_to_rest(loc);
        if (auto in = ctx_.input_switches()) {
          // The live machine: short dwells, so time passes on the card and a stop ends it.
          while (in && (*in)[static_cast<size_t>(c - 1)] != closed) {
            ctx_.dwell(0.01, loc);
            in = ctx_.input_switches();
          }
        } else if (!io_.confirm(fmt::format("{}: waiting for input {} to {}; continue when it "
                                            "has",
                                            code, c, closed ? "close" : "open"),
                                loc)) {
          throw OperatorStop(
              {loc, Severity::Error, fmt::format("stopped by the operator at {}", code)});
        }
        break;
      }
      case 171:  // run the next line only if input C is on / off
      case 181: {
        const int c = channel(12, "input");
        ctx_.come_to_rest(loc);
        skip_next_ = input_on(c) != (w.wm == 171);
        break;
      }
      case 172:  // ... if output C is on / off
      case 182: {
        const int c = channel(12, "output");
        skip_next_ = output_on(c) != (w.wm == 172);
        break;
      }
      case 173:  // ... if virtual input C (L60/L61) is on / off
      case 183: {
        const int c = channel(64, "virtual input");
        skip_next_ = virtual_on(c) != (w.wm == 173);
        break;
      }
      case 174:  // ... if C is 1 / 0
      case 184: {
        const double c = required('C', code, "0 or 1");
        const int v = whole(c, 0, 1, w.at('C', loc), code + " C");
        skip_next_ = (v == 1) != (w.wm == 174);
        break;
      }
      case 370: {  // M37: tool measure (manual, M37 and "Tool Length Offset")
        const char tool_letter = w.has('T') ? 'T' : 'H';
        if (w.has('T') && w.has('H'))
          fail(w.at('H', loc), "M37 takes the tool number as T or H, not both");
        if (w.has('O') && w.has('Z'))
          fail(w.at('Z', loc), "M37 takes the length as O or the tip's Z, not both");
        const ToolChangerSettings& tc = ctx_.settings().toolchanger;
        const SourceLoc at = at_col(w.wm_col);
        // Neither O nor Z: the sensor measures it (as G37), where the profile has one.
        const bool by_sensor = !w.has('O') && !w.has('Z');
        if (by_sensor && tc.sensor_input == 0)
          required('Z', code,
                   "what Z reads at the tool's tip now (M37 Z0 with the tip on the table), or "
                   "O, the offset (this machine has no tool-length sensor to measure it on: "
                   "toolchanger.sensor_input)");
        int t = o.tool;
        if (w.has(tool_letter))
          t = whole(w.get(tool_letter), 0, 99999, w.at(tool_letter, loc),
                    fmt::format("M37 {}", tool_letter));
        if (by_sensor && t == 0)
          fail(at,
               "M37: the spindle holds no tool (tool 0) to measure on the sensor; name it "
               "with T, as M37 T1");
        std::optional<Vec6> start;  // where a rack's change began: the machine goes back
        if (t != o.tool && tc.rack()) {
          // A rack: the change is M6's sequence (docs/hardware.md, "Tool changer"). A tip
          // then hangs over the rack, at no known point: Z cannot measure it.
          if (w.has('Z'))
            fail(w.at('Z', loc),
                 fmt::format("M37 T{} Z: the rack changes the tool first, and its tip is then "
                             "at no known point; give O (its length), or neither (the sensor "
                             "measures it), or change with M6 T{}, bring the tip to a known "
                             "point and M37 Z there",
                             t, t));
          check_tool_change(ctx_, o.tool, t, at);  // a change refused moves nothing
          ctx_.come_to_rest(loc);
          start = st.position + st.zero;
          rack_tool_change(ctx_, o.tool, t, at);
        } else if (t != o.tool) {  // no rack: the operator loads it
          ctx_.come_to_rest(loc);
          if (!io_.confirm(by_sensor ? fmt::format("M37: load tool {}, then continue", t)
                                     : fmt::format("M37: load tool {} and bring its tip to "
                                                   "the measuring point, then continue",
                                                   t),
                           loc))
            throw OperatorStop({loc, Severity::Error, "stopped by the operator at M37"});
        }
        o.tool = t;
        selected_tool_ = t;
        if (by_sensor) {
          std::optional<double> length;
          if (start) {
            length = measure_tool(ctx_, t, at);  // checked with the change
            return_from_change(ctx_, (*start)[0], (*start)[1], at);
          } else {
            length = measure_tool_in_spindle(ctx_, "M37", at);
          }
          if (length) o.measured_length = *length;  // a check measures nothing
        } else {
          if (w.has('O')) {
            o.measured_length = w.get('O') * length_scale();
          } else {
            // The tip reads Z (no G92) from now on: file Z - length = Z.
            o.measured_length = ctx_.position()[2] - w.get('Z') * k[2];
          }
          if (ToolEntry* e = o.tool != 0 ? o.tools.change(o.tool) : nullptr)
            e->offset[2] = o.measured_length;  // for L110
          if (start) return_from_change(ctx_, (*start)[0], (*start)[1], at);
        }
        o.tool_length = o.measured_length;  // M37 turns G43 on
        break;
      }
      case 371: {  // M37.1: the sensor's height, TM1 (calibrates G37)
        if (ctx_.settings().toolchanger.sensor_input == 0)
          fail(at_col(w.wm_col),
               "M37.1 sets the tool-length sensor's height (TM1, for G37), and this machine's "
               "profile has none (toolchanger.sensor_input)");
        if (w.has('Z')) {
          // Z: the sensor's top as the tip reads it there (M37's frame: no G92).
          ctx_.change_values(ValueScope::Permanent).toolchanger.sensor_zero_z =
              w.get('Z') * k[2] + st.zero[2];
          break;
        }
        // Alone: the tool in the spindle, its length M37 measured, closes the sensor.
        if (o.measured_length == 0)
          fail(at_col(w.wm_col),
               "M37.1: the tool in the spindle has no measured length: measure it first (M37 "
               "Z0 with its tip on the table), or give the sensor's height, as M37.1 Z1.25");
        const std::optional<double> zero =
            calibrate_sensor(ctx_, o.measured_length, "M37.1", at_col(w.wm_col));
        if (zero) ctx_.change_values(ValueScope::Permanent).toolchanger.sensor_zero_z = *zero;
        break;
      }
      case 991:
        fail(at_col(w.wm_col), "M99.1: the program aborts here (WinCNC's commanded abort)");
      default:
        break;
    }
  }

  if (w.wl >= 0) {
    const std::string code = code_name('L', w.wl);
    const SourceLoc at = at_col(w.wl_col);
    if (const char* why = refusal('L', w.wl)) fail(at, why);
    only_axes(code, w.wl == 30 || w.wl == 40 || w.wl == 280 ? kAxes
                    : w.wl == 600 || w.wl == 610            ? "C"
                    : w.wl == 1110                          ? "A"
                    : w.wl == 900 || w.wl == 910            ? kAxes
                                                            : "");
    switch (w.wl) {
      case 30:  // L3 XYZ: store the axes' positions (values ignored)
        if (!named_axes()) fail(at, "L3 needs the axes to store, as L3 XYZ");
        for (int a = 0; a < kAxisCount; ++a)
          if (named_axes() & (1u << a)) l3_position_[a] = st.position[a] + st.zero[a];
        l3_axes_ |= named_axes();
        return;
      case 40: {  // L4 XYZ: back to L3's positions, at rapid
        const unsigned axes = named_axes();
        if (!axes) fail(at, "L4 needs the axes to return, as L4 XYZ");
        for (int a = 0; a < kAxisCount; ++a)
          if ((axes & (1u << a)) && !(l3_axes_ & (1u << a)))
            fail(w.at(kAxes[static_cast<size_t>(a)], loc),
                 fmt::format("L4 {0}: no position of {0} was stored; store it with L3 {0} first",
                             kAxes[static_cast<size_t>(a)]));
        line(program_from_table_base(l3_position_, axes), SpeedClass::Jog, 0, loc);
        return;
      }
      case 280: {  // L28 X Y: the current position becomes these machine coordinates
        const unsigned axes = named_axes();
        if (!axes) fail(at, "L28 needs the axes to set, as L28 X0 Y0");
        Vec6 tb = Vec6::Zero();
        for (int a = 0; a < kAxisCount; ++a)
          if (axes & (1u << a)) tb[a] = w.get(kAxes[static_cast<size_t>(a)]) * k[a];
        ctx_.set_table_base(axes, tb);
        return;
      }
      case 530:  // L53: raise the heads as high as they go, level: one head here
        return wincnc_lift(loc);
      case 600:  // L60 C / L61 C: virtual input off / on
      case 610: {
        const double c = required('C', code, "the virtual input (1-64)");
        const int n = whole(c, 1, 64, w.at('C', loc), code + " C");
        const std::uint64_t bit = std::uint64_t{1} << (n - 1);
        virtual_inputs_ = w.wl == 610 ? virtual_inputs_ | bit : virtual_inputs_ & ~bit;
        return;
      }
      case 900:  // L90, L91: run() applied them to this block's motion
      case 910:
        return;
      case 920:  // L92: this file's G92 offsets stay when it ends
        if (!file_g92_.empty()) file_g92_.back().keep = true;
        return;
      case 1100: {  // L110 T: the tool in the spindle; its stored measure comes back
        const int t =
            whole(required('T', code, "the tool number"), 0, 99999, w.at('T', loc), "L110 T");
        o.tool = t;
        selected_tool_ = t;
        if (const ToolEntry* e = o.tools.find(t)) {
          o.measured_length = e->length();
          o.tool_length = o.measured_length;
        }
        return;
      }
      case 1110:  // L111 T [A]: run the next line if the tool is T; L112 T: skip it then
      case 1120: {
        const int t =
            whole(required('T', code, "the tool number"), 0, 99999, w.at('T', loc), code + " T");
        if (w.has('A') && w.get('A') == 2)
          fail(w.at('A', loc),
               fmt::format("{} A2 tests the second tool changer: {}", code, kNoSecondHead));
        skip_next_ = (o.tool == t) != (w.wl == 1110);
        return;
      }
      // Accepted with no effect on this machine (manual: they change only WinCNC's screen or
      // its require-home flags, which Gantry does not have).
      case 290:   // L29 clear require-home flags
      case 291:   // L29.1 ignore them
      case 700:   // L70 re-enter the last command
      case 9100:  // L910, L911 G-code line display
      case 9110:
        return;
      default:
        fail(at, fmt::format("{} is not an L code of WinCNC's manual (its \"L Codes\" chapter "
                             "lists them)",
                             code));
    }
  }
}

}  // namespace gantry
