// The machine profile: everything the pipeline needs to know about one machine.
#pragma once

#include <array>
#include <cmath>  // fmod
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gantry/core/axes.hpp"        // kAxisCount
#include "gantry/core/diagnostic.hpp"  // Diagnostic for load errors

namespace gantry {

enum class Units { Inches, Millimetres };

// Which OpenSBP the part files are written in: SB3 (trigonometry in radians) or FabMo
// (degrees).
enum class Dialect { SB3, FabMo };
// Which G-code G-code files are written in: LinuxCNC's RS274/NGC (standard) or WinCNC's
// (docs/gcode.md, "The WinCNC dialect").
enum class GcodeDialect { Standard, WinCNC };

// One speed (or ramp speed) per group, as MS/JS/VS/VR name them: XY is a vector speed.
struct GroupSpeeds {
  double xy = 0, z = 0, a = 0, b = 0, c = 0;
};

struct AxisSettings {
  double steps_per_unit = 1;  // motor steps per unit (in, mm or degree)
  double max_speed = 1;       // hardware speed limit, units/s
  double max_accel = 1;       // hardware acceleration limit, units/s^2
  double min = 0, max = 0;    // soft limits (table envelope), units
  double backlash = 0;        // slack taken up at each reversal, units (docs/hardware.md)
  double wrap = 0;            // the position is reported modulo this (a rotary axis: 360); 0: not
};

// The position of an axis as reported (readouts, run reports): modulo its `wrap` when set,
// in [0, wrap).
inline double reported_position(const AxisSettings& a, double v) {
  if (a.wrap <= 0) return v;
  const double r = std::fmod(v, a.wrap);
  return r < 0 ? r + a.wrap : r;
}

struct SpeedSettings {  // VS: the operator's move and jog speeds
  GroupSpeeds move, jog;
};

struct RampSettings {  // VR: SB3 ramp model values
  GroupSpeeds move_ramp_speed, jog_ramp_speed;
  double move_ramp_rate = 0.2;  // distance over which speed changes by 2 units/s
  double jog_ramp_rate = 0.2;
  double threshold_3d = 100;  // percent
  double min_distance = 0.15;
  double slow_corner = 65;  // percent
  double keypad_ramp_rate = 0.2;
  double small_circle = 0.25;
};

// How the planner joins moves: SB3's ramp model, junction-deviation cornering, or a stop
// at every move (the baseline that the other two are measured against).
enum class PlannerMode { SB3, Junction, Stop };

struct PlannerSettings {
  PlannerMode mode = PlannerMode::SB3;
  double corner_jump = 0.11;          // largest instant speed change, fraction of max_speed
  double junction_deviation = 0.002;  // junction mode: corner rounding the speed allows, units
  double chord_tolerance = 0.0005;    // arcs run as chords at most this far from the arc, units
  double jerk = 0;                    // S-curve ramps within this jerk, units/s^3; 0: linear
  int lookahead = 1024;               // moves planned ahead, at least
};

struct PinSettings {  // one axis's bits in the card's 32-bit output word
  int step_bit = 0;
  int dir_bit = 8;
  bool invert_dir = false;
  bool step_active_low = false;  // pulse goes low (negative-edge drives)
};

// Other bits of the output word. -1: not wired.
struct OutputSettings {
  int charge_pump_bit = 16;       // a square wave while the card plays: drives stay enabled
  double charge_pump_hz = 10000;  // only while pulses flow (WinCNC's `watch=` watchdog)
  int spindle_bit = 17;           // on while the spindle runs
  std::vector<int> aux_bits;      // output switches 1, 2, ... (SO); -1: that one not wired
};

// The spindle's speed signal, set by TR (docs/settings.md, [spindle]). With `pwm_bit` wired,
// that output bit carries a square wave whose duty is rpm / max_rpm (a PWM-to-0-10 V board
// feeds it to the VFD's speed input); its on/off is output switch 1, as on every ShopBot.
struct SpindleSettings {
  int pwm_bit = -1;        // -1: no speed output; TR only records the RPM
  double pwm_hz = 1000;    // the square wave's frequency (speed_mode pwm)
  double max_rpm = 24000;  // the RPM at 100 % duty, and the most TR may ask for
  // How `pwm_bit` carries the speed: a duty at pwm_hz (a PWM-to-0-10 V board), or a square
  // wave whose frequency is rpm / max_rpm x max_hz (a VFD's pulse-train input; WinCNC's
  // spindle=T3 on CN2 pin 11).
  enum class SpeedMode { Pwm, Frequency } speed_mode = SpeedMode::Pwm;
  double max_hz = 1000;  // frequency mode: the frequency at max_rpm
  // M4: the output switch that makes the spindle run counter-clockwise (0: none, M4 refused).
  // Direction wiring: it selects the direction while output 1 runs the spindle; run wiring
  // (a VFD's FWD and REV terminals): output 1 runs it forward and this one in reverse.
  int reverse_output = 0;
  enum class ReverseWiring { Direction, Run } reverse_wiring = ReverseWiring::Direction;
  double spin_up_s = 0;    // the machine waits this long after the spindle starts
  double spin_down_s = 0;  // ... and after it stops, before anything else moves
  // An input switch (1-12) the drive closes when the spindle is at speed (0: none): after a
  // start or a change of speed the machine waits for it, at most at_speed_timeout_s.
  int at_speed_input = 0;
  double at_speed_timeout_s = 10;
  // A D/A converter's input word (WinCNC's da=): output bits, least significant first, that
  // hold rpm / max_rpm x (2^n - 1) while the spindle's speed stands (empty: none). A speed
  // output as pwm_bit is; the profile gives one of them.
  std::vector<int> dac_bits;
  double initial_rpm = 0;  // the RPM TR and S hold at start (WinCNC's spindle I, da I)
  bool speed_output() const { return pwm_bit >= 0 || !dac_bits.empty(); }
};

// An automatic tool changer (docs/hardware.md, "Tool changer"): a rack of slots, one per tool
// (slot k holds tool k), a drawbar output, and a tool-length sensor. All positions are table
// base coordinates. No slots: tool changes are manual (the operator is asked).
struct ToolChangerSettings {
  std::vector<std::array<double, 2>> slots;  // X, Y of each slot
  double slot_z = 0;       // Z where a tool sits in its slot (WinCNC's atc H: unload height)
  double clear_z = 0;      // Z the spindle travels at over the rack and to the sensor
  int release_output = 0;  // the output switch that opens the drawbar (1-12)
  double release_s = 0.5;  // wait after the drawbar opens or closes
  int sensor_input = 0;    // the tool-length sensor's input switch (1-12; 0: none)
  double sensor_x = 0, sensor_y = 0;  // where it is (WinCNC's g37 X Y)
  double sensor_start_z = 0;  // Z the probe starts from, at jog speed (above every tool's trip)
  double sensor_min_z = 0;  // the lowest Z the probe goes to: the sensor never closing is an error
  double sensor_speed = 0.5;  // the probe's speed, units/s (g37 F)
  double sensor_zero_z = 0;   // Z at which a tool of length 0 would close it: length = trip - this
  bool rack() const { return !slots.empty(); }
};

// Bits of the card's 32-bit input word. -1: not wired. A switch is "active" when its bit
// reads 1, or 0 for the active-low ones (normally-closed E-stop chains read 0 when broken).
struct InputSettings {
  int estop_bit = 0;
  bool estop_active_low = true;
  int probe_bit = 1;
  std::array<int, kAxisCount> min_bit{}, max_bit{}, home_bit{};  // limit and proximity switches
  bool limits_active_low = false;
  // The input switches 1-12 that part files read (%(51)...) and watch (ON INPUT, probes): the
  // bit each one is (-1: not wired). A switch reads closed (1) when its bit reads 1. Several
  // may name a bit already named above (the Z zero plate is the probe bit).
  std::array<int, 12> switch_bits{1, -1, 8, 0, -1, -1, -1, -1, -1, -1, -1, -1};
};

// C3's homing on proximity switches. Each axis of `order` runs towards its switch at
// fast_speed until the switch closes, backs off by back_off, comes back at slow_speed, and
// the table base location where the switch closed is set to at[axis]; the tool then backs
// off the switch again. Lengths in the profile's units.
struct HomingSettings {
  int input = 3;  // the input switch the proximity switches close (1-12)
  std::string order = "zxy";
  double fast_speed = 1.0;  // units/s
  double slow_speed = 0.1;
  double back_off = 0.25;
  std::array<int, kAxisCount> direction{-1, -1, 1, -1, -1, -1};  // towards the switch
  std::array<double, kAxisCount> at{};                           // table base at the switch
  // A slaved axis (two driver channels, docs/hardware.md): the input switch (1-12) its second
  // motor's home switch closes; C3 then squares the gantry. 0: none, both motors home as one.
  std::array<int, kAxisCount> square_input{};
  // How far the second motor then moves on its own past where its switch closed (WinCNC's
  // g28altmove): the squaring correction. Units.
  std::array<double, kAxisCount> square_offset{};
  // Per axis, as WinCNC's g28move lines give them (nullopt: the values above): the first
  // approach's speed (F), the measured approach's (T), the back-off between them (R), how far
  // off the switch the axis ends (X Y Z W), and the longest search for the switch (L; left
  // out: the axis's soft-limit span and two back-offs).
  std::array<std::optional<double>, kAxisCount> fast{}, slow{}, retract{}, offset{}, search{};
  // The axes that must be homed again after an E-stop or a card fault stopped the machine
  // mid-motion (WinCNC's enab A"axes"): bit i, axis i. A run moving one of them is refused
  // until C3 (or G28) homes it, or the operator confirms the position.
  std::uint32_t require = 0;
  // Input samples in a row a home switch must read closed before homing takes it (WinCNC's
  // g28_lim_cnt; limits.debounce is lim_cnt, for the limit switches).
  int debounce = 1;
  // Per axis: the input switch (1-12) its home switch closes, instead of `input` (0: `input`):
  // WinCNC's g28move A, homing on another switch than the others'.
  std::array<int, kAxisCount> axis_input{};
  // Per axis: where it goes after homing (table base; WinCNC's g28coord). nullopt: it stays.
  std::array<std::optional<double>, kAxisCount> park{};
};

// What a move beyond the soft limits does (WinCNC's softlim B and V).
enum class SoftClamp { Off, Vertical, All };

// [limits]: how a limit switch stops the machine (WinCNC's lim_mode, lim_cnt, lim_step,
// esc_step) and what a move beyond the soft limits does (softlim B1, V1).
struct LimitSettings {
  bool travel_only = false;  // only a switch on the side the axis travels to stops it
  int debounce = 1;          // input samples in a row a limit input must read active to count
  int cushion_steps = 0;     // steps of deceleration after a hit, instead of a dead stop
  int esc_steps = 0;         // the same after the operator's E-stop
  SoftClamp soft_clamp = SoftClamp::Off;  // refused (Off), or clamped: Z only, or every axis
};

// [feed_override]: the bounds of the operator's live feed override, percent of the programmed
// speeds (WinCNC's override L and H), for every front end that changes it.
struct FeedOverrideSettings {
  int min = 10;
  int max = 200;
};

// The simulated card's machine (card.type "sim"; docs/hardware.md): where its proximity
// switches and its Z zero plate are, in the card's own coordinates (the table base at power-up,
// before any homing), in the profile's units. Each is optional: absent, there is none.
struct SimulatorSettings {
  // The proximity (home) switch of each axis: closed at or beyond this position on the side
  // homing.<axis>.direction points to (at or below it for "-", at or above it for "+").
  std::array<std::optional<double>, kAxisCount> home{};
  std::optional<double> plate_z;  // the Z zero plate's top: the probe input closes at or below
};

// A GPIO line and the bit of the card's word it carries (type = "gpiod").
struct GpioLineBit {
  int bit = 0;
  unsigned line = 0;
};

struct CardSettings {
  std::string type = "sim";  // "sim", "pci7200", "gpiod"
  std::string gpiod_chip = "/dev/gpiochip0";
  std::vector<GpioLineBit> gpiod_outputs;  // output-word bit -> line
  std::vector<GpioLineBit> gpiod_inputs;   // line -> input-word bit
  double clock_hz = 4'000'000;             // PCI-7200 8254 timer clock
  int pacer_divisor = 20;                  // pacer = clock / divisor
  double step_pulse_us = 5;
  double dir_setup_us = 5;
  // The bounded lead: at most this much motion (ms) generated ahead of the tick a real card
  // has played; a hold begins within it (docs/controller.md, "The lead into the card").
  double lead_ms = 20;

