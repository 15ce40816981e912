// The settings schema table: each profile key's path, member, kind, range, unit kind and help.
#include "gantry/settings/settings_schema.hpp"

#include <fmt/format.h>  // describe, docs

#include <algorithm>  // find_if
#include <cmath>      // isfinite, fabs
#include <cstdio>     // sscanf
#include <cctype>     // toupper
#include <stdexcept>  // out_of_range

#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

// VR's ramp rates: one range for the profile, the values file and VR (issue 24 resolved the
// drift between the profile's (0, 1e6] and VR's [1e-6, 1e6] to VR's closed range, which the
// command table's inclusive ParamSpec ranges can state).
constexpr SettingRange kRampRate{1e-6, 1e6};
constexpr SettingRange kSpeed{0, 1e5, true};
constexpr SettingRange kAny{-1e9, 1e9};
constexpr SettingRange kBit{-1, 31};      // an input or output bit; -1: not wired
constexpr SettingRange kPinBit{0, 31};    // a step or direction bit: always wired
constexpr SettingRange kPositive{0, 1e6, true};

constexpr std::string_view kUnits[] = {"in", "mm"};
constexpr std::string_view kDialects[] = {"sb3", "fabmo"};
constexpr std::string_view kGcodeDialects[] = {"standard", "wincnc"};
constexpr std::string_view kPlannerModes[] = {"sb3", "junction", "stop"};
constexpr std::string_view kCardTypes[] = {"sim", "pci7200", "gpiod"};
constexpr std::string_view kBitLine[] = {"BIT:LINE"};
constexpr std::string_view kLineBit[] = {"LINE:BIT"};
constexpr std::string_view kSigns[] = {"-", "+"};
constexpr std::string_view kTriggerAxes[] = {"z", "a"};
constexpr std::string_view kAxisUnits[] = {"in", "mm", "deg"};  // AxisUnit's order
constexpr std::string_view kSpeedModes[] = {"pwm", "frequency"};     // SpindleSettings::SpeedMode
constexpr std::string_view kReverseWirings[] = {"direction", "run"};  // ...::ReverseWiring
constexpr std::string_view kSoftClamps[] = {"off", "vertical", "all"};  // SoftClamp's order
constexpr std::string_view kWAxes[] = {"none", "a", "b", "c"};  // display.w_axis

// The speed limit of a speed group (xy z a b c): the axis max_speed, XY's the lower of X's and Y's.
double group_limit(const Settings& s, int i) {
  return i == 0 ? std::min(s.axes[0].max_speed, s.axes[1].max_speed) : s.axes[i + 1].max_speed;
}

double& group(GroupSpeeds& g, int i) {
  switch (i) {
    case 0: return g.xy;
    case 1: return g.z;
    case 2: return g.a;
    case 3: return g.b;
    default: return g.c;
  }
}

std::string homing_order_rule(std::string_view order) {
  if (order.empty() || order.find_first_not_of("xyzabc") != std::string_view::npos)
    return "must list the axes to home, in order, as letters x y z a b c";
  return "";
}

std::string folder_rule(std::string_view folder) {
  if (folder.starts_with("/") || folder.starts_with("~/")) return "";
  return fmt::format("must list folders as absolute paths or ~/..., not \"{}\"", folder);
}

std::string gamepad_rule(std::string_view device) {
  if (device == "off" || device == "auto" || device.starts_with("/dev/")) return "";
  return fmt::format("must be \"off\", \"auto\" or a device path (/dev/input/event5), not \"{}\"",
                     device);
}

std::string coordinates_rule(std::string_view frame) {
  if (frame == "work" || frame == "machine") return "";
  return fmt::format("must be \"work\" or \"machine\", not \"{}\"", frame);
}

std::string channels_text(const Settings& s) {
  std::string channels;
  for (int axis : s.drivers.channel_axis) channels += "XYZABC"[axis];
  return channels;
}

std::string require_text(const Settings& s) {
  std::string out;
  for (int i = 0; i < kAxisCount; ++i)
    if (s.homing.require >> i & 1u) out += kAxisLetters[i];
  return out;
}

bool require_read(Settings& s, std::string_view axes) {
  s.homing.require = 0;
  for (const char c : axes) {
    const size_t i = std::string_view("xyzabc").find(static_cast<char>(std::tolower(c)));
    if (i == std::string_view::npos) return false;
    s.homing.require |= 1u << i;
  }
  return true;
}

bool channels_read(Settings& s, std::string_view channels) {
  s.drivers.channel_axis = {0, 1, 2, 3, 4, 5};
  bool ok = channels.size() == kAxisCount;
  for (size_t k = 0; ok && k < channels.size(); ++k) {
    const size_t axis =
        std::string_view("XYZABC").find(static_cast<char>(std::toupper(channels[k])));
    ok = axis != std::string_view::npos;
    if (ok) s.drivers.channel_axis[k] = static_cast<int>(axis);
  }
  return ok;
}

// The tool rack's slots: "x y; x y" (slot k holds tool k).
std::string slots_text(const Settings& s) {
  std::string out;
  for (const auto& [x, y] : s.toolchanger.slots)
    out += fmt::format("{}{} {}", out.empty() ? "" : "; ", x, y);
  return out;
}

