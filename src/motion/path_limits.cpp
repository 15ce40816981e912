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

}  // namespace

double limit_along(std::span<const double> shares, std::span<const double> limits) {
  double v = std::numeric_limits<double>::infinity();
  for (size_t g = 0; g < shares.size(); ++g)
    if (std::abs(shares[g]) > 1e-12) v = std::min(v, limits[g] / std::abs(shares[g]));
  return v;
}

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
  const double rate = m.keypad ? s.ramps.keypad_ramp_rate
                      : jog      ? s.ramps.jog_ramp_rate
                                 : s.ramps.move_ramp_rate;
  const auto fractions = group_fractions(delta, out.length);
  const std::array<double, 5> group_accel = {ramp_accel(rs.xy, rate), ramp_accel(rs.z, rate),
                                             ramp_accel(rs.a, rate), ramp_accel(rs.b, rate),
                                             ramp_accel(rs.c, rate)};
  const Vec6 unit = delta / out.length;
  std::array<double, kAxisCount> max_speed{}, max_accel{};
  for (int i = 0; i < kAxisCount; ++i) {
    max_speed[i] = s.axes[i].max_speed;
    max_accel[i] = s.axes[i].max_accel;
  }
  const std::span<const double> shares(unit.data(), kAxisCount);
  out.accel = std::min(limit_along(fractions, group_accel), limit_along(shares, max_accel));
  out.machine_speed = limit_along(shares, max_speed);
  out.speed = std::min(limit_along(fractions, as_array(m.speeds)), out.machine_speed);
  return out;
}

}  // namespace gantry
