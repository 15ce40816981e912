// The values a bare value command shows, from the settings schema's rows.
#include "values_display.hpp"

#include <fmt/format.h>

#include <algorithm>  // max
#include <optional>   // a key left out
#include <vector>     // the lines

#include "gantry/commands/values_sheets.hpp"
#include "gantry/interp/value.hpp"              // format_number
#include "gantry/settings/settings.hpp"         // display.axes
#include "gantry/settings/settings_schema.hpp"  // SettingRow

namespace gantry {
namespace {

// The profile's rows each bare V command lists after its parameters. A row of a table named
// here is shown however it came to be (a new key of [limits] is in VL's listing by itself);
// a new table needs its line here or in kProfileOnly (values_sheets_test checks both ways).
constexpr SheetRows kSheetRows[] = {
    {"VL", "limits."},                // the limit switches (WinCNC's lim_*, softlim)
    {"VL", "homing."},                // homing, per axis (g28move, g28coord, ...)
    {"VU", "axes.<x..c>.max_speed"},  // the drive's limits and calibration
    {"VU", "axes.<x..c>.max_accel"},  //
    {"VU", "axes.<x..c>.backlash"},   //
    {"VU", "axes.<x..c>.wrap"},       //
    {"VD", "display.w_axis"},         // the axes shown
    {"VC", "spindle."},               // the cutter: its spindle and its changer
    {"VC", "toolchanger."},           //
    {"VS", "feed_override."},         // the speeds: the live override's bounds
    {"VN", "inputs.switch_bits"},     // the input switches' bits, beside their modes
};

// The machine's wiring and set-up: read from the profile only, shown in no sheet.
constexpr std::string_view kProfileOnly[] = {
    "",  // name, dialect, gcode_dialect, tool_table, subroutines (units: VD's)
    "card",    "pins.<x..c>", "inputs",  "inputs.<x..c>", "outputs",         "files",
    "pendant", "simulator",   "planner", "machine",       "friendly_motion",
};

// A row's value as the listing shows it: a key left out as "-", text as written.
std::string profile_value_text(const SettingRow& row, const Settings& s, int i) {
  switch (row.kind) {
    case SettingKind::OptionalNumber: {
      const auto* v = row.member<std::optional<double>>(s, i);
      return *v ? format_number(**v) : "-";
    }
    case SettingKind::Coded: {
      const std::string text = row.encode(s);
      return text.empty() ? "\"\"" : text;
    }
    case SettingKind::Text: {
      const std::string& text = *row.member<std::string>(s, i);
      return text.empty() ? "\"\"" : text;
    }
    case SettingKind::Texts: {
      std::string out;
      for (const std::string& t : *row.member<std::vector<std::string>>(s, i))
        out += (out.empty() ? "" : ", ") + t;
      return out.empty() ? "-" : out;
    }
    case SettingKind::IntList:
    case SettingKind::NumberList: {
      std::string out;
      for (int k = 0; k < std::max(1, row.count); ++k)
        out += (k ? ", " : "") + setting_value_text(row, s, k);
      return out;
    }
    default:
      return setting_value_text(row, s, i);
  }
}

}  // namespace

std::span<const SheetRows> sheet_profile_rows() {
  return kSheetRows;
}

std::span<const std::string_view> profile_only_tables() {
  return kProfileOnly;
}

std::string sheet_profile_lines(std::string_view code, const Settings& s) {
  std::vector<std::pair<std::string, std::string>> lines;  // key, value
  for (const SettingRow& row : settings_schema()) {
    const std::string path = row.path();
    bool shown = false;
    for (const SheetRows& r : kSheetRows)
      shown = shown || (r.code == code && path.starts_with(r.prefix));
    if (!shown) continue;
    if (row.family == SettingFamily::None) {
      lines.emplace_back(path, profile_value_text(row, s, 0));
      continue;
    }
    // A family on one line: the axes (groups) in use, each with its value.
    std::string values;
    const int in_use = std::min(row.size(), s.display.axes);
    for (int i = 0; i < in_use; ++i) {
      const std::string key = row.key_at(i), section = row.section_at(i);
      const std::string name = row.section.find('<') != std::string_view::npos
                                   ? section.substr(section.rfind('.') + 1)
                                   : key.substr(key.rfind('_') + 1);
      values += fmt::format("{}{} {}", i ? "  " : "", name, profile_value_text(row, s, i));
    }
    lines.emplace_back(path, values);
  }
  if (lines.empty()) return "";
  std::size_t width = 0;
  for (const auto& l : lines) width = std::max(width, l.first.size());
  std::string out = "  set in the profile (docs/settings.md; - : left out):\n";
  for (const auto& [key, value] : lines)
    out += fmt::format("      {:<{}}  {}\n", key, width, value);
  return out;
}

std::string setting_value_text(const SettingRow& row, const Settings& s, int i) {
  switch (row.kind) {
    case SettingKind::Number:
      return format_number(row.get(s, i));
    case SettingKind::Integer:
      return std::to_string(*row.member<int>(s, i));
    case SettingKind::Bool:
      return *row.member<bool>(s, i) ? "1" : "0";
    case SettingKind::Choice: {
      const int k = row.choice_get ? row.choice_get(s, i) : *row.member<int>(s, i);
      return k >= 0 && static_cast<std::size_t>(k) < row.names.size() ? std::string(row.names[k])
                                                                      : std::to_string(k);
    }
    case SettingKind::IntList:
      return std::to_string(row.member<int>(s)[i]);
    case SettingKind::NumberList:
      return format_number(row.member<double>(s)[i]);
    case SettingKind::Coded: {
      const std::string text = row.encode(s);
      return static_cast<std::size_t>(i) < text.size() ? text.substr(i, 1) : text;
    }
    case SettingKind::Text:
      return *row.member<std::string>(s, i);
    default:
      return "";
  }
}

std::string values_listing(const CommandSpec& spec, const std::vector<ShownValue>& values,
                           const Settings& s) {
  const std::string u = units_name(s.units);
  std::size_t width = 0;
  for (const ShownValue& v : values) width = std::max(width, v.param->name.size());
  std::string out = fmt::format("{}, {} (in force):\n", spec.code, spec.name);
  for (const ShownValue& v : values) {
    std::string unit = v.unit.empty() ? std::string(v.param->unit) : v.unit;
    if (unit == "units")
      unit = u;
    else if (unit.starts_with("units/"))
      unit = u + unit.substr(5);
    else if (unit == "steps/unit")
      unit = "steps/" + u;
    out += fmt::format("  {:>2}  {:<{}}  {}{}{}\n", v.number, v.param->name, width, v.value,
                       unit.empty() ? "" : " ", unit);
  }
  return out + sheet_profile_lines(spec.code, s);
}

}  // namespace gantry
