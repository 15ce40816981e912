// Changing a profile's linear units (VD): every length-based value scales together.
#include <cmath>  // pow, log10, round

#include "gantry/settings/settings.hpp"

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

void convert_units(Settings& s, Units to) {
  const double f = units_factor(s.units, to);
  s.units = to;
  if (f == 1) return;
  // X, Y, Z are lengths; A, B, C only when VD says their unit is a length.
  std::array<bool, kAxisCount> linear{true, true, true};
  for (int i = 0; i < 3; ++i) linear[3 + i] = s.display.rotary_units[i] != AxisUnit::Degrees;
  const auto axis_f = [&](int i) { return linear[i] ? f : 1.0; };
  for (int i = 0; i < kAxisCount; ++i) {
    AxisSettings& a = s.axes[i];
    a.steps_per_unit = round12(a.steps_per_unit / axis_f(i));
    a.max_speed = round12(a.max_speed * axis_f(i));
    a.max_accel = round12(a.max_accel * axis_f(i));
    a.min = round12(a.min * axis_f(i));
    a.max = round12(a.max * axis_f(i));
  }
  // Speed groups: XY and Z are lengths; A, B, C follow their axes.
  const auto groups = [&](GroupSpeeds& g) {
    g.xy = round12(g.xy * f);
    g.z = round12(g.z * f);
    g.a = round12(g.a * axis_f(3));
    g.b = round12(g.b * axis_f(4));
    g.c = round12(g.c * axis_f(5));
  };
  groups(s.speeds.move);
  groups(s.speeds.jog);
  RampSettings& r = s.ramps;
  groups(r.move_ramp_speed);
  groups(r.jog_ramp_speed);
  for (double* v : {&r.move_ramp_rate,
                    &r.jog_ramp_rate,
                    &r.min_distance,
                    &r.keypad_ramp_rate,
                    &r.small_circle,
                    &s.planner.junction_deviation,
                    &s.planner.chord_tolerance,
                    &s.planner.jerk,
                    &s.cutter.diameter,
                    &s.cutter.safe_z,
                    &s.tabs.pull_up,
                    &s.tabs.spacing,
                    &s.tabs.size,
                    &s.tabs.leads,
                    &s.display.keypad_step,
                    &s.preview.grid,
                    &s.preview.table_x,
                    &s.preview.table_y,
                    &s.preview.table_z,
                    &s.calibration.circle_resolution})
    *v = round12(*v * f);
  s.cutter.safe_a = round12(s.cutter.safe_a * axis_f(3));
  const double trigger_f = axis_f(s.cutter.trigger_axis);
  s.cutter.trigger_on = round12(s.cutter.trigger_on * trigger_f);
  s.cutter.trigger_off = round12(s.cutter.trigger_off * trigger_f);
}

}  // namespace gantry