bool slots_read(Settings& s, std::string_view text) {
  std::vector<std::array<double, 2>> slots;
  while (!text.empty() && text.find_first_not_of(" \t") != std::string_view::npos) {
    const size_t end = text.find(';');
    std::string one(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    std::array<double, 2> xy{};
    char extra = 0;
    if (std::sscanf(one.c_str(), " %lf %lf %c", &xy[0], &xy[1], &extra) != 2) return false;
    if (!std::isfinite(xy[0]) || !std::isfinite(xy[1]) || std::fabs(xy[0]) > 1e9 ||
        std::fabs(xy[1]) > 1e9)
      return false;
    slots.push_back(xy);
  }
  s.toolchanger.slots = std::move(slots);
  return true;
}

// The member a row sets, typed: a row of the wrong kind's type does not compile.
#define GANTRY_FIELD(T, expr) \
  [](Settings& s, int i) -> void* { (void)i; T* p = &(s.expr); return p; }
#define GANTRY_DATA(T, expr) \
  [](Settings& s, int i) -> void* { (void)i; T* p = s.expr.data(); return p; }
// An enum member held as the index of its names (the enum's order is the names').
#define GANTRY_ENUM(expr, T)                                                             \
  .choice_get = [](const Settings& s, int i) { (void)i; return static_cast<int>(s.expr); }, \
  .choice_set = [](Settings& s, int i, int v) { (void)i; s.expr = static_cast<T>(v); }

#define NUM(sec_, key_, expr, range_, unit_, help_, ...)                                          \
  {.section = sec_, .key = key_, .kind = SettingKind::Number,                             \
   .field = GANTRY_FIELD(double, expr), .range = range_, .unit = SettingUnit::unit_, \
   .help = help_, __VA_ARGS__}
#define AXIS_NUM(sec_, key_, expr, range_, unit_, help_, ...)                                     \
  {.section = sec_, .key = key_, .kind = SettingKind::Number,                             \
   .field = GANTRY_FIELD(double, expr), .range = range_, .unit = SettingUnit::unit_, \
   .help = help_, .family = SettingFamily::Axes, __VA_ARGS__}
#define GROUP(sec_, expr, help_, ...)                                                  \
  {.section = sec_, .key = "<xy,z,a,b,c>", .kind = SettingKind::Number,               \
   .field = [](Settings& s, int i) -> void* { return &group(s.expr, i); }, .range = kSpeed, \
   .unit = SettingUnit::Axis, .help = help_, .family = SettingFamily::Groups, __VA_ARGS__}
#define INT(sec_, key_, expr, lo_, hi_, help_, ...)                                            \
  {.section = sec_, .key = key_, .kind = SettingKind::Integer, .field = GANTRY_FIELD(int, expr), \
   .range = {lo_, hi_}, .help = help_, __VA_ARGS__}
#define AXIS_INT(sec_, key_, expr, lo_, hi_, help_, ...)                                       \
  {.section = sec_, .key = key_, .kind = SettingKind::Integer, .field = GANTRY_FIELD(int, expr), \
   .range = {lo_, hi_}, .help = help_, .family = SettingFamily::Axes, __VA_ARGS__}
#define BOOL(sec_, key_, expr, help_, ...)                                                     \
  {.section = sec_, .key = key_, .kind = SettingKind::Bool, .field = GANTRY_FIELD(bool, expr), \
   .help = help_, __VA_ARGS__}
#define AXIS_BOOL(sec_, key_, expr, help_, ...)                                                \
  {.section = sec_, .key = key_, .kind = SettingKind::Bool, .field = GANTRY_FIELD(bool, expr), \
   .help = help_, .family = SettingFamily::Axes}

// Each row names only the fields it needs; the others keep their defaults.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
// clang-format off
const SettingRow kRows[] = {
  {.section = "", .key = "name", .kind = SettingKind::Text, .field = GANTRY_FIELD(std::string, name),
   .help = "shown in reports", .docs_allowed = "any", .owner = SettingOwner::MachineTable},
  {.section = "", .key = "units", .kind = SettingKind::Choice,
   .help = "unit of every length, speed and acceleration in the profile and in part files",
   .names = kUnits, GANTRY_ENUM(units, Units)},
  {.section = "", .key = "dialect", .kind = SettingKind::Choice,
   .help = "the OpenSBP dialect of part files: trigonometric functions take and give radians (SB3) or degrees (FabMo)",
   .names = kDialects, GANTRY_ENUM(dialect, Dialect), .owner = SettingOwner::MachineTable},
  {.section = "", .key = "gcode_dialect", .kind = SettingKind::Choice,
   .help = "the G-code dialect of G-code files and lines: LinuxCNC's (standard) or WinCNC's (G21 centimetres, G22 millimetres, G4 without X waits for the operator...; docs/gcode.md). Optional: `\"standard\"` when left out",
   .names = kGcodeDialects, .optional = true, GANTRY_ENUM(gcode_dialect, GcodeDialect)},
  {.section = "", .key = "tool_table", .kind = SettingKind::Text, .field = GANTRY_FIELD(std::string, tool_table),
   .help = "G-code's tool table, LinuxCNC's file (`T1 P1 D0.25 Z+1.5 ;comment`, lengths in `units`; docs/gcode.md, \"Tool table\"): a relative path is from the profile's folder; G10 L1/L10/L11 write it back. Left out: no table, every tool has length 0 (Z is zeroed after each tool change). `--tool-table FILE` overrides it for one command. Read from the profile only: a values file's is ignored",
   .optional = true, .omit_empty = true, .docs_allowed = "a path; optional"},
  {.section = "", .key = "subroutines", .kind = SettingKind::Texts,
   .field = GANTRY_FIELD(std::vector<std::string>, subroutines),
   .help = "where G-code's `o<name> call` finds `name.ngc` when the calling file does not define it, after the calling file's folder and the folders given with `--subroutines DIR` (docs/gcode.md, \"O-words\"); a relative path is from the profile's folder, `~/` is the home folder. A folder that is not there is an error at this key. Read-only to part files. Read from the profile only: a values file's is ignored",
   .optional = true, .omit_empty = true, .docs_allowed = "folders that exist; optional"},

  AXIS_NUM("axes.<x..c>", "steps_per_unit", axes[i].steps_per_unit, (SettingRange{-1e6, 1e6}), PerAxis,
           "motor steps per unit (per degree for rotary axes); negative reverses the axis; not 0"),
  AXIS_NUM("axes.<x..c>", "max_speed", axes[i].max_speed, kSpeed, Axis, "hardware speed limit, units/s", .owner = SettingOwner::MachineKey),
  AXIS_NUM("axes.<x..c>", "max_accel", axes[i].max_accel, (SettingRange{0, 1e7, true}), Axis,
           "hardware acceleration limit, units/s^2", .owner = SettingOwner::MachineKey),
  AXIS_NUM("axes.<x..c>", "min", axes[i].min, kAny, Axis,
           "soft limit: no move may take the axis below it; below `max`"),
  AXIS_NUM("axes.<x..c>", "max", axes[i].max, kAny, Axis,
           "soft limit: no move may take the axis above it"),
  AXIS_NUM("axes.<x..c>", "backlash", axes[i].backlash, (SettingRange{0, 1000}), Axis,
           "backlash compensation: the drive's slack, taken up by extra motor steps at each reversal of the axis, at its corner jump speed; the position reported does not count them (docs/hardware.md, \"Backlash\"). Left out: 0, none",
           .optional = true, .owner = SettingOwner::MachineKey),
  AXIS_NUM("axes.<x..c>", "wrap", axes[i].wrap, (SettingRange{0, 1e6}), Axis,
           "a rotary axis's position is reported modulo this (360: degrees in [0, 360)) in the readouts and the run report; moves and part files keep the whole position. Left out: 0, not wrapped",
           .optional = true, .owner = SettingOwner::MachineKey),

  GROUP("speeds.move", speeds.move,
        "move (cutting) speeds, as VS/MS set them; XY is the vector speed; at most the axis max_speed",
        .most = group_limit),
  GROUP("speeds.jog", speeds.jog, "jog (rapid) speeds, as VS/JS set them; at most the axis max_speed",
        .most = group_limit),

  NUM("ramps", "move_ramp_rate", ramps.move_ramp_rate, kRampRate, Length,
      "VR move ramp rate: distance over which the speed changes by 2 units/s (a length)"),
  NUM("ramps", "jog_ramp_rate", ramps.jog_ramp_rate, kRampRate, Length,
      "VR jog ramp rate, as the move ramp rate (a length)"),
  NUM("ramps", "threshold_3d", ramps.threshold_3d, (SettingRange{0, 1000}), None,
      "VR 3D ramp threshold, percent"),
  NUM("ramps", "min_distance", ramps.min_distance, (SettingRange{0, 1e3}), Length,
      "VR minimum distance to check (a length)"),
  NUM("ramps", "slow_corner", ramps.slow_corner, (SettingRange{0, 100}), None,
      "VR slow corner speed, percent"),
  NUM("ramps", "keypad_ramp_rate", ramps.keypad_ramp_rate, kRampRate, Length,
      "VR keypad ramp rate (a length)"),
  NUM("ramps", "small_circle", ramps.small_circle, (SettingRange{0, 1e3}), Length,
      "VR small-circle diameter (a length)"),
  GROUP("ramps.move_speed", ramps.move_ramp_speed, "VR move ramp (start and end) speeds"),
  GROUP("ramps.jog_speed", ramps.jog_ramp_speed, "VR jog ramp (start and end) speeds"),

  {.section = "planner", .key = "mode", .kind = SettingKind::Choice,
   .help = "how moves are joined (docs/planner.md)", .names = kPlannerModes,
   GANTRY_ENUM(planner.mode, PlannerMode), .owner = SettingOwner::MachineKey},
  NUM("planner", "corner_jump", planner.corner_jump, (SettingRange{0, 1}), None,
      "the largest speed change an axis makes at once (corners, starts from rest), as a fraction of its `max_speed`", .owner = SettingOwner::MachineKey),
  NUM("planner", "junction_deviation", planner.junction_deviation, (SettingRange{0, 1e3}), Length,
      "junction mode: how far from a corner its speed's arc may pass (a length)", .owner = SettingOwner::MachineKey),
  NUM("planner", "chord_tolerance", planner.chord_tolerance, (SettingRange{0, 1e3, true}), Length,
      "arcs run as chords at most this far from the arc (a length)", .owner = SettingOwner::MachineKey),
  NUM("planner", "jerk", planner.jerk, (SettingRange{0, 1e9}), Rate,
      "above 0: S-curve speed ramps within this jerk, units/s^3; 0: linear ramps"),
  INT("planner", "lookahead", planner.lookahead, 2, 1 << 20,
      "moves planned ahead, at least (more when stopping needs more path)", .owner = SettingOwner::MachineKey),

  {.section = "card", .key = "type", .kind = SettingKind::Text, .field = GANTRY_FIELD(std::string, card.type),
   .help = "the card to drive (`gantry run --card` overrides); docs/hardware.md", .names = kCardTypes, .owner = SettingOwner::MachineTable},
  NUM("card", "clock_hz", card.clock_hz, (SettingRange{1e3, 1e9}), None, "timer clock (PCI-7200: 4 MHz)", .owner = SettingOwner::MachineTable),
  INT("card", "pacer_divisor", card.pacer_divisor, 2, 65535,
      "pacer = clock_hz / pacer_divisor; one output word per pacer tick", .owner = SettingOwner::MachineTable),
  NUM("card", "step_pulse_us", card.step_pulse_us, (SettingRange{0, 1e4, true}), None,
      "step pulse width, rounded up to whole ticks", .owner = SettingOwner::MachineTable),
  NUM("card", "dir_setup_us", card.dir_setup_us, (SettingRange{0, 1e4}), None,
      "direction set this long before each step, rounded up to whole ticks", .owner = SettingOwner::MachineTable),
  {.section = "card", .key = "gpiod_chip", .kind = SettingKind::Text,
   .field = GANTRY_FIELD(std::string, card.gpiod_chip),
   .help = "type gpiod: the GPIO chip (`/dev/gpiochip0`)", .docs_allowed = "a path", .owner = SettingOwner::MachineTable},
  {.section = "card", .key = "gpiod_outputs", .kind = SettingKind::LineBits,
   .field = GANTRY_FIELD(std::vector<GpioLineBit>, card.gpiod_outputs),
   .help = "type gpiod: which line carries each output-word bit", .names = kBitLine,
   .docs_allowed = "`\"BIT:LINE, ...\"`", .owner = SettingOwner::MachineTable},
  {.section = "card", .key = "gpiod_inputs", .kind = SettingKind::LineBits,
   .field = GANTRY_FIELD(std::vector<GpioLineBit>, card.gpiod_inputs),
   .help = "type gpiod: which line sets each input-word bit", .names = kLineBit,
   .docs_allowed = "`\"LINE:BIT, ...\"`", .owner = SettingOwner::MachineTable},
  NUM("card", "lead_ms", card.lead_ms, (SettingRange{1, 1000}), None,
      "a real card (and --realtime): at most this much motion, ms, generated ahead of the tick played; a hold, stop or jog release begins within it. Shorter: faster holds, more underrun risk (docs/hardware.md). Left out: 20 (a profile written before it keeps working)", .optional = true, .owner = SettingOwner::MachineTable),

  AXIS_INT("pins.<x..c>", "step_bit", pins[i].step_bit, 0, 31, "the step bit of the output word; each bit used once", .owner = SettingOwner::MachineTable),
  AXIS_INT("pins.<x..c>", "dir_bit", pins[i].dir_bit, 0, 31, "the direction bit of the output word; each bit used once", .owner = SettingOwner::MachineTable),
  AXIS_BOOL("pins.<x..c>", "invert_dir", pins[i].invert_dir, "direction line high means positive travel", .owner = SettingOwner::MachineTable),
  AXIS_BOOL("pins.<x..c>", "step_active_low", pins[i].step_active_low, "the step line idles high and pulses low", .owner = SettingOwner::MachineTable),

  NUM("cutter", "diameter", cutter.diameter, (SettingRange{0, 1e4}), Length,
      "VC cutter diameter, for the O and I (outside, inside) cut offsets (a length)"),
  NUM("cutter", "safe_z", cutter.safe_z, kAny, Length,
      "VC safe Z: the working Z that MH and JH raise the tool to first; AMB-4: default 1 in (a length)"),
  NUM("cutter", "safe_a", cutter.safe_a, kAny, AxisA, "VC safe A, for an A axis used as a second Z"),
  {.section = "cutter", .key = "plunge_direction", .kind = SettingKind::Choice,
   .help = "VC plunge direction: `\"-\"`, a negative Z goes into the material", .names = kSigns,
   .choice_get = [](const Settings& s, int) { return s.cutter.plunge_negative ? 0 : 1; },
   .choice_set = [](Settings& s, int, int v) { s.cutter.plunge_negative = v == 0; }},
  NUM("cutter", "pocket_overlap", cutter.pocket_overlap, (SettingRange{0, 99}), None,
      "VC pocket overlap, percent of the cutter diameter"),
  NUM("cutter", "trigger_on", cutter.trigger_on, kAny, TriggerAxis,
      "VC Z (or A) below which the triggered output switch comes on"),
  NUM("cutter", "trigger_off", cutter.trigger_off, kAny, TriggerAxis,
      "VC Z (or A) above which the triggered output switch goes off"),
  {.section = "cutter", .key = "trigger_axis", .kind = SettingKind::Choice,
   .help = "VC the axis the triggered output switch follows", .names = kTriggerAxes,
   .choice_get = [](const Settings& s, int) { return s.cutter.trigger_axis == 3 ? 1 : 0; },
   .choice_set = [](Settings& s, int, int v) { s.cutter.trigger_axis = v ? 3 : 2; }},
  INT("cutter", "trigger_output", cutter.trigger_output, 3, 12, "VC the triggered output switch (not 4)"),

  NUM("tabs", "pull_up", tabs.pull_up, (SettingRange{0, 1e4}), Length,
      "VB tab height: how far the cutter lifts for a tab (a length)"),
  NUM("tabs", "spacing", tabs.spacing, (SettingRange{0, 1e6, true}), Length,
      "VB distance from one tab to the next (a length)"),
  NUM("tabs", "size", tabs.size, (SettingRange{0, 1e6}), Length,
      "VB tab length along the path (a length)"),
  NUM("tabs", "leads", tabs.leads, (SettingRange{0, 1e6}), Length,
      "VB length of the incline up to and down from a tab (a length)"),

  INT("display", "axes", display.axes, 3, 6, "VD axes shown and used: 3 XYZ, 4 adds A, 5 adds B, 6 adds C"),
  {.section = "display", .key = "units_a", .kind = SettingKind::Choice, .help = "VD unit of A",
   .names = kAxisUnits, GANTRY_ENUM(display.rotary_units[0], AxisUnit)},
  {.section = "display", .key = "units_b", .kind = SettingKind::Choice, .help = "VD unit of B",
   .names = kAxisUnits, GANTRY_ENUM(display.rotary_units[1], AxisUnit)},
  {.section = "display", .key = "units_c", .kind = SettingKind::Choice, .help = "VD unit of C",
   .names = kAxisUnits, GANTRY_ENUM(display.rotary_units[2], AxisUnit)},
  {.section = "display", .key = "w_axis", .kind = SettingKind::Choice,
   .help = "the axis shown and programmed as W, a second vertical head (WinCNC's W): the readouts and messages name it W, G-code's W words move it, G28 W homes it; OpenSBP still reaches it through its own letter's commands (docs/hardware.md, \"The W axis\"). It must be an axis in use with a length unit. Left out: `\"none\"`",
   .names = kWAxes, .optional = true,
   .choice_get = [](const Settings& s, int) { return s.display.w_axis < 3 ? 0 : s.display.w_axis - 2; },
   .choice_set = [](Settings& s, int, int v) { s.display.w_axis = v == 0 ? -1 : v + 2; },
   .owner = SettingOwner::MachineKey},
  BOOL("display", "show_comments", display.show_comments, "VD part-file comments shown as the file runs"),
  NUM("display", "keypad_step", display.keypad_step, (SettingRange{0, 1e4, true}), Length,
      "VD SK fixed-distance step (a length)"),
  INT("display", "keypad_remote", display.keypad_remote, 0, 2,
      "VD 0 keyboard, 1 pendant on the inputs, 2 other"),
  BOOL("display", "part_file_log", display.part_file_log, "VD a log line per part file run"),
  BOOL("display", "system_log", display.system_log, "VD a system log for diagnostics"),
  BOOL("display", "show_progress", display.show_progress, "VD a progress bar while a file runs"),
  BOOL("display", "keypad_outputs_off", display.keypad_outputs_off,
       "VD output switches off when the keypad closes"),

  NUM("preview", "grid", preview.grid, (SettingRange{0, 1e6}), Length, "VP grid spacing (a length)"),
  NUM("preview", "table_x", preview.table_x, (SettingRange{0, 1e6, true}), Length, "VP table size in X (a length)"),
  NUM("preview", "table_y", preview.table_y, (SettingRange{0, 1e6, true}), Length, "VP table size in Y (a length)"),
  NUM("preview", "table_z", preview.table_z, (SettingRange{0, 1e6, true}), Length, "VP table size in Z (a length)"),
  BOOL("preview", "simulate_cutting", preview.simulate_cutting, "VP simulate cutting"),
  BOOL("preview", "draw_tool", preview.draw_tool, "VP draw the tool"),
  BOOL("preview", "start_at_location", preview.start_at_location, "VP start at the current location"),
  BOOL("preview", "show_jogs", preview.show_jogs, "VP show jogs"),

  INT("accessories", "mode", accessories.mode, 0, 1, "VH 1 on, 0 off (needs switches.accessory)"),
  NUM("accessories", "plasma_rate", accessories.plasma_rate, (SettingRange{0, 10}), None, "VH plasma rate"),
  NUM("accessories", "pwm_low", accessories.pwm_low, (SettingRange{0, 100}), None, "VH PWM low, percent"),
  NUM("accessories", "pwm_high", accessories.pwm_high, (SettingRange{0, 100}), None, "VH PWM high, percent"),
  NUM("accessories", "pulse_khz", accessories.pulse_khz, (SettingRange{0, 1e3}), None, "VH pulse frequency, kHz"),
  NUM("accessories", "low_cycle", accessories.low_cycle, (SettingRange{1, 10}), None, "VH low cycle"),
  NUM("accessories", "temperature", accessories.temperature, (SettingRange{0, 1e4}), None, "VH temperature"),

  BOOL("switches", "limits", switches.limits, "VN limit switches stop the machine"),
  BOOL("switches", "stop_normally_open", switches.stop_normally_open,
       "VN input 4 (stop) wiring; false: normally closed"),
  INT("switches", "accessory", switches.accessory, 0, 3, "VN 0 none, 1 torch height, 2 laser, 3 analog"),
  {.section = "switches", .key = "input_modes", .kind = SettingKind::IntList,
   .field = GANTRY_DATA(int, switches.input_modes), .range = {0, 4},
   .help = "VN input switch modes 1-12: 0 standard, 1 NO limit, 2 NC limit, 3 NO stop, 4 NC stop", .count = 12},
  {.section = "switches", .key = "output_modes", .kind = SettingKind::IntList,
   .field = GANTRY_DATA(int, switches.output_modes), .range = {0, 5},
   .help = "VN output switch modes 1-12, SB3's", .count = 12},

  {.section = "drivers", .key = "channels", .kind = SettingKind::Coded,
   .help = "VI the axis each driver channel 1-6 drives (`\"XYZABC\"`); an axis on two channels is slaved: both motors step together (`\"XYZAYC\"`: Y on channels 2 and 5; docs/hardware.md, \"Slaved axes\")", .encode = channels_text,
   .decode = channels_read, .rule = "must name six axes, one per driver channel, such as \"XYZABC\"",
   .docs_allowed = "six axis letters; each axis in use once or twice"},

  NUM("calibration", "circle_resolution", calibration.circle_resolution, (SettingRange{0, 1e3, true}), Length,
      "VU arc segment length (a length)"),
  {.section = "calibration", .key = "resolution_multipliers", .kind = SettingKind::NumberList,
   .field = GANTRY_DATA(double, calibration.resolution_multiplier), .range = {0, 10},
   .help = "VU X..B jog resolution shift", .count = 5},
  INT("calibration", "step_divider", calibration.step_divider, 1, 100, "VU speeds run at 1/n of their value"),
  BOOL("calibration", "no_resolution_shift", calibration.no_resolution_shift, "VU no resolution shift"),

  BOOL("machine", "limit_checking", machine.limit_checking, "SF, VL 9: moves are checked against the soft limits"),
  NUM("machine", "warning_s", machine.warning_s, (SettingRange{0, 3600}), None,
      "SW warning before movement starts, s"),
  {.section = "machine", .key = "max_dwell_s", .kind = SettingKind::Number,
   .field = GANTRY_FIELD(double, machine.max_dwell_s), .range = {0, 2592000, true},
   .help = "the longest wait a part file may ask for (`PAUSE 5`, `G4 P5`, a DIALOG's TIMER), s (2592000: 30 days); a longer one, a negative one or one that is not a number is an error at check time (docs/reliability.md). Left out: 86400 (24 h)",
   .optional = true},
  INT("machine", "switch4_mode", machine.switch4_mode, -4, -1,
      "SO 4: -1 to -3: output switch 4 is on while a run moves the tool (from the warning on); -4: an ordinary switch"),
  {.section = "machine", .key = "editor", .kind = SettingKind::Text, .field = GANTRY_FIELD(std::string, machine.editor),
   .help = "FE: the program FE opens files in, with its options, split at spaces and started without a shell; `\"\"`: `$VISUAL`, then `$EDITOR`, then `vi`. Read from the profile only: a values file's is ignored (docs/security.md)",
   .optional = true, .docs_allowed = "any; optional"},

  {.section = "files", .key = "allow", .kind = SettingKind::Texts,
   .field = GANTRY_FIELD(std::vector<std::string>, files.allow),
   .help = "folders part files may read and write in besides their job's folder and Gantry's data folder (`--allow-path DIR` adds one for a run). Read from the profile only (docs/security.md)",
   .optional = true, .optional_table = true, .check = folder_rule,
   .docs_allowed = "absolute paths or `~/...`; the `[files]` table is optional"},

  {.section = "pendant", .key = "gamepad", .kind = SettingKind::Text,
   .field = GANTRY_FIELD(std::string, pendant.gamepad),
   .help = "a Linux gamepad or joystick as a pendant: `\"off\"`, `\"auto\"` (the first one found, looked for every second) or its device (`/dev/input/event5`); off unless set, as a gamepad may be meant for something else (docs/hardware.md, \"A gamepad as a pendant\")",
   .optional = true, .optional_table = true, .check = gamepad_rule,
   .docs_allowed = "`\"off\"`, `\"auto\"` or `/dev/...`; the `[pendant]` table is optional"},
  {.section = "pendant", .key = "gamepad_<x..c>", .kind = SettingKind::Text,
   .field = [](Settings& s, int i) -> void* { return &s.pendant.gamepad_jog[static_cast<size_t>(i)]; },
   .help = "the gamepad's sticks that jog the axis, the kernel's names with a minus to reverse one (`\"-ABS_Y, -ABS_HAT0Y\"`), or `\"none\"`; left out: X the left stick and the hat across, Y them up and down, Z the right stick up and down",
   .family = SettingFamily::Axes, .optional = true, .optional_table = true,
   .docs_allowed = "`ABS_*` names, `none`"},
  {.section = "pendant", .key = "gamepad_buttons", .kind = SettingKind::Text,
   .field = GANTRY_FIELD(std::string, pendant.gamepad_buttons),
   .help = "the gamepad's buttons, and a hat's ways as buttons (`ABS_HAT0X+`): `\"BTN_SOUTH = start/pause, BTN_NORTH = macro 1, ABS_HAT0X+ = step x+ 0.01\"` (the pendant's actions: reset, stop, start/pause, feed +, feed -, spindle +, spindle -, machine home, safe Z, work home, spindle on/off, probe Z, macro 1 to 10, `jog x+` while held, `step x+` an exact step); left out: A start/pause, B stop, the shoulders feed - and +, Select reset",
   .optional = true, .optional_table = true, .docs_allowed = "`BTN_* = action, ...`"},
  {.section = "pendant", .key = "keys", .kind = SettingKind::Texts,
   .field = GANTRY_FIELD(std::vector<std::string>, pendant.keys),
   .help = "keys of the console and the window bound to the pendant's actions, one a string: `[\"F5 = start/pause\", \"Ctrl+Right = jog x+\", \"F8 = step z- 0.01\"]` (the actions: the pendant's buttons, `macro 1` to `macro 10`, `jog x+` continuous, `step x+` one step); a bound key does only that; a name not known is an error at its line and that key is left unbound (docs/console.md, \"Keys as a pendant\")",
   .optional = true, .optional_table = true, .omit_empty = true,
   .docs_allowed = "`\"KEY = action\"` strings; left out: none"},
#define PENDANT_MACRO(n)                                                                         \
  {.section = "pendant", .key = "macro_" #n, .kind = SettingKind::Text,                          \
   .field = GANTRY_FIELD(std::string, pendant.macros[n - 1]),                                  \
   .help = "what the pendant's macro " #n " runs, at rest only: a line (`\"C3\"`, `\"MZ, 1\"`) or a part file's path (`\"~/jobs/corner.sbp\"`, from the profile's folder when relative); left out: macro " #n " is unbound and says so", \
   .optional = true, .optional_table = true, .omit_empty = true, .docs_allowed = "a line or a part file"}
  PENDANT_MACRO(1), PENDANT_MACRO(2), PENDANT_MACRO(3), PENDANT_MACRO(4), PENDANT_MACRO(5),
  PENDANT_MACRO(6), PENDANT_MACRO(7), PENDANT_MACRO(8), PENDANT_MACRO(9), PENDANT_MACRO(10),
#undef PENDANT_MACRO
  {.section = "pendant", .key = "xhc_coordinates", .kind = SettingKind::Text,
   .field = GANTRY_FIELD(std::string, pendant.xhc_coordinates),
   .help = "what the XHC pendant's display shows at start: `\"work\"` coordinates (X1, Y1, Z1 on its screen) or `\"machine\"` ones; its Macro-10 key switches between them",
   .optional = true, .optional_table = true, .check = coordinates_rule,
   .docs_allowed = "`\"work\"`, `\"machine\"`"},

  INT("friendly_motion", "laser_output", friendly_motion.laser_output, 0, 12,
      "a Friendly Motion laser table's beam gate: the output switch M100 and M101 switch and G16's strokes turn on and off (docs/friendlymotion.md); 0: none. Left out: 1; the `[friendly_motion]` table is optional",
      .optional = true, .optional_table = true),
  NUM("friendly_motion", "laser_on_s", friendly_motion.laser_on_s, (SettingRange{0, 60}), None,
      "the wait after the beam switches on, at rest, before the next move starts, s. Left out: 0",
      .optional = true, .optional_table = true),
  NUM("friendly_motion", "laser_off_s", friendly_motion.laser_off_s, (SettingRange{0, 60}), None,
      "the wait after the beam switches off, at rest, before the next move starts, s. Left out: 0",
      .optional = true, .optional_table = true),
  {.section = "friendly_motion", .key = "relay_a", .kind = SettingKind::IntList,
   .field = GANTRY_FIELD(std::vector<int>, friendly_motion.relay_a), .range = {0, 12},
   .help = "the relay matrix (P): the output switch that connects test probe 1, 2, ... to bus A (`PA#`); 0: that probe has no relay. Left out: none, P is refused",
   .optional = true, .optional_table = true, .omit_empty = true, .docs_allowed = "`\"a, b, ...\"`, each 0 to 12; optional"},
  {.section = "friendly_motion", .key = "relay_b", .kind = SettingKind::IntList,
   .field = GANTRY_FIELD(std::vector<int>, friendly_motion.relay_b), .range = {0, 12},
   .help = "the same for bus B (`PB#`)",
   .optional = true, .optional_table = true, .omit_empty = true, .docs_allowed = "`\"a, b, ...\"`, each 0 to 12; optional"},
  {.section = "friendly_motion", .key = "feed_min", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, friendly_motion.feed_min), .range = kPositive, .unit = SettingUnit::Rate,
   .help = "the slowest X-Y feed a Friendly Motion F may set, units/s; a slower one is an error. Left out: 0.005 in/s (the manual's)",
   .optional = true, .optional_table = true},
  {.section = "friendly_motion", .key = "feed_max", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, friendly_motion.feed_max), .range = kPositive, .unit = SettingUnit::Rate,
   .help = "the fastest X-Y feed a Friendly Motion F may set, units/s; a faster one is an error. Left out: 6 in/s (the manual's)",
   .optional = true, .optional_table = true},

  INT("outputs", "charge_pump_bit", outputs.charge_pump_bit, -1, 31, "a square wave while pulses flow (-1: none)", .owner = SettingOwner::MachineTable),
  NUM("outputs", "charge_pump_hz", outputs.charge_pump_hz, kPositive, None, "its frequency", .owner = SettingOwner::MachineTable),
  INT("outputs", "spindle_bit", outputs.spindle_bit, -1, 31, "on while the spindle runs", .owner = SettingOwner::MachineTable),
  {.section = "outputs", .key = "aux_bits", .kind = SettingKind::IntList,
   .field = GANTRY_FIELD(std::vector<int>, outputs.aux_bits), .range = kBit,
   .help = "output switches 1, 2, ... (SO numbers)", .owner = SettingOwner::MachineTable},

  INT("spindle", "pwm_bit", spindle.pwm_bit, -1, 31,
      "the output bit carrying TR's spindle speed as a square wave of duty rpm / `max_rpm` (-1: none; TR only records the RPM and warns once a run); the `[spindle]` table is optional (none: no speed output)",
      .optional_table = true),
  NUM("spindle", "pwm_hz", spindle.pwm_hz, kPositive, None,
      "the square wave's frequency; at most the pacer / 100 when `pwm_bit` is wired",
      .optional_table = true),
  NUM("spindle", "max_rpm", spindle.max_rpm, kPositive, None,
      "the RPM at 100 % duty; with `pwm_bit` wired, TR above it is refused", .optional_table = true),
  {.section = "spindle", .key = "speed_mode", .kind = SettingKind::Choice,
   .help = "how `pwm_bit` carries the speed: `\"pwm\"`, a duty of rpm / `max_rpm` at `pwm_hz`; `\"frequency\"`, a square wave of rpm / `max_rpm` x `max_hz` (a VFD's pulse-train input, WinCNC's spindle=T3). Left out: pwm",
   .names = kSpeedModes, .optional = true, .optional_table = true,
   GANTRY_ENUM(spindle.speed_mode, SpindleSettings::SpeedMode)},
  NUM("spindle", "max_hz", spindle.max_hz, kPositive, None,
      "frequency mode: the frequency at `max_rpm`; at most the pacer / 2. Left out: 1000",
      .optional = true, .optional_table = true),
  INT("spindle", "reverse_output", spindle.reverse_output, 0, 12,
      "the output switch that runs the spindle counter-clockwise (M4); 0: none, M4 is refused. Left out: 0",
      .optional = true, .optional_table = true),
  {.section = "spindle", .key = "reverse_wiring", .kind = SettingKind::Choice,
   .help = "`\"direction\"`: `reverse_output` selects the direction while output switch 1 runs the spindle; `\"run\"`: output 1 runs it forward and `reverse_output` in reverse, never both (a VFD's FWD and REV terminals). Left out: direction",
   .names = kReverseWirings, .optional = true, .optional_table = true,
   GANTRY_ENUM(spindle.reverse_wiring, SpindleSettings::ReverseWiring)},
  NUM("spindle", "spin_up_s", spindle.spin_up_s, (SettingRange{0, 3600}), None,
      "the machine waits this long after the spindle starts (M3, M4, SO 1, C6), s, before anything moves. Left out: 0",
      .optional = true, .optional_table = true),
  NUM("spindle", "spin_down_s", spindle.spin_down_s, (SettingRange{0, 3600}), None,
      "the machine waits this long after the spindle stops (M5, SO 1 off, C7, a tool change), s. Left out: 0",
      .optional = true, .optional_table = true),
  INT("spindle", "at_speed_input", spindle.at_speed_input, 0, 12,
      "the input switch the drive closes when the spindle is at speed; after a start or a speed change the machine waits for it, and a job whose spindle is not at speed within `at_speed_timeout_s` stops with an error. 0: none. Left out: 0",
      .optional = true, .optional_table = true),
  NUM("spindle", "at_speed_timeout_s", spindle.at_speed_timeout_s, (SettingRange{0, 3600, true}), None,
      "the longest wait for `at_speed_input`, s. Left out: 10", .optional = true, .optional_table = true),
  {.section = "spindle", .key = "dac_bits", .kind = SettingKind::IntList,
   .field = GANTRY_FIELD(std::vector<int>, spindle.dac_bits), .range = {0, 31},
   .help = "a D/A converter's input word carrying TR's and S's speed (WinCNC's da=, a 0-10 V board on parallel lines): output bits, least significant first, holding rpm / `max_rpm` x (2^n - 1), set with the machine at rest as an output is; at most 16 bits, instead of `pwm_bit`. Left out or empty: none",
   .optional = true, .optional_table = true, .omit_empty = true,
   .docs_allowed = "`\"a, b, ...\"`, each 0 to 31; optional"},
  NUM("spindle", "initial_rpm", spindle.initial_rpm, (SettingRange{0, 1000000}), None,
      "the RPM TR and S hold when Gantry starts (WinCNC's spindle I): the spindle runs at it when it starts before any TR or S; at most `max_rpm` with a speed output. Left out: 0",
      .optional = true, .optional_table = true),

  {.section = "toolchanger", .key = "slots", .kind = SettingKind::Coded,
   .unit = SettingUnit::Length, .help = "the tool rack: the table base X and Y of each slot, slot k holding tool k, as `\"2 40; 6 40; 10 40\"` for tools 1 to 3 (a length). Left out or empty: no rack, a tool change asks the operator (docs/hardware.md, \"Tool changer\"); the `[toolchanger]` table is optional",
   .optional = true, .optional_table = true, .encode = slots_text,
   .decode = slots_read, .rule = "must list each slot's X and Y, slots apart with `;` (\"2 40; 6 40\")",
   .docs_allowed = "`\"x y; x y; ...\"`; optional"},
  NUM("toolchanger", "slot_z", toolchanger.slot_z, kAny, Length,
      "the table base Z at which the spindle holds a tool in its slot: where a tool is left and picked, WinCNC's atc H (a length)",
      .optional = true, .optional_table = true),
  NUM("toolchanger", "clear_z", toolchanger.clear_z, kAny, Length,
      "the table base Z the spindle travels at to and over the rack and to the sensor; above `slot_z` (a length)",
      .optional = true, .optional_table = true),
  INT("toolchanger", "release_output", toolchanger.release_output, 0, 12,
      "the output switch that opens the drawbar (the collet's air); needed with a rack. Left out: 0",
      .optional = true, .optional_table = true),
  NUM("toolchanger", "release_s", toolchanger.release_s, (SettingRange{0, 60}), None,
      "the wait after the drawbar opens or closes, s. Left out: 0.5", .optional = true, .optional_table = true),
  INT("toolchanger", "sensor_input", toolchanger.sensor_input, 0, 12,
      "the tool-length sensor's input switch: after each change (M6, C9) the new tool is measured on it and its length written to the tool table (G43's). 0: none. Left out: 0",
      .optional = true, .optional_table = true),
  NUM("toolchanger", "sensor_x", toolchanger.sensor_x, kAny, Length,
      "the sensor's table base X, WinCNC's g37 X (a length)", .optional = true, .optional_table = true),
  NUM("toolchanger", "sensor_y", toolchanger.sensor_y, kAny, Length,
      "the sensor's table base Y (a length)", .optional = true, .optional_table = true),
  NUM("toolchanger", "sensor_start_z", toolchanger.sensor_start_z, kAny, Length,
      "the table base Z the measuring probe starts from, reached at jog speed: above where the longest tool closes the sensor, at most `clear_z` (a length)",
      .optional = true, .optional_table = true),
  NUM("toolchanger", "sensor_min_z", toolchanger.sensor_min_z, kAny, Length,
      "the lowest table base Z the probe goes to: a sensor that has not closed by then stops the job with an error (a length)",
      .optional = true, .optional_table = true),
  NUM("toolchanger", "sensor_speed", toolchanger.sensor_speed, kPositive, Rate,
      "the probe's speed, units/s (WinCNC's g37 F). Left out: 0.5", .optional = true, .optional_table = true),
  NUM("toolchanger", "sensor_zero_z", toolchanger.sensor_zero_z, kAny, Length,
      "the table base Z at which a tool of length 0 would close the sensor: a tool's length is the Z where it closes less this (a length)",
      .optional = true, .optional_table = true),

  INT("inputs", "estop_bit", inputs.estop_bit, -1, 31, "the E-stop's input-word bit (-1: not wired)", .owner = SettingOwner::MachineTable),
  BOOL("inputs", "estop_active_low", inputs.estop_active_low, "the E-stop input reads 0 when active", .owner = SettingOwner::MachineTable),
  INT("inputs", "probe_bit", inputs.probe_bit, -1, 31, "the probe's input-word bit (-1: not wired)", .owner = SettingOwner::MachineTable),
  BOOL("inputs", "limits_active_low", inputs.limits_active_low, "the limit inputs read 0 when active", .owner = SettingOwner::MachineTable),
  AXIS_INT("inputs.<x..c>", "min_bit", inputs.min_bit[i], -1, 31, "the axis's min limit switch bit", .owner = SettingOwner::MachineTable),
  AXIS_INT("inputs.<x..c>", "max_bit", inputs.max_bit[i], -1, 31, "the axis's max limit switch bit", .owner = SettingOwner::MachineTable),
  AXIS_INT("inputs.<x..c>", "home_bit", inputs.home_bit[i], -1, 31,
           "the axis's proximity switch bit; several axes may share one", .owner = SettingOwner::MachineTable),
  {.section = "inputs", .key = "switch_bits", .kind = SettingKind::IntList,
   .field = GANTRY_DATA(int, inputs.switch_bits), .range = kBit,
   .help = "the bit of input switches 1-12 that part files read and watch (`%(51)`, `ON INPUT`, probes)",
   .count = 12, .owner = SettingOwner::MachineTable},

  INT("homing", "input", homing.input, 1, 12, "the input switch the proximity switches close (C3)"),
  {.section = "homing", .key = "order", .kind = SettingKind::Text, .field = GANTRY_FIELD(std::string, homing.order),
   .help = "the axes C3 homes, in order", .check = homing_order_rule, .docs_allowed = "letters `xyzabc`"},
  NUM("homing", "fast_speed", homing.fast_speed, kPositive, Rate, "the first approach's speed, units/s"),
  NUM("homing", "slow_speed", homing.slow_speed, kPositive, Rate, "the measured approach's speed, units/s"),
  NUM("homing", "back_off", homing.back_off, kPositive, Length,
      "off the switch between the approaches and at the end (a length)"),
  {.section = "homing.<x..c>", .key = "direction", .kind = SettingKind::Choice,
   .help = "towards the switch", .family = SettingFamily::Axes, .names = kSigns,
   .choice_get = [](const Settings& s, int i) { return s.homing.direction[i] > 0 ? 1 : 0; },
   .choice_set = [](Settings& s, int i, int v) { s.homing.direction[i] = v ? 1 : -1; }},
  AXIS_NUM("homing.<x..c>", "at", homing.at[i], kAny, Axis,
           "the table base location where the switch closes"),
  AXIS_INT("homing.<x..c>", "square_input", homing.square_input[i], 0, 12,
           "a slaved axis (two driver channels): the input switch its second motor's home switch closes; C3 then squares the gantry, each motor stopping on its own switch (docs/hardware.md, \"Slaved axes\"). Left out or 0: the motors home as one",
           .optional = true),
  AXIS_NUM("homing.<x..c>", "square_offset", homing.square_offset[i], kAny, Axis,
           "a squared axis: how far the second motor then moves on its own, towards its switch, to square the gantry (WinCNC's g28altmove; a length). Left out: 0",
           .optional = true),

  {.section = "homing.<x..c>", .key = "fast_speed", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, homing.fast[i]), .range = kPositive, .unit = SettingUnit::Axis,
   .help = "this axis's first approach speed, units/s (WinCNC's g28move F). Left out: `homing.fast_speed`",
   .family = SettingFamily::Axes, .optional = true},
  {.section = "homing.<x..c>", .key = "slow_speed", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, homing.slow[i]), .range = kPositive, .unit = SettingUnit::Axis,
   .help = "this axis's measured approach speed, units/s (g28move T). Left out: `homing.slow_speed`",
   .family = SettingFamily::Axes, .optional = true},
  {.section = "homing.<x..c>", .key = "back_off", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, homing.retract[i]), .range = kPositive, .unit = SettingUnit::Axis,
   .help = "how far this axis backs off the switch after the first contact, before the measured approach (g28move R; a length). Left out: `homing.back_off`",
   .family = SettingFamily::Axes, .optional = true},
  {.section = "homing.<x..c>", .key = "offset", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, homing.offset[i]), .range = kPositive, .unit = SettingUnit::Axis,
   .help = "how far off the switch this axis ends when homed (g28move X Y Z W; a length). Left out: the back-off",
   .family = SettingFamily::Axes, .optional = true},
  {.section = "homing.<x..c>", .key = "search", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, homing.search[i]), .range = kPositive, .unit = SettingUnit::Axis,
   .help = "the longest run towards the switch before homing gives up with an error (g28move L; a length). Left out: the axis's soft-limit span plus two back-offs",
   .family = SettingFamily::Axes, .optional = true},
  {.section = "homing", .key = "require", .kind = SettingKind::Coded,
   .help = "the axes that must be homed again (C3, G28) after an E-stop or a card fault stopped a motion (WinCNC's enab A\"axes\"): a run or a typed line that moves one is refused until then, or until the operator types `confirm`; left out or `\"\"`: none",
   .optional = true, .omit_empty = true, .encode = require_text, .decode = require_read,
   .rule = "must list axes as letters x y z a b c", .docs_allowed = "letters `xyzabc`, or `\"\"`",
   .docs_type = "string"},
  INT("homing", "debounce", homing.debounce, 1, 30,
      "while homing (C3, G28), a home switch counts once its input has read closed in this many of the card's input samples in a row, so a shorter spike does not stop the approach; the table base is still taken where the run of samples began (WinCNC's g28_lim_cnt; a sample as for `limits.debounce`). Left out: 1, the first closing",
      .optional = true),
  AXIS_INT("homing.<x..c>", "input", homing.axis_input[i], 0, 12,
           "the input switch this axis's home switch closes, instead of `homing.input`: an axis homing on a switch of its own (WinCNC's g28move A, its alternate switch; docs/hardware.md, \"Homing as WinCNC describes it\"). Left out or 0: `homing.input`",
           .optional = true),
  {.section = "homing.<x..c>", .key = "park", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, homing.park[i]), .range = kAny, .unit = SettingUnit::Axis,
   .help = "where this axis goes after homing (C3, G28), at jog speed, in table base coordinates, within the soft limits: the axes homing down first, then those homing up (WinCNC's g28coord; a length). Left out: it stays off its switch",
   .family = SettingFamily::Axes, .optional = true},

  BOOL("limits", "travel_only", limits.travel_only,
       "a limit switch stops the machine only while its axis travels towards it (WinCNC's lim_mode 1); false: any limit switch that closes stops it. Every card (docs/hardware.md, \"Limit modes\"); the `[limits]` table is optional",
       .optional = true, .optional_table = true),
  INT("limits", "debounce", limits.debounce, 1, 30,
      "a limit switch stops the machine once its input has read active in this many of the card's input samples in a row (the simulated card samples every word, the PCI-7200 each pass of its feeder, the GPIO card at its input rate), so a shorter spike does not (WinCNC's lim_cnt, at most 30). Left out: 1",
      .optional = true, .optional_table = true),
  INT("limits", "cushion_steps", limits.cushion_steps, 0, 100000,
      "after a limit switch trips, every moving motor decelerates to rest within this many more steps instead of stopping dead (WinCNC's lim_step: the switch's safe compression times the lowest steps per unit); the steps are counted, and the run still ends on the limit. Every card (docs/hardware.md, \"Cushioned stop\"). Left out: 0, a dead stop",
      .optional = true, .optional_table = true),
  INT("limits", "esc_steps", limits.esc_steps, 0, 100000,
      "the same cushion after the operator's E-stop (the console's and the window's E-stop, a second Ctrl-C; WinCNC's esc_step, 200 suggested); the E-stop input itself always stops dead. Every card. Left out: 0, a dead stop",
      .optional = true, .optional_table = true),
  {.section = "limits", .key = "soft_clamp", .kind = SettingKind::Choice,
   .help = "a move beyond the soft limits: `\"off\"` refused (the file stops at its line), `\"vertical\"` Z's target clamped to its limit without a word and other axes refused (WinCNC's softlim V1), `\"all\"` every axis's target clamped, the run warned once (softlim B1; docs/hardware.md, \"Soft-limit clamp\"). Left out: `\"off\"`",
   .names = kSoftClamps, .optional = true, .optional_table = true, GANTRY_ENUM(limits.soft_clamp, SoftClamp)},

  INT("feed_override", "min", feed_override.min, 1, 200,
      "the lowest live feed override, percent of the programmed speeds, as the console's and the window's keys, the feed slider, the pendant and `--feed-override` may set it (WinCNC's override L); below `max`. Left out: 10; the `[feed_override]` table is optional",
      .optional = true, .optional_table = true),
  INT("feed_override", "max", feed_override.max, 1, 200,
      "the highest live feed override, percent (WinCNC's override H). Left out: 200",
      .optional = true, .optional_table = true),

  {.section = "simulator", .key = "home_<x..c>", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, simulator.home[i]), .range = kAny, .unit = SettingUnit::Axis,
   .help = "the simulated card's proximity switch of that axis: closed at or beyond this position on the side `homing.<axis>.direction` points to. In the card's own coordinates: the table base at power-up, before any homing",
   .family = SettingFamily::Axes, .optional = true, .optional_table = true},
  {.section = "simulator", .key = "plate_z", .kind = SettingKind::OptionalNumber,
   .field = GANTRY_FIELD(std::optional<double>, simulator.plate_z), .range = kAny, .unit = SettingUnit::Length,
   .help = "the simulated Z zero plate's top: the probe input (`inputs.probe_bit`, input 1) closes at or below this Z (a length)",
   .optional = true, .optional_table = true},
};
// clang-format on
#pragma GCC diagnostic pop

