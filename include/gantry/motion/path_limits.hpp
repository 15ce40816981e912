// Speed and acceleration along a straight path, from per-axis and per-group limits.
#pragma once

#include <span>

#include "gantry/canon/canon_move.hpp"  // CanonMove, SpeedClass
#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

// The path is parametrised by its Euclidean length in units over all six axes. A move's
// speed along it is the largest that keeps (1) the XY vector speed, and the Z, A, B, C
// speeds, within the commanded speeds of the move's class, and (2) every axis within its
// max_speed; likewise its acceleration.
struct PathLimits {
  double length = 0;         // units
  double speed = 0;          // units/s along the path: commanded, within the machine's limit
  double machine_speed = 0;  // units/s: the axes' max_speed alone (feed override's ceiling)
  double accel = 0;          // units/s^2 along the path
};

// The largest s with s |share_i| <= limit_i for every component with a share (infinity when
// none has one): how fast (or hard) a path may go when each component takes its share.
double limit_along(std::span<const double> shares, std::span<const double> limits);

// The commanded speed along the path, before machine limits: what `gantry moves` reports.
double nominal_path_speed(const Vec6& delta, const GroupSpeeds& speeds);

// Acceleration of one speed group from its SB3 ramp values. Ramp Rate is the distance over
// which the speed changes by 2 units/s, starting from the ramp speed v_r; at constant
// acceleration a, (v_r + 2)^2 - v_r^2 = 2 a rate, so a = 2 (v_r + 1) / rate.
// With the defaults (v_r = 0.4 in/s, rate = 0.2 in) a = 14 in/s^2.
double ramp_accel(double ramp_speed, double ramp_rate);

PathLimits path_limits(const CanonMove& m, const Settings& s);

}  // namespace gantry
