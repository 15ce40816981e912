// The %(n) table: handbook numbering, value mapping from the snapshot, and its Markdown page.
#include "gantry/interp/system_variables.hpp"

#include <algorithm>  // lower_bound
#include <array>
#include <cmath>   // floor, llround
#include <cstdio>  // snprintf
#include <ctime>   // time, localtime_r
#include <string>

namespace gantry {
namespace {

using Info = SystemVariableInfo;

// The handbook's list (Part File Programming Handbook, "System Variables" at its end), in
// its order. Numbers it leaves blank (26, 45, 50, 59, 64-65, 69-70, 110, 140, 143, 148-149,
// 157, 160, 162-169) are not variables, so they have no row.
constexpr std::array kTable{
    Info{1, "Location X", "units", false, "Working X position (the position readout)."},
    Info{2, "Location Y", "units", false, "Working Y position."},
    Info{3, "Location Z", "units", false, "Working Z position."},
    Info{4, "Location A", "units", false, "Working A position."},
    Info{5, "Location B", "units", false, "Working B position."},
    Info{6, "Base Coord X", "units", false, "X in table base coordinates (ZT, ST, VA 6)."},
    Info{7, "Base Coord Y", "units", false, "Y in table base coordinates (VA 7)."},
    Info{8, "Base Coord Z", "units", false, "Z in table base coordinates (VA 8)."},
    Info{9, "Base Coord A", "units", false, "A in table base coordinates (VA 9)."},
    Info{10, "Base Coord B", "units", false, "B in table base coordinates (VA 10)."},
    Info{11, "Min Table Limit X", "units", false, "Lowest X the soft limits allow (VL 1)."},
    Info{12, "Max Table Limit X", "units", false, "Highest X the soft limits allow (VL 2)."},
    Info{13, "Min Table Limit Y", "units", false, "Lowest Y the soft limits allow (VL 3)."},
    Info{14, "Max Table Limit Y", "units", false, "Highest Y the soft limits allow (VL 4)."},
    Info{15, "Min Table Limit Z", "units", false, "Deepest Z the soft limits allow (VL 5)."},
    Info{16, "Max Table Limit Z", "units", false, "Highest Z the soft limits allow (VL 6)."},
    Info{17, "Min Table Limit A", "units", false, "Lowest A the soft limits allow (VL 7)."},
    Info{18, "Max Table Limit A", "units", false, "Highest A the soft limits allow (VL 8)."},
    Info{19, "Min Table Limit B", "units", false, "Lowest B the soft limits allow (VL 10)."},
    Info{20, "Max Table Limit B", "units", false, "Highest B the soft limits allow (VL 11)."},
    Info{21, "Distance", "0-1", false, "Distance mode: 0 absolute (SA), 1 relative (SR)."},
    Info{22, "Mode", "0-1", false, "Execution mode: 0 move/cut (SM), 1 preview (SP)."},
    Info{23, "Cutter Dia", "units", false, "Diameter of the current cutter (VC 1)."},
    Info{24, "SW Delay", "s", false, "Length of the warning before motion starts (SW)."},
    Info{25, "Unit", "0-1", false, "Linear units: 0 inches, 1 millimetres (VD 3)."},
    Info{27, "Number of Axes", "3-5", false, "How many axes are active (VD 2)."},
    Info{28, "Safe_Z", "units", false, "Height Z lifts to before transit moves (VC 4)."},
    Info{29, "Safe_A", "units", false, "Pull-up position of A before transit moves (VC 7)."},
    Info{30, "Number of Axes to Ck Lim", "1-5", false, "How many axes soft limits check."},
    Info{31, "WUx", "steps/unit", false, "Motor steps per unit of X (VU 1)."},
    Info{32, "WUy", "steps/unit", false, "Motor steps per unit of Y (VU 2)."},
    Info{33, "WUz", "steps/unit", false, "Motor steps per unit of Z (VU 3)."},
    Info{34, "WUa", "steps/unit", false, "Motor steps per unit of A (VU 4)."},
    Info{35, "WUb", "steps/unit", false, "Motor steps per unit of B (VU 9)."},
    Info{36, "Driver Channel 1", "axis letter", true, "Axis that driver channel 1 moves (VI)."},
    Info{37, "Driver Channel 2", "axis letter", true, "Axis that driver channel 2 moves (VI)."},
    Info{38, "Driver Channel 3", "axis letter", true, "Axis that driver channel 3 moves (VI)."},
    Info{39, "Driver Channel 4", "axis letter", true, "Axis that driver channel 4 moves (VI)."},
    Info{40, "Driver Channel 5", "axis letter", true, "Axis that driver channel 5 moves (VI)."},
    Info{41, "Tabbing Dist Up", "units", false, "How far the cutter rises to leave a tab (VB 1)."},
    Info{42, "Tabbing Dist Next", "units", false, "Spacing from one tab to the next (VB 2)."},
    Info{43, "Tabbing Size", "units", false, "Width of each tab (VB 3)."},
    Info{44, "Tabbing Lead Size", "units", false, "Length of the incline into a tab (VB 4)."},
    Info{46, "Inp #3 Mode", "0-1", false, "Legacy 0/1 mode flag of input switch 3."},
    Info{47, "Inp #4 Mode", "0-1", false,
         "Stop input 4 wiring: 0 normally closed, 1 normally open (VN 2)."},
    Info{48, "Software Version", "text", true, "Version of the controlling software."},
    Info{49, "Firmware Version", "integer", false, "Firmware version of the step card."},
    Info{51, "Inp #1", "0-1", false, "Input switch 1: 1 closed, 0 open."},
    Info{52, "Inp #2", "0-1", false, "Input switch 2: 1 closed, 0 open."},
    Info{53, "Inp #3", "0-1", false, "Input switch 3: 1 closed, 0 open."},
    Info{54, "Inp #4", "0-1", false, "Input switch 4: 1 closed, 0 open."},
    Info{55, "Inp #5", "0-1", false, "Input switch 5: 1 closed, 0 open."},
    Info{56, "Inp #6", "0-1", false, "Input switch 6: 1 closed, 0 open."},
    Info{57, "Inp #7", "0-1", false, "Input switch 7: 1 closed, 0 open."},
    Info{58, "Inp #8", "0-1", false, "Input switch 8: 1 closed, 0 open."},
    Info{60, "Current File Name", "text", true, "Absolute path of the part file now running."},
    Info{61, "X Offset Current File", "units", false, "X offset the running file has (FP)."},
    Info{62, "Y Offset Current File", "units", false, "Y offset the running file has (FP)."},
    Info{63, "Z Offset Current File", "units", false, "Z offset the running file has (FP)."},
    Info{66, "X Proportion Current File", "ratio", false, "X scale of the running file (FP)."},
    Info{67, "Y Proportion Current File", "ratio", false, "Y scale of the running file (FP)."},
    Info{68, "Z Proportion Current File", "ratio", false, "Z scale of the running file (FP)."},
    Info{71, "MoveSpeed X", "units/s", false, "Cutting speed in XY (MS 1, VS 1)."},
    Info{72, "MoveSpeed Y", "units/s", false, "Cutting speed in XY, same as %(71)."},
    Info{73, "MoveSpeed Z", "units/s", false, "Cutting speed of Z (MS 2, VS 2)."},
    Info{74, "MoveSpeed A", "units/s", false, "Cutting speed of A (MS 3, VS 3)."},
    Info{75, "MoveSpeed B", "units/s", false, "Cutting speed of B (MS 4, VS 4)."},
    Info{76, "JogSpeed X", "units/s", false, "Rapid speed in XY (JS 1, VS 5)."},
    Info{77, "JogSpeed Y", "units/s", false, "Rapid speed in XY, same as %(76)."},
    Info{78, "JogSpeed Z", "units/s", false, "Rapid speed of Z (JS 2, VS 6)."},
    Info{79, "JogSpeed A", "units/s", false, "Rapid speed of A (JS 3, VS 7)."},
    Info{80, "JogSpeed B", "units/s", false, "Rapid speed of B (JS 4, VS 8)."},
    Info{81, "MoveRamp X", "units/s", false, "Speed cutting moves in XY ramp from/to (VR 1)."},
    Info{82, "MoveRamp Y", "units/s", false, "Same as %(81): XY shares one ramp speed."},
    Info{83, "MoveRamp Z", "units/s", false, "Speed cutting moves of Z ramp from/to (VR 2)."},
    Info{84, "MoveRamp A", "units/s", false, "Speed cutting moves of A ramp from/to (VR 3)."},
    Info{85, "MoveRamp B", "units/s", false, "Speed cutting moves of B ramp from/to (VR 4)."},
    Info{86, "JogRamp X", "units/s", false, "Speed rapid moves in XY ramp from/to (VR 5)."},
    Info{87, "JogRamp Y", "units/s", false, "Same as %(86): XY shares one ramp speed."},
    Info{88, "JogRamp Z", "units/s", false, "Speed rapid moves of Z ramp from/to (VR 6)."},
    Info{89, "JogRamp A", "units/s", false, "Speed rapid moves of A ramp from/to (VR 7)."},
    Info{90, "JogRamp B", "units/s", false, "Speed rapid moves of B ramp from/to (VR 8)."},
    Info{91, "Mode Input #1", "0-4", false, "Role of input switch 1, 0 standard (VN)."},
    Info{92, "Mode Input #2", "0-4", false, "Role of input switch 2 (VN)."},
    Info{93, "Mode Input #3", "0-4", false, "Role of input switch 3 (VN)."},
    Info{94, "Mode Input #4", "0-4", false, "Role of input switch 4 (VN)."},
    Info{95, "Mode Input #5", "0-4", false, "Role of input switch 5 (VN)."},
    Info{96, "Mode Input #6", "0-4", false, "Role of input switch 6 (VN)."},
    Info{97, "Mode Input #7", "0-4", false, "Role of input switch 7 (VN)."},
    Info{98, "Mode Input #8", "0-4", false, "Role of input switch 8 (VN)."},
    Info{99, "Torch Height", "0-1", false, "1 while torch height / laser control is on (VH 1)."},
    Info{100, "Full Output Byte", "0-255", false, "Outputs 1-8 as bits; output n is bit n-1."},
    Info{101, "Status Out #1", "0-1", false, "Output switch 1: 1 on, 0 off."},
    Info{102, "Status Out #2", "0-1", false, "Output switch 2: 1 on, 0 off."},
    Info{103, "Status Out #3", "0-1", false, "Output switch 3: 1 on, 0 off."},
    Info{104, "Status Out #4", "0-1", false, "Output switch 4: 1 on, 0 off."},
    Info{105, "Status Out #5", "0-1", false, "Output switch 5: 1 on, 0 off."},
    Info{106, "Status Out #6", "0-1", false, "Output switch 6: 1 on, 0 off."},
    Info{107, "Status Out #7", "0-1", false, "Output switch 7: 1 on, 0 off."},
    Info{108, "Status Out #8", "0-1", false, "Output switch 8: 1 on, 0 off."},
    Info{109, "Mode #4", "-1 to -4", false,
         "How output 4 follows motion (SO 4,-1 .. SO 4,-4; -4 disables it)."},
    Info{111, "Mode Output #1", "0-5", false, "End-of-file and stop behaviour of output 1 (VN)."},
    Info{112, "Mode Output #2", "0-5", false, "Behaviour mode of output 2 (VN)."},
    Info{113, "Mode Output #3", "0-5", false, "Behaviour mode of output 3 (VN)."},
    Info{114, "Mode Output #4", "0-5", false, "Behaviour mode of output 4 (VN)."},
    Info{115, "Mode Output #5", "0-5", false, "Behaviour mode of output 5 (VN)."},
    Info{116, "Mode Output #6", "0-5", false, "Behaviour mode of output 6 (VN)."},
    Info{117, "Mode Output #7", "0-5", false, "Behaviour mode of output 7 (VN)."},
    Info{118, "Mode Output #8", "0-5", false, "Behaviour mode of output 8 (VN)."},
    Info{119, "Mode Output #9", "0-5", false, "Behaviour mode of output 9 (VN)."},
    Info{120, "Mode Output #10", "0-5", false, "Behaviour mode of output 10 (VN)."},
    Info{121, "Mode Output #11", "0-5", false, "Behaviour mode of output 11 (VN)."},
    Info{122, "Mode Output #12", "0-5", false, "Behaviour mode of output 12 (VN)."},
    Info{123, "IndexerON", "0-1", false, "1 while the MI indexer or oscillation runs."},
    Info{124, "Analog Input #1", "0-9", false, "Reading of analog input 1."},
    Info{125, "Analog Input #2", "0-9", false, "Reading of analog input 2."},
    Info{126, "Inp #9", "0-1", false, "Input switch 9: 1 closed, 0 open."},
    Info{127, "Inp #10", "0-1", false, "Input switch 10: 1 closed, 0 open."},
    Info{128, "Inp #11", "0-1", false, "Input switch 11: 1 closed, 0 open."},
    Info{129, "Inp #12", "0-1", false, "Input switch 12: 1 closed, 0 open."},
    Info{130, "Elapsed Time", "s", false,
         "Whole seconds of machine time since the top-level run began; 0 in a check."},
    Info{131, "Mode Input #9", "0-4", false, "Role of input switch 9 (VN)."},
    Info{132, "Mode Input #10", "0-4", false, "Role of input switch 10 (VN)."},
    Info{133, "Mode Input #11", "0-4", false, "Role of input switch 11 (VN)."},
    Info{134, "Mode Input #12", "0-4", false, "Role of input switch 12 (VN)."},
    Info{135, "Upper Output Byte", "0-15", false, "Outputs 9-12 as bits; output n is bit n-9."},
    Info{136, "Status Out #9", "0-1", false, "Output switch 9: 1 on, 0 off."},
    Info{137, "Status Out #10", "0-1", false, "Output switch 10: 1 on, 0 off."},
    Info{138, "Status Out #11", "0-1", false, "Output switch 11: 1 on, 0 off."},
    Info{139, "Status Out #12", "0-1", false, "Output switch 12: 1 on, 0 off."},
    Info{141, "Z/A Trigger ON Thresh", "units", false,
         "Plunge level that switches the triggered output on (VC 9)."},
    Info{142, "Z/A Trigger OFF Thresh", "units", false,
         "Pull-up level that switches the triggered output off (VC 10)."},
    Info{144, "Location C", "units", false, "Working C position."},
    Info{145, "Base Coord C", "units", false, "C in table base coordinates."},
    Info{146, "Date", "text", true, "Today's local date as MM/DD/YYYY."},
    Info{147, "Time", "text", true, "Local time of day as HH:MM:SS, 24-hour clock."},
    Info{150, "Step Interval Divider", "1-100", false,
         "Divisor that slows step timing below the minimum speed (VU 15)."},
    Info{151, "Multiplier X", "0-10", false, "Resolution multiplier of X (VU 10)."},
    Info{152, "Multiplier Y", "0-10", false, "Resolution multiplier of Y (VU 11)."},
    Info{153, "Multiplier Z", "0-10", false, "Resolution multiplier of Z (VU 12)."},
    Info{154, "Multiplier A", "0-10", false, "Resolution multiplier of A (VU 13)."},
    Info{155, "Multiplier B", "0-10", false, "Resolution multiplier of B (VU 14)."},
    Info{156, "Multiplier C", "0-10", false, "Resolution multiplier of C."},
    Info{158, "Current uController Voltage", "0-9", false, "Supply reading of the card."},
    Info{159, "Current uController Temp", "°C", false, "Temperature of the card."},
    Info{161, "RPM Spindle", "text", true,
         "Spindle speed in RPM (TR's) while output 1, the spindle, is on; whole digits."},
};

Value flag(bool b) {
  return Value::number(b ? 1.0 : 0.0);
}

Value axis_letter(char c) {
  return Value::string(std::string(1, c));
}

// Switches `first`..`first + count - 1` (1-based) as bits, lowest switch in bit 0.
Value output_bits(const std::array<bool, 12>& outputs, int first, int count) {
  int bits = 0;
  for (int i = 0; i < count; ++i) {
    if (outputs[first - 1 + i]) bits |= 1 << i;
  }
  return Value::number(bits);
}

// Room for three full-range ints, so snprintf can never truncate.
std::string date_text(const MachineSnapshot::DateTime& t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%02d/%02d/%04d", t.month, t.day, t.year);
  return buf;
}

std::string time_text(const MachineSnapshot::DateTime& t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%02d:%02d:%02d", t.hour, t.minute, t.second);
  return buf;
}

// The escaped text of a Markdown table cell: a `|` would end the cell.
std::string cell(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

constexpr std::string_view kPageHead =
    R"(# Gantry system variables

Generated from the system-variable table by `system_variables_markdown()` in
src/interp/system_variables.cpp; a unit test keeps this page equal to it, so edit the table,
not the page.

A part file reads these as `%(n)`, anywhere a value may stand: `&Y_NOW = %(2)`. They are
read-only. Lengths, speeds and thresholds are in the current user units (inches or
millimetres, degrees for rotary axes set that way), speeds per second. Text-typed variables
are strings, all others numbers. A number not listed here (including the slots the
handbook leaves blank, 0, negatives and anything above 169) is the error
"unknown system variable".

| %(n) | Name | Unit | Type | Meaning |
|---:|---|---|---|---|
)";

constexpr std::string_view kPageTail = R"(
## Decisions

Where the handbook's list is unclear or contradicts the command references, Gantry decided:

* **Cutter diameter is %(23), not %(20).** The VC text of both command references says the
  cutter diameter is %(20), but the handbook's table has 20 = maximum B limit and
  23 = cutter diameter. The table wins: %(20) is the B limit, %(23) the cutter.
* **0/1 encodings** (the table prints only "0-1"): %(21) 0 = absolute (SA), 1 = relative
  (SR); %(22) 0 = move/cut (SM), 1 = preview (SP); %(25) 0 = inches, 1 = millimetres, the
  same code as the VD linear-units field.
* **Speeds and ramp speeds** (%(71)-%(90)) are printed "userUnits" but are speeds: user
  units per second. X and Y report the same value, because MS, JS, VS and VR set one vector
  speed for XY.
* **Elapsed time** (%(130), "long") is whole seconds, rounded down, of machine time since
  the top-level run started, read where the tool is: the moves before the line play out
  first, as for an input. Machine time is the card's clock, the one the console shows as
  elapsed: it runs while pulses and dwells play (SW's warning too) and stands still while
  the file waits at rest for the operator (PAUSE, INPUT). On the simulated card it is
  virtual time, so a run reads the same value however fast it plays. A check (`gantry
  check`, `estimate`, `preview`, `moves`) has no machine: %(130) reads 0 there, as its inputs
  read open.
* **Date and time** (%(146), %(147)) are local, `MM/DD/YYYY` and `HH:MM:SS` on a 24-hour
  clock; the table prints only "string".
* **Current file name** (%(60)) is the absolute path of the innermost file running, so a
  file called with FP reports its own name.
* **Switch counts:** inputs and outputs 1-12 are all readable, though some handbook pages
  say 8; hardware with fewer channels reports the missing ones as 0.
* **Output bytes:** %(100) holds outputs 1-8 with output n in bit n-1; %(135) holds
  outputs 9-12 with output n in bit n-9.
* **Output switches** (%(100)-%(108), %(135)-%(139)) read the switches as the file has set
  them so far (SO, MO, a file's end; switch 4 also while it follows motion, from SW's
  warning on). The machine switches them at rest between the moves around the SO, in
  order, so the value read is the one in force for the next move. A preview (SP) switches
  nothing, so it reads them unchanged.
* **Switch 4's mode** (%(109)) is the last `SO, 4, -n` (-1 to -3: on while a run moves the
  tool; -4: a plain switch), kept in the values like SW; -1 by default.
* **Output modes** (%(111)-%(122)) are the VN output modes in force, as VN changes them.
* **Driver channels** (%(36)-%(40), "XYZA or B") are one-letter strings, `X` to `B`.
* **%(46) and %(47)** ("Inp #3 Mode", "Inp #4 Mode", 0-1) are not the 0-4 role codes of
  %(91)-%(98): %(47) is the VN wiring flag of the stop input 4 (0 normally closed,
  1 normally open) and %(46) the matching legacy flag of input 3.
* **Spindle RPM** (%(161)) is a string, as listed: the speed rounded to whole revolutions
  per minute, `0` when the spindle is stopped. Gantry measures no speed: it is the speed TR
  last set while output switch 1, the spindle, is on.
* **Rows 158 and 159** are printed over two lines each in the handbook; they are one
  variable each, the card's supply voltage reading and its temperature in degrees Celsius.
* **The list ends at 169.** The handbook's row 170 ("current max") marks the end of the
  list and is not a variable. The index may be an expression (`%(50 + &I)`) as long as it
  comes out a whole number listed here.
)";

}  // namespace