#undef NUM
#undef AXIS_NUM
#undef GROUP
#undef INT
#undef AXIS_INT
#undef BOOL
#undef AXIS_BOOL
#undef GANTRY_ENUM
#undef GANTRY_DATA
#undef GANTRY_FIELD

constexpr std::string_view kAxesPlaceholder = "<x..c>";
constexpr std::string_view kGroupsPlaceholder = "<xy,z,a,b,c>";
constexpr std::string_view kGroupNames[] = {"xy", "z", "a", "b", "c"};

std::string substitute(std::string_view text, SettingFamily f, int i) {
  std::string out(text);
  if (f == SettingFamily::None) return out;
  const std::string_view ph = f == SettingFamily::Axes ? kAxesPlaceholder : kGroupsPlaceholder;
  const size_t at = out.find(ph);
  if (at == std::string::npos) return out;
  const std::string name =
      f == SettingFamily::Axes ? std::string(1, kAxisLetters[i]) : std::string(kGroupNames[i]);
  return out.replace(at, ph.size(), name);
}

std::string quoted_names(std::span<const std::string_view> names) {
  std::string out;
  for (std::string_view n : names) out += fmt::format("{}`\"{}\"`", out.empty() ? "" : ", ", n);
  return out;
}

}  // namespace

std::string SettingRange::describe() const {
  return fmt::format("{} {} and <= {}", lo_open ? ">" : ">=", lo, hi);
}

