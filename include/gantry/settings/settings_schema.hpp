// The settings schema: one row per numeric setting (key, member, range, unit kind, help) that
// the profile reader and writer, the unit conversion, the V-commands and docs/settings.md share.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace gantry {

struct Settings;

// How a setting follows VD's linear units (convert_units): not at all, or as a length.
enum class SettingUnit { None, Length };

// Allowed values of one numeric setting.
struct SettingRange {
  double lo, hi;
  bool lo_open = false;  // lo itself not allowed

  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && v <= hi; }
  // ">= 0 and <= 1000", as the profile reader's messages say it.
  std::string describe() const;
  // "0 to 1000", as docs/settings.md writes it.
  std::string docs() const;
};

struct SettingRow {
  std::string_view section;      // the TOML table: "ramps"
  std::string_view key;          // the key in it: "move_ramp_rate"
  double& (*member)(Settings&);  // the field it sets
  SettingRange range;            // checked by the profile, values-file and V-command readers
  SettingUnit unit;              // how convert_units scales it
  std::string_view help;         // one line, as docs/settings.md says it

  std::string path() const;  // "ramps.move_ramp_rate"
  double get(const Settings& s) const { return member(const_cast<Settings&>(s)); }
  double fallback() const;  // the value a default-constructed Settings holds
};

// Every row, in the order the profile is written.
std::span<const SettingRow> settings_schema();
// The rows of one TOML table ("ramps"), in order.
std::span<const SettingRow> settings_schema(std::string_view section);
// The row of a key path ("ramps.move_ramp_rate"); throws std::out_of_range for an unknown one.
const SettingRow& setting_row(std::string_view path);

// Sets a setting within its range; false (and `s` unchanged) when `v` is outside it.
bool set_setting(Settings& s, const SettingRow& row, double v);

}  // namespace gantry
