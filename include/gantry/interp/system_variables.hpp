// The OpenSBP system-variable table %(n): what each number means and its value in a snapshot.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "gantry/core/vec6.hpp"     // Vec6
#include "gantry/interp/value.hpp"  // Value

namespace gantry {

// The live machine state that %(n) can read, copied by the interpreter when a part file asks.
// Plain data so the table can be tested without a machine. Every length, speed and
// threshold is already in the current user units (inches or mm; degrees for rotary axes),
// because the handbook reports distances "in the current user units". Defaults are the
// shipped profile (settings/default.toml) and the command references' defaults, so a field
// the interpreter does not track yet still reads a plausible value.
struct MachineSnapshot {
  // One value per axis group, as MS/JS/VS/VR address them: XY shares one vector speed.
  struct Groups {
    double xy = 0, z = 0, a = 0, b = 0, c = 0;
  };
  // A local calendar date and wall-clock time; the interpreter fills it from its clock.
  struct DateTime {
    int year = 2000, month = 1, day = 1;   // calendar date, month and day 1-based
    int hour = 0, minute = 0, second = 0;  // 24-hour clock
  };

  // Position and coordinate systems.
  Vec6 location = Vec6::Zero();    // working location X..C, the position readout
  Vec6 table_base = Vec6::Zero();  // table base coordinates X..C (ZT/ST/VA fields 6-10)
  Vec6 limit_min = (Vec6() << 0, 0, -4, -1e5, -1e5, -1e5).finished();  // VL low limits
  Vec6 limit_max = (Vec6() << 24, 18, 5.5, 1e5, 1e5, 1e5).finished();  // VL high limits
  int limit_check_axes = 3;  // how many axes (1-5) soft limits are checked on

  // Modes (SA/SR, SM/SP, VD).
  bool relative = false;  // SR relative distances; false is SA absolute
  bool preview = false;   // SP preview; false is SM move/cut
  bool metric = false;    // VD linear units: millimetres; false is inches
  int axis_count = 3;     // VD number of active axes, 3-5

  // Cutter and safety (VC, SW).
  double cutter_diameter = 0.25;       // VC 1
  double safe_z = 1.0;                 // VC 4 safe-Z pull-up height
  double safe_a = 1.0;                 // VC 7 safe-A pull-up height
  double trigger_on_threshold = 0.0;   // VC 9: Z/A level that turns the triggered output on
  double trigger_off_threshold = 0.0;  // VC 10: Z/A level that turns it off again
  double warning_delay = 2.0;          // SW pre-move warning, seconds

  // Tabbing (VB 1-4).
  double tab_pull_up = 0.1;  // height the cutter lifts for a tab
  double tab_spacing = 4.0;  // distance from one tab to the next
  double tab_size = 1.0;     // tab width along the path
  double tab_lead = 0.5;     // length of the incline up to and down from a tab

  // Speeds and ramps (MS/JS/VS, VR), units/s.
  Groups move_speed{2.0, 0.5, 10.0, 10.0, 10.0};  // cutting speeds
  Groups jog_speed{6.0, 3.0, 45.0, 45.0, 45.0};   // rapid speeds
  Groups move_ramp{0.4, 0.4, 0.4, 0.4, 0.4};      // ramp start/end speeds for moves
  Groups jog_ramp{0.4, 0.4, 0.4, 0.4, 0.4};       // ramp start/end speeds for jogs

  // Calibration and drivers (VU, VI).
  Vec6 steps_per_unit =
      (Vec6() << 916.7324, 916.7324, 1018.5916, 13.8889, 13.8889, 13.8889).finished();  // VU
  std::array<int, kAxisCount> resolution_multiplier{1, 1, 1, 1, 1, 1};  // VU resM X..C, 0-10
  int step_interval_divider = 1;  // VU 15: step timing divisor, 1-100
  std::array<char, kAxisCount> driver_channel_axis{'X', 'Y', 'Z', 'A', 'B', 'C'};  // VI 1-6

  // Input switches 1-12 (index 0 is switch 1).
  std::array<bool, 12> inputs{};          // closed (on) state
  std::array<int, 12> input_mode{};       // VN mode 0-4; 0 standard, readable by part files
  int input3_mode = 0;                    // legacy 0/1 mode flag of input 3 (old limit wiring)
  int input4_mode = 0;                    // VN 2, stop input 4: 0 normally closed, 1 normally open
  std::array<double, 2> analog_inputs{};  // analog inputs 1-2, as the card reports (0-9)

  // Output switches 1-12 (index 0 is switch 1).
  std::array<bool, 12> outputs{};     // on state
  std::array<int, 12> output_mode{};  // VN output mode 0-5 (end-of-file/stop behaviour)
  int output4_auto_mode = -1;         // SO 4,-n: when output 4 follows motion, -1..-4

  // Accessories.
  bool torch_height_control = false;  // VH 1: torch height / laser control active
  bool indexer_on = false;            // MI: independent indexer or oscillation running
  double spindle_rpm = 0.0;           // measured spindle speed, 0 when stopped

  // Controller and software.
  std::string software_version = GANTRY_VERSION;  // this program's version
  int firmware_version = 0;                       // card firmware; 0 for the simulated card
  double controller_voltage = 0.0;                // card supply reading (0-9)
  double controller_temperature = 0.0;            // card temperature, degrees Celsius

  // The running part file.
  std::string file_path;                // absolute path of the innermost running file
  Vec6 file_offset = Vec6::Zero();      // FP offset applied to the file (X, Y, Z used)
  Vec6 file_proportion = Vec6::Ones();  // FP proportion (scale) of the file (X, Y, Z used)
  double elapsed_seconds = 0.0;         // the machine's clock since the top-level run started
  DateTime now;                         // local date and time of the read
};

// The local calendar date and time of day now, from the system clock (%(146), %(147)).
MachineSnapshot::DateTime local_date_time();

// One row of the handbook's system-variable list.
struct SystemVariableInfo {
  int number;                // n in %(n)
  std::string_view name;     // the handbook's label, spelling normalised
  std::string_view unit;     // unit, or the value range when it has none
  bool is_string;            // %(n) is a string; otherwise a number
  std::string_view meaning;  // what it reports and which setting it mirrors
};

// Every defined %(n), sorted by number. Numbers the handbook leaves blank are absent.
std::span<const SystemVariableInfo> system_variable_table();

// The table entry for `n`, or null when %(n) is not defined.
const SystemVariableInfo* find_system_variable(int n);

// The value of %(n) in `m`; nullopt when n is not a defined variable (the caller reports
// "unknown system variable").
std::optional<Value> read_system_variable(int n, const MachineSnapshot& m);

// docs/system_variables.md: the table as Markdown plus the decisions behind it.
std::string system_variables_markdown();

}  // namespace gantry