std::string SettingRange::docs() const {
  return lo_open ? fmt::format("> {}, <= {}", lo, hi) : fmt::format("{} to {}", lo, hi);
}

std::string SettingRow::path() const {
  return section.empty() ? std::string(key) : fmt::format("{}.{}", section, key);
}

std::string SettingRow::section_at(int i) const {
  return substitute(section, family, i);
}

std::string SettingRow::key_at(int i) const {
  return substitute(key, family, i);
}

std::string SettingRow::path(int i) const {
  return section.empty() ? key_at(i) : fmt::format("{}.{}", section_at(i), key_at(i));
}

int SettingRow::size() const {
  return family == SettingFamily::Axes ? kAxisCount : family == SettingFamily::Groups ? 5 : 1;
}

double SettingRow::fallback() const {
  static const Settings defaults;
  return get(defaults);
}

SettingRange SettingRow::range_in(const Settings& s, int i) const {
  SettingRange r = range;
  if (most) r.hi = std::min(r.hi, most(s, i));
  return r;
}

std::string SettingRow::type_name() const {
  if (!docs_type.empty()) return std::string(docs_type);
  switch (kind) {
    case SettingKind::Number:
    case SettingKind::OptionalNumber: return "number";
    case SettingKind::Integer: return "integer";
    case SettingKind::Bool: return "bool";
    case SettingKind::Texts: return "array of strings";
    default: return "string";
  }
}

