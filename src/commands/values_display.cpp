// The values a bare value command shows, from the settings schema's rows.
#include "values_display.hpp"

#include <fmt/format.h>

#include <algorithm>  // max

#include "gantry/interp/value.hpp"              // format_number
#include "gantry/settings/settings_schema.hpp"  // SettingRow

namespace gantry {

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
    if (unit == "units") unit = u;
    else if (unit.starts_with("units/")) unit = u + unit.substr(5);
    else if (unit == "steps/unit") unit = "steps/" + u;
    out += fmt::format("  {:>2}  {:<{}}  {}{}{}\n", v.number, v.param->name, width, v.value,
                       unit.empty() ? "" : " ", unit);
  }
  return out;
}

}  // namespace gantry