MachineSnapshot::DateTime local_date_time() {
  const std::time_t now = std::time(nullptr);
  std::tm t{};
  localtime_r(&now, &t);
  return {t.tm_year + 1900, t.tm_mon + 1, t.tm_mday, t.tm_hour, t.tm_min, t.tm_sec};
}

std::span<const SystemVariableInfo> system_variable_table() {
  return kTable;
}

const SystemVariableInfo* find_system_variable(int n) {
  auto it = std::lower_bound(kTable.begin(), kTable.end(), n,
                             [](const Info& row, int key) { return row.number < key; });
  return it != kTable.end() && it->number == n ? &*it : nullptr;
}

std::optional<Value> read_system_variable(int n, const MachineSnapshot& m) {
  auto num = [](double d) { return std::optional<Value>(Value::number(d)); };
  // Per-switch and per-axis runs of the table, located by their first number.
  if (n >= 1 && n <= 5) return num(m.location[n - 1]);
  if (n >= 6 && n <= 10) return num(m.table_base[n - 6]);
  if (n >= 11 && n <= 20) {
    const int axis = (n - 11) / 2;
    return num((n - 11) % 2 == 0 ? m.limit_min[axis] : m.limit_max[axis]);
  }
  if (n >= 31 && n <= 35) return num(m.steps_per_unit[n - 31]);
  if (n >= 36 && n <= 40) return axis_letter(m.driver_channel_axis[n - 36]);
  if (n >= 51 && n <= 58) return flag(m.inputs[n - 51]);
  if (n >= 91 && n <= 98) return num(m.input_mode[n - 91]);
  if (n >= 101 && n <= 108) return flag(m.outputs[n - 101]);
  if (n >= 111 && n <= 122) return num(m.output_mode[n - 111]);
  if (n >= 124 && n <= 125) return num(m.analog_inputs[n - 124]);
  if (n >= 126 && n <= 129) return flag(m.inputs[n - 126 + 8]);
  if (n >= 131 && n <= 134) return num(m.input_mode[n - 131 + 8]);
  if (n >= 136 && n <= 139) return flag(m.outputs[n - 136 + 8]);
  if (n >= 151 && n <= 156) return num(m.resolution_multiplier[n - 151]);

  // Speeds and ramps: X and Y both read the XY group.
  if (n >= 71 && n <= 90) {
    const MachineSnapshot::Groups* g[] = {&m.move_speed, &m.jog_speed, &m.move_ramp, &m.jog_ramp};
    const MachineSnapshot::Groups& group = *g[(n - 71) / 5];
    const double by_axis[] = {group.xy, group.xy, group.z, group.a, group.b};
    return num(by_axis[(n - 71) % 5]);
  }

  switch (n) {
    case 21:
      return flag(m.relative);
    case 22:
      return flag(m.preview);
    case 23:
      return num(m.cutter_diameter);
    case 24:
      return num(m.warning_delay);
    case 25:
      return flag(m.metric);
    case 27:
      return num(m.axis_count);
    case 28:
      return num(m.safe_z);
    case 29:
      return num(m.safe_a);
    case 30:
      return num(m.limit_check_axes);
    case 41:
      return num(m.tab_pull_up);
    case 42:
      return num(m.tab_spacing);
    case 43:
      return num(m.tab_size);
    case 44:
      return num(m.tab_lead);
    case 46:
      return num(m.input3_mode);
    case 47:
      return num(m.input4_mode);
    case 48:
      return Value::string(m.software_version);
    case 49:
      return num(m.firmware_version);
    case 60:
      return Value::string(m.file_path);
    case 61:
      return num(m.file_offset[0]);
    case 62:
      return num(m.file_offset[1]);
    case 63:
      return num(m.file_offset[2]);
    case 66:
      return num(m.file_proportion[0]);
    case 67:
      return num(m.file_proportion[1]);
    case 68:
      return num(m.file_proportion[2]);
    case 99:
      return flag(m.torch_height_control);
    case 100:
      return output_bits(m.outputs, 1, 8);
    case 109:
      return num(m.output4_auto_mode);
    case 123:
      return flag(m.indexer_on);
    case 130:
      return num(std::floor(m.elapsed_seconds));
    case 135:
      return output_bits(m.outputs, 9, 4);
    case 141:
      return num(m.trigger_on_threshold);
    case 142:
      return num(m.trigger_off_threshold);
    case 144:
      return num(m.location[5]);
    case 145:
      return num(m.table_base[5]);
    case 146:
      return Value::string(date_text(m.now));
    case 147:
      return Value::string(time_text(m.now));
    case 150:
      return num(m.step_interval_divider);
    case 158:
      return num(m.controller_voltage);
    case 159:
      return num(m.controller_temperature);
    case 161:
      return Value::string(std::to_string(std::llround(m.spindle_rpm)));
    default:
      return std::nullopt;
  }
}

std::string system_variables_markdown() {
  std::string out(kPageHead);
  for (const Info& v : kTable) {
    out += "| " + std::to_string(v.number) + " | " + cell(v.name) + " | " + cell(v.unit) + " | " +
           (v.is_string ? "string" : "number") + " | " + cell(v.meaning) + " |\n";
  }
  out += kPageTail;
  return out;
}

}  // namespace gantry
