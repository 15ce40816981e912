// A constant-acceleration speed profile along one path: accelerate, cruise, decelerate.
#pragma once

namespace gantry {

//  speed
//    ^      ______________  v_cruise
//    |     /              \ .
//    |    /                \ .
//    |   /                  \  v_exit
//    |  |v_entry             |
//    +--+----+-----------+---+--> time
//        t_accel  t_cruise  t_decel
//
// With acceleration a, the distance to change speed from u to v is |v^2 - u^2| / (2a).
// If the ramps alone exceed the length L, the cruise phase vanishes and the peak speed is
//   v_peak^2 = (2 a L + v_entry^2 + v_exit^2) / 2,
// found by equating the two ramp distances to L.
struct Trapezoid {
  double length = 0, accel = 0;
  double v_entry = 0, v_cruise = 0, v_exit = 0;
  double t_accel = 0, t_cruise = 0, t_decel = 0;
  double s_accel = 0, s_cruise = 0;  // lengths of the first two phases

  // Plans the fastest profile within v_max and accel. Requires the entry and exit speeds to
  // be reachable from each other over `length` (v_entry, v_exit <= v_max).
  static Trapezoid plan(double length, double v_entry, double v_max, double v_exit, double accel);

  double duration() const { return t_accel + t_cruise + t_decel; }
  // Distance travelled at time t (clamped to [0, duration]).
  double distance_at(double t) const;
  // Time at which distance s is reached (the inverse of distance_at), for s in [0, length].
  double time_at(double s) const;
  double speed_at(double t) const;
};

}  // namespace gantry
