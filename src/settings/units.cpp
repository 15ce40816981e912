// Changing a profile's linear units (VD): every length-based value scales together.
#include <cmath>  // pow, log10, round

#include "gantry/settings/settings.hpp"
#include "gantry/settings/settings_schema.hpp"  // the length settings

namespace gantry {

double units_factor(Units from, Units to) {
  if (from == to) return 1;
  return to == Units::Millimetres ? 25.4 : 1 / 25.4;
}

namespace {

// Converted values keep 12 significant digits, so that inches to millimetres and back gives
// the profile's own numbers again (24 in is 609.6 mm, not 609.5999999999999).
double round12(double v) {
  if (v == 0 || !std::isfinite(v)) return v;
  const double scale = std::pow(10.0, 11 - static_cast<int>(std::floor(std::log10(std::fabs(v)))));
  return std::round(v * scale) / scale;
}

}  // namespace

std::array<double, kAxisCount> units_scale(const Settings& s, Units to) {
  const double f = units_factor(s.units, to);
  std::array<double, kAxisCount> scale;
  scale.fill(f);
  for (int i = 0; i < 3; ++i)
    if (s.display.rotary_units[i] == AxisUnit::Degrees) scale[3 + i] = 1;
  return scale;
}

void scale_speeds(GroupSpeeds& g, const std::array<double, kAxisCount>& scale) {
  g.xy = round12(g.xy * scale[0]);
  g.z = round12(g.z * scale[2]);
  g.a = round12(g.a * scale[3]);
  g.b = round12(g.b * scale[4]);
  g.c = round12(g.c * scale[5]);
}

void convert_units(Settings& s, Units to) {
  const auto scale = units_scale(s, to);
  const double f = scale[0];
  s.units = to;
  if (f == 1) return;
  for (const SettingRow& row : settings_schema()) {
    if (row.unit == SettingUnit::None) continue;
    if (row.kind == SettingKind::Coded) continue;  // the rack's slots, below
    for (int i = 0; i < row.size(); ++i) {
      double factor = f;
      switch (row.unit) {
        case SettingUnit::Axis:
        case SettingUnit::PerAxis: factor = scale[setting_axis(row.family, i)]; break;
        case SettingUnit::AxisA: factor = scale[3]; break;
        case SettingUnit::TriggerAxis: factor = scale[s.cutter.trigger_axis]; break;
        default: break;
      }
      if (row.kind == SettingKind::OptionalNumber) {
        if (auto& v = *static_cast<std::optional<double>*>(row.field(s, i))) *v = round12(*v * factor);
      } else {
        double& v = row.number(s, i);
        v = round12(row.unit == SettingUnit::PerAxis ? v / scale[setting_axis(row.family, i)]
                                                     : v * factor);
      }
    }
  }
  for (auto& slot : s.toolchanger.slots)
    for (double& v : slot) v = round12(v * f);
}

}  // namespace gantry