  double pacer_hz() const { return clock_hz / pacer_divisor; }
};

// VC: the cutter and the heights it is pulled up to.
struct CutterSettings {
  double diameter = 0.25;       // used by the O and I (outside, inside) cut offsets
  double safe_z = 1.0;          // working Z that MH and JH raise the tool to first
  double safe_a = 1.0;          // the same for an A axis used as a second Z
  bool plunge_negative = true;  // VC 5 "-": a negative Z goes into the material
  double pocket_overlap = 10;   // percent of the cutter diameter, pocketing passes
  // Z- or A-triggered output switch (an air drill): thresholds, the axis and the switch.
  double trigger_on = 0, trigger_off = 0;
  int trigger_axis = 2;    // 2 Z, 3 A
  int trigger_output = 3;  // output switch 3-12, not 4
};

struct TabSettings {  // VB: tabs left on the last pass of a cut
  double pull_up = 0.1, spacing = 4, size = 1, leads = 0.5;
};

// Units of a rotary-capable axis (VD 4, 5): a length or degrees.
enum class AxisUnit { Inches, Millimetres, Degrees };

struct DisplaySettings {  // VD
  int axes = 3;           // axes shown and used: 3 XYZ, 4 adds A, 5 adds B, 6 adds C
  std::array<AxisUnit, 3> rotary_units{AxisUnit::Degrees, AxisUnit::Degrees,
                                       AxisUnit::Degrees};  // A, B, C
  bool show_comments = false;       // part-file comments shown as the file runs
  double keypad_step = 0.1;         // SK fixed-distance step, units
  int keypad_remote = 0;            // 0 keyboard, 1 pendant on the inputs, 2 other
  bool part_file_log = true;        // a log line per part file run
  bool system_log = true;           // a system log for diagnostics
  bool show_progress = false;       // a progress bar while a file runs
  bool keypad_outputs_off = false;  // output switches off when the keypad closes
  // The axis (3 A, 4 B, 5 C) shown and programmed as W, WinCNC's second vertical head; -1: none.
  int w_axis = -1;
};

struct PreviewSettings {  // VP
  double grid = 6, table_x = 24, table_y = 18, table_z = 6;
  bool simulate_cutting = false, draw_tool = true, start_at_location = true, show_jogs = true;
};

struct AccessorySettings {  // VH: torch height control, laser PWM, heater
  int mode = 0;             // 1 on, 0 off (needs switches.accessory)
  double plasma_rate = 0.25, pwm_low = 0, pwm_high = 0, pulse_khz = 5.4, low_cycle = 3,
         temperature = 0;
};

struct SwitchSettings {                // VN
  bool limits = true;                  // limit switches stop the machine
  bool stop_normally_open = false;     // input 4 (stop) wiring; false: normally closed
  int accessory = 0;                   // 0 none, 1 torch height, 2 laser, 3 analog
  std::array<int, 12> input_modes{};   // 0 standard, 1 NO limit, 2 NC limit, 3 NO stop, 4 NC stop
  std::array<int, 12> output_modes{};  // 0-5, SB3's output switch modes
};

struct DriverSettings {  // VI: which axis each driver channel 1-6 drives
  std::array<int, kAxisCount> channel_axis{0, 1, 2, 3, 4, 5};
};

struct CalibrationSettings {                                   // VU beyond steps per unit
  double circle_resolution = 0.05;                             // arc segment length, units
  std::array<double, 5> resolution_multiplier{1, 1, 1, 1, 1};  // X..B, jog resolution shift
  int step_divider = 1;  // 1-100: speeds run 1/n of their value (very slow moves)
  bool no_resolution_shift = false;
};

// Values the commands read beyond the groups above.
struct MachineSettings {
  bool limit_checking = true;  // SF, VL 9: moves checked against the soft limits
  double warning_s = 2;        // SW: warning before movement starts, s; 0 none
  double max_dwell_s = 86400;  // the longest wait a file may ask for (PAUSE n, G4), s
  // SO 4,-1..-4: -1 to -3 switch 4 comes on with the warning and goes off when the run's
  // motion ends (it drives a "machine moving" light); -4 it is an ordinary switch.
  int switch4_mode = -1;
  std::string editor;  // FE's program ("": $VISUAL, $EDITOR); read from the profile only
};

// Where part files may read and write besides their job's folder and Gantry's data folder
// (docs/security.md). Only the machine profile's count: a values file's or UR's are ignored.
struct FilesSettings {
  std::vector<std::string> allow;  // folders, absolute or ~/...
};

// [pendant]: a gamepad used as a pendant, keys bound to the pendant's actions, the macros'
// lines and the XHC display's frame (the XHC USB pendant itself needs no setting: it is found
// when plugged in). docs/hardware.md, "A gamepad as a pendant"; docs/console.md, "Pendant".
struct PendantSettings {
  std::string gamepad = "off";               // "off", "auto" (the first found) or a device path
  std::array<std::string, kAxisCount> gamepad_jog{};  // per axis: the sticks, "-ABS_Y, -ABS_HAT0Y"; "": usual
  std::string gamepad_buttons;               // "BTN_SOUTH = start/pause, ..."; "": the usual ones
  std::vector<std::string> keys;             // "F5 = start/pause", "Ctrl+Right = jog x+", ...
  std::array<std::string, 10> macros{};      // macro_1..macro_10: a line ("C3") or a part file
  std::string xhc_coordinates = "work";      // the XHC display at start: "work" or "machine"
};

// [friendly_motion]: a Friendly Motion laser table's hardware (docs/friendlymotion.md): the
// beam's gate (M100's output, the output G16's strokes switch) and its timing, the resistor
// trimmer's relay matrix (P), the X-Y feed range. The table is optional.
struct FriendlyMotionSettings {
  int laser_output = 1;      // the output switch that gates the beam; 0: none
  double laser_on_s = 0;     // the wait after the beam switches on, before the move (s)
  double laser_off_s = 0;    // ... after it switches off (s)
  std::vector<int> relay_a;  // P: the switch joining probe 1, 2, ... to bus A (0: none)
  std::vector<int> relay_b;  // ... to bus B
  std::optional<double> feed_min, feed_max;  // the X-Y feed range, units/s; none: 0.005-6 in/s
};

struct Settings {
  std::string name;
  Units units = Units::Inches;
  Dialect dialect = Dialect::SB3;
  GcodeDialect gcode_dialect = GcodeDialect::Standard;
  // G-code's tool table (docs/gcode.md, "Tool table"): the key as written ("" none: every
  // tool has length 0), and the file it names, relative paths from the profile's folder
  // (`gantry ... --tool-table FILE` sets the file). Read from the profile only.
  std::string tool_table;
  std::string tool_table_path;
  // Folders where G-code's `o<name> call` finds name.ngc after the calling file's folder
  // (docs/gcode.md, "O-words"): the key as written, and the folders it names (relative ones
  // from the profile's folder; each must exist). `--subroutines DIR` adds folders before
  // these. Read from the profile only.
  std::vector<std::string> subroutines;
  std::vector<std::string> subroutine_paths;
  std::array<AxisSettings, kAxisCount> axes{};
  SpeedSettings speeds;
  RampSettings ramps;
  PlannerSettings planner;
  CardSettings card;
  std::array<PinSettings, kAxisCount> pins{};
  OutputSettings outputs;
  SpindleSettings spindle;
  ToolChangerSettings toolchanger;
  InputSettings inputs;
  HomingSettings homing;
  LimitSettings limits;
  FeedOverrideSettings feed_override;
  SimulatorSettings simulator;
  CutterSettings cutter;
  TabSettings tabs;
  DisplaySettings display;
  PreviewSettings preview;
  AccessorySettings accessories;
  SwitchSettings switches;
  DriverSettings drivers;
  CalibrationSettings calibration;
  MachineSettings machine;
  FilesSettings files;
  PendantSettings pendant;
  FriendlyMotionSettings friendly_motion;
};

// The letter an axis is shown and programmed by: X Y Z A B C, or W for the axis the profile
// names W (display.w_axis; docs/hardware.md, "The W axis").
inline char axis_name(const Settings& s, int i) {
  return i == s.display.w_axis ? 'W' : "XYZABC"[i];
}
// The six letters, in axis order ("XYZWBC" when A is W).
inline std::string axis_names(const Settings& s) {
  std::string out = "XYZABC";
  if (s.display.w_axis >= 0) out[static_cast<size_t>(s.display.w_axis)] = 'W';
  return out;
}

// The result of loading a profile: settings, or every problem found in it.
struct SettingsLoad {
  Settings settings;
  std::vector<Diagnostic> errors;
  bool ok() const { return errors.empty(); }
};

// Parses and validates a profile. `origin` names it in messages (a path).
SettingsLoad parse_settings(const std::string& text, const std::string& origin);

// The rules that tie keys together (speeds within axis limits, step rates within the card,
// soft limits ordered, pins distinct), as messages; empty when `s` keeps them all.
std::vector<std::string> settings_problems(const Settings& s);

// Converts every length, speed and acceleration to `to` (VD's linear units): lengths scale
// by 25.4, steps per unit inversely. A, B and C follow when their unit is a length.
void convert_units(Settings& s, Units to);
// The factor from the profile's units to `to`: 1, 25.4 or 1/25.4.
double units_factor(Units from, Units to);
// Per axis, the factor convert_units(s, to) applies: X, Y, Z always; A, B, C only when VD
// gives them a length unit.
std::array<double, kAxisCount> units_scale(const Settings& s, Units to);
// Scales a speed group as convert_units does (XY by X's factor, 12 significant digits).
void scale_speeds(GroupSpeeds& g, const std::array<double, kAxisCount>& scale);

// Reads and validates a profile file; a missing file is an error like any other.
SettingsLoad load_settings_file(const std::string& path);

// The shipped default profile (settings/default.toml, compiled in).
const std::string& default_profile_text();
Settings default_settings();

const char* units_name(Units u);
const char* planner_mode_name(PlannerMode m);

}  // namespace gantry
