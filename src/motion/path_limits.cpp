// Per-move path speed and acceleration from group speeds, ramps and axis limits.
#include "gantry/motion/path_limits.hpp"

#include <algorithm>  // min
#include <cmath>      // hypot, abs
#include <limits>     // infinity

namespace gantry {
namespace {

// Projections of the unit direction onto the five groups: |u_xy|, |u_z|, |u_a|, ...
std::array<double, 5> group_fractions(const Vec6& delta, double length) {
  return {std::hypot(delta[0], delta[1]) / length, std::abs(delta[2]) / length,
          std::abs(delta[3]) / length, std::abs(delta[4]) / length, std::abs(delta[5]) / length};
}

std::array<double, 5> as_array(const GroupSpeeds& g) {
  return {g.xy, g.z, g.a, g.b, g.c};
}

// min over groups/axes with a non-zero share of limit / share.
double limit_along(const std::array<double, 5>& fractions, const std::array<double, 5>& limits) {
  double v = std::numeric_limits<double>::infinity();
  for (size_t g = 0; g < fractions.size(); ++g)
    if (fractions[g] > 1e-12) v = std::min(v, limits[g] / fractions[g]);
  return v;
}

}  // namespace

double nominal_path_speed(const Vec6& delta, const GroupSpeeds& speeds) {
  const double length = delta.norm();
  if (length == 0) return 0;
  return limit_along(group_fractions(delta, length), as_array(speeds));
}

double ramp_accel(double ramp_speed, double ramp_rate) {
  return 2 * (ramp_speed + 1) / ramp_rate;
}

PathLimits path_limits(const CanonMove& m, const Settings& s) {
  PathLimits out;
  const Vec6 delta = m.to - m.from;
  out.length = delta.norm();
  if (out.length == 0) return out;
  const bool jog = m.speed_class == SpeedClass::Jog;
  const GroupSpeeds& rs = jog ? s.ramps.jog_ramp_speed : s.ramps.move_ramp_speed;
  const double rate = jog ? s.ramps.jog_ramp_rate : s.ramps.move_ramp_rate;
  const auto fractions = group_fractions(delta, out.length);
  const std::array<double, 5> group_accel = {ramp_accel(rs.xy, rate), ramp_accel(rs.z, rate),
                                             ramp_accel(rs.a, rate), ramp_accel(rs.b, rate),
                                             ramp_accel(rs.c, rate)};
  out.accel = limit_along(fractions, group_accel);
  out.machine_speed = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kAxisCount; ++i) {
    const double f = std::abs(delta[i]) / out.length;
    if (f <= 1e-12) continue;
    out.machine_speed = std::min(out.machine_speed, s.axes[i].max_speed / f);
    out.accel = std::min(out.accel, s.axes[i].max_accel / f);
  }
  out.speed = std::min(limit_along(fractions, as_array(m.speeds)), out.machine_speed);
  return out;
}

}  // namespace gantry
