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
  const std::array<double, kAxisCount> scale = units_scale(s, to);
  const double f = scale[0];
  s.units = to;
  if (f == 1) return;
  for (int i = 0; i < kAxisCount; ++i) {
    AxisSettings& a = s.axes[i];
    a.steps_per_unit = round12(a.steps_per_unit / scale[i]);
    a.max_speed = round12(a.max_speed * scale[i]);
    a.max_accel = round12(a.max_accel * scale[i]);
    a.min = round12(a.min * scale[i]);
    a.max = round12(a.max * scale[i]);
    s.homing.at[i] = round12(s.homing.at[i] * scale[i]);
    if (std::optional<double>& h = s.simulator.home[i]) *h = round12(*h * scale[i]);
  }
  if (s.simulator.plate_z) *s.simulator.plate_z = round12(*s.simulator.plate_z * f);
  RampSettings& r = s.ramps;
  for (GroupSpeeds* g : {&s.speeds.move, &s.speeds.jog, &r.move_ramp_speed, &r.jog_ramp_speed})
    scale_speeds(*g, scale);
  for (const SettingRow& row : settings_schema())
    if (row.unit == SettingUnit::Length) row.member(s) = round12(row.member(s) * f);
  for (double* v : {&s.planner.junction_deviation,
                    &s.planner.chord_tolerance,
                    &s.planner.jerk,
                    &s.cutter.diameter,
                    &s.cutter.safe_z,
                    &s.display.keypad_step,
                    &s.homing.fast_speed,
                    &s.homing.slow_speed,
                    &s.homing.back_off,
                    &s.preview.grid,
                    &s.preview.table_x,
                    &s.preview.table_y,
                    &s.preview.table_z,
                    &s.calibration.circle_resolution})
    *v = round12(*v * f);
  s.cutter.safe_a = round12(s.cutter.safe_a * scale[3]);
  const double trigger_f = scale[s.cutter.trigger_axis];
  s.cutter.trigger_on = round12(s.cutter.trigger_on * trigger_f);
  s.cutter.trigger_off = round12(s.cutter.trigger_off * trigger_f);
}

}  // namespace gantry
