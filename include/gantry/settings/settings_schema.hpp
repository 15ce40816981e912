// The settings schema: one row per profile key (path, member, kind, range, unit kind, help) that
// the profile reader and writer, the unit conversion, the V-commands and docs/settings.md share.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace gantry {

struct Settings;

// How a setting follows VD's linear units (convert_units).
enum class SettingUnit {
  None,         // not at all (a percent, a bit, a frequency)
  Length,       // a length: X's factor
  Rate,         // a speed, or a jerk, of the path: X's factor
  Axis,         // a length or speed of the row's own axis (its family index): that axis's factor
  PerAxis,      // steps per unit: divided by the axis's factor
  AxisA,        // a length along A (safe_a): A's factor
  TriggerAxis,  // along cutter.trigger_axis (Z or A)
};

// What a row's value is, in the profile and in memory.
enum class SettingKind {
  Number,          // double
  Integer,         // int
  Bool,            // bool
  Choice,          // one of `names`, held as its index (an enum, a sign...)
  Text,            // std::string; one of `names` when there are any
  OptionalNumber,  // std::optional<double>: the key may be left out
  IntList,         // "a, b, c" whole numbers: std::vector<int> (count 0) or std::array<int, count>
  NumberList,      // "a, b, c" numbers: std::array<double, count>
  LineBits,        // "a:b, c:d" (names[0] says "BIT:LINE" or "LINE:BIT"): vector<GpioLineBit>
  Texts,           // a TOML array of strings: std::vector<std::string>
  Coded,           // a string coded and decoded by the row's functions (drivers.channels)
};

// Per-axis keys: one row for the family, `i` the index.
enum class SettingFamily {
  None,
  Axes,    // x y z a b c: "axes.<x..c>.max_speed"
  Groups,  // xy z a b c (GroupSpeeds): "speeds.move.<xy,z,a,b,c>"
};

// Whose a key is: the operator's (a V command's, UR may load it from a values file) or the
// machine's, which UR refuses to change (machine_key_changed names the key or its table).
enum class SettingOwner { Operator, MachineKey, MachineTable };

// Allowed values of one numeric setting.
struct SettingRange {
  double lo = 0, hi = 0;
  bool lo_open = false;  // lo itself not allowed

  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && v <= hi; }
  // ">= 0 and <= 1000", as the profile reader's messages say it.
  std::string describe() const;
  // "0 to 1000", as docs/settings.md writes it.
  std::string docs() const;
};

struct SettingRow {
  std::string_view section;  // the TOML table, with the family's placeholder: "axes.<x..c>"
  std::string_view key;      // the key in it: "max_speed", "home_<x..c>"
  SettingKind kind = SettingKind::Number;
  void* (*field)(Settings&, int i) = nullptr;  // the member (its type per `kind`); i: family index
  SettingRange range{};                        // Number, Integer and list items
  SettingUnit unit = SettingUnit::None;        // how convert_units scales it
  std::string_view help;                       // one line, as docs/settings.md says it
  SettingFamily family = SettingFamily::None;
  std::span<const std::string_view> names{};  // Choice and Text: the allowed strings
  bool optional = false;                      // the key may be left out (the default stays)
  bool optional_table = false;                // its whole table may be left out (no key asked)
  bool omit_empty = false;                    // Text, Texts, Coded: not written when empty
  int count = 0;                              // lists: how many values (0: any)
  // Choice: the held value as an index of `names`, and back (null: an int member holds it).
  int (*choice_get)(const Settings&, int i) = nullptr;
  void (*choice_set)(Settings&, int i, int index) = nullptr;
  // Text: a rule each value (Texts: each item) must keep, and its message (after the key).
  std::string (*check)(std::string_view value) = nullptr;
  // Coded: the text form and its decoding (false: not valid; `rule` says why).
  std::string (*encode)(const Settings&) = nullptr;
  bool (*decode)(Settings&, std::string_view) = nullptr;
  std::string_view rule;
  std::string_view docs_allowed;  // docs/settings.md's "allowed" cell when the kind cannot say it
  std::string_view docs_type;     // docs/settings.md's "type" cell when the kind's is not it
  SettingOwner owner = SettingOwner::Operator;
  // Number: a bound above `range` that other keys set (the speeds: the axis max_speed).
  double (*most)(const Settings&, int i) = nullptr;

  std::string path() const;            // "ramps.move_ramp_rate", "axes.<x..c>.max_speed"
  std::string path(int i) const;       // with the family's letter: "axes.x.max_speed"
  std::string section_at(int i) const;  // "axes.x"
  std::string key_at(int i) const;      // "home_x"
  int size() const;                    // 1, or the family's size
  // The Number (or family member) as a reference.
  double& number(Settings& s, int i = 0) const { return *static_cast<double*>(field(s, i)); }
  double get(const Settings& s, int i = 0) const { return number(const_cast<Settings&>(s), i); }
  // The member, read only, as its type per `kind` (a list's first item).
  template <class T>
  const T* member(const Settings& s, int i = 0) const {
    return static_cast<const T*>(field(const_cast<Settings&>(s), i));
  }
  double fallback() const;  // a Number's value in a default-constructed Settings
  // The range in force in `s`: `range`, its top lowered to `most(s, i)` when the row has one.
  SettingRange range_in(const Settings& s, int i = 0) const;
  // docs/settings.md's cells.
  std::string type_name() const;
  std::string allowed() const;
};

// Every row, in the order the profile is read.
std::span<const SettingRow> settings_schema();
// The rows of one TOML table ("ramps"), in order.
std::span<const SettingRow> settings_schema(std::string_view section);
// Every setting in the order the profile is read: a family's consecutive rows in one table
// (axes.<x>.min, axes.<x>.max, ...) axis by axis, each other row on its own. `visit(row, i)`
// returns false to stop; the result is false when it stopped.
bool for_each_setting(const std::function<bool(const SettingRow& row, int i)>& visit);
// The row of a key path ("ramps.move_ramp_rate"); throws std::out_of_range for an unknown one.
const SettingRow& setting_row(std::string_view path);

// Sets a Number setting within its range; false (and `s` unchanged) when `v` is outside it.
bool set_setting(Settings& s, const SettingRow& row, double v, int i = 0);

// The axis index (0 X .. 5 C) of a family's index: Groups' xy is X.
int setting_axis(SettingFamily f, int i);

}  // namespace gantry