std::string SettingRow::allowed() const {
  if (!docs_allowed.empty()) return std::string(docs_allowed);
  const std::string opt = optional ? "; optional" : "";
  switch (kind) {
    case SettingKind::Number:
    case SettingKind::OptionalNumber:
    case SettingKind::Integer: return range.docs() + opt;
    case SettingKind::Bool: return "`true`, `false`" + opt;
    case SettingKind::Choice:
    case SettingKind::Text: return quoted_names(names) + opt;
    case SettingKind::IntList:
    case SettingKind::NumberList:
      return count ? fmt::format("{} values, each {}", count, range.docs())
                   : fmt::format("`\"a, b, ...\"`, each {}", range.docs());
    default: return "any" + opt;
  }
}

std::span<const SettingRow> settings_schema() {
  return kRows;
}

bool for_each_setting(const std::function<bool(const SettingRow& row, int i)>& visit) {
  const std::span<const SettingRow> rows = kRows;
  for (size_t r = 0; r < rows.size();) {
    size_t end = r + 1;  // a run of rows of one family in one table
    if (rows[r].family != SettingFamily::None)
      while (end < rows.size() && rows[end].family == rows[r].family &&
             rows[end].section == rows[r].section)
        ++end;
    for (int i = 0; i < rows[r].size(); ++i)
      for (size_t k = r; k < end; ++k)
        if (!visit(rows[k], i)) return false;
    r = end;
  }
  return true;
}

