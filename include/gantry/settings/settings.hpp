// The machine profile: everything the pipeline needs to know about one machine.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "gantry/core/axes.hpp"        // kAxisCount
#include "gantry/core/diagnostic.hpp"  // Diagnostic for load errors

namespace gantry {

enum class Units { Inches, Millimetres };

// Which OpenSBP the part files are written in: SB3 (trigonometry in radians) or FabMo
// (degrees).
enum class Dialect { SB3, FabMo };

// One speed (or ramp speed) per group, as MS/JS/VS/VR name them: XY is a vector speed.
struct GroupSpeeds {
  double xy = 0, z = 0, a = 0, b = 0, c = 0;
};

struct AxisSettings {
  double steps_per_unit = 1;  // motor steps per unit (in, mm or degree)
  double max_speed = 1;       // hardware speed limit, units/s
  double max_accel = 1;       // hardware acceleration limit, units/s^2
  double min = 0, max = 0;    // soft limits (table envelope), units
};

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

// Bits of the card's 32-bit input word. -1: not wired. A switch is "active" when its bit
// reads 1, or 0 for the active-low ones (normally-closed E-stop chains read 0 when broken).
struct InputSettings {
  int estop_bit = 0;
  bool estop_active_low = true;
  int probe_bit = 1;
  std::array<int, kAxisCount> min_bit{}, max_bit{}, home_bit{};  // limit and proximity switches
  bool limits_active_low = false;
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

  double pacer_hz() const { return clock_hz / pacer_divisor; }
};

// The machine's own values that commands read (and issue 6's V commands will set).
struct MachineSettings {
  double safe_z = 1.0;  // working Z that MH and JH raise the tool to first (VC's Safe-Z)
};

struct Settings {
  std::string name;
  Units units = Units::Inches;
  Dialect dialect = Dialect::SB3;
  std::array<AxisSettings, kAxisCount> axes{};
  SpeedSettings speeds;
  RampSettings ramps;
  PlannerSettings planner;
  CardSettings card;
  std::array<PinSettings, kAxisCount> pins{};
  OutputSettings outputs;
  InputSettings inputs;
  MachineSettings machine;
};

// The result of loading a profile: settings, or every problem found in it.
struct SettingsLoad {
  Settings settings;
  std::vector<Diagnostic> errors;
  bool ok() const { return errors.empty(); }
};

// Parses and validates a profile. `origin` names it in messages (a path).
SettingsLoad parse_settings(const std::string& text, const std::string& origin);

// Reads and validates a profile file; a missing file is an error like any other.
SettingsLoad load_settings_file(const std::string& path);

// The shipped default profile (settings/default.toml, compiled in).
const std::string& default_profile_text();
Settings default_settings();

const char* units_name(Units u);
const char* planner_mode_name(PlannerMode m);

}  // namespace gantry