std::span<const SettingRow> settings_schema(std::string_view section) {
  const SettingRow* begin = std::find_if(std::begin(kRows), std::end(kRows),
                                         [&](const SettingRow& r) { return r.section == section; });
  const SettingRow* end = std::find_if(begin, std::end(kRows),
                                       [&](const SettingRow& r) { return r.section != section; });
  return {begin, end};
}

const SettingRow& setting_row(std::string_view path) {
  // path() compared without building it: the command table looks up a few hundred keys
  // whenever a process starts (a fifth of a one-line `gantry check`'s instructions).
  for (const SettingRow& r : kRows) {
    const std::string_view sec = r.section, key = r.key;
    if (sec.empty() ? path == key
                    : path.size() == sec.size() + 1 + key.size() && path.starts_with(sec) &&
                          path[sec.size()] == '.' && path.ends_with(key))
      return r;
  }
  throw std::out_of_range(fmt::format("no setting {}", path));
}

bool set_setting(Settings& s, const SettingRow& row, double v, int i) {
  if (!row.range.contains(v)) return false;
  row.number(s, i) = v;
  return true;
}

int setting_axis(SettingFamily f, int i) {
  if (f == SettingFamily::Groups) return i == 0 ? 0 : i + 1;
  return i;
}

}  // namespace gantry
