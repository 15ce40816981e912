// A speed profile along one path: accelerate, cruise, decelerate, at a bounded acceleration
// and, optionally, a bounded jerk (S-curve ramps).
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
// Linear ramps (jerk = 0): with acceleration a, the distance to change speed from u to v is
// |v^2 - u^2| / (2a). If the ramps alone exceed the length L, the cruise phase vanishes and
// the peak speed is v_peak^2 = (2 a L + v_entry^2 + v_exit^2) / 2, found by equating the two
// ramp distances to L.
//
// S-curve ramps (jerk j > 0): the speed follows the smoothstep u + dv (3x^2 - 2x^3), x = t/T,
// so the acceleration rises from 0 and falls back to 0 within each ramp. Its peak is
// 1.5 dv / T and the jerk's is 6 dv / T^2; keeping them within a and j gives
//     T = max(1.5 dv / a, sqrt(6 dv / j)).
// The mean speed over the ramp is still (u + v) / 2, so the ramp covers (u + v) T / 2.
struct Trapezoid {
  double length = 0, accel = 0, jerk = 0;
  double v_entry = 0, v_cruise = 0, v_exit = 0;
  double t_accel = 0, t_cruise = 0, t_decel = 0;
  double s_accel = 0, s_cruise = 0;  // lengths of the first two phases

  // Plans the fastest profile within v_max, accel (and jerk, when above 0). Requires the
  // entry and exit speeds to be reachable from each other over `length` (both <= v_max).
  static Trapezoid plan(double length, double v_entry, double v_max, double v_exit, double accel,
                        double jerk = 0);

  double duration() const { return t_accel + t_cruise + t_decel; }
  // Distance travelled at time t (clamped to [0, duration]).
  double distance_at(double t) const;
  // Time at which distance s is reached (the inverse of distance_at), for s in [0, length].
  double time_at(double s) const;
  double speed_at(double t) const;
};

// A ramp between speeds u and v at acceleration a (jerk j; 0: linear): its duration and the
// distance it covers.
double ramp_time(double u, double v, double a, double j);
double ramp_distance(double u, double v, double a, double j);
// The highest speed reachable from u within distance d, speeding up.
double ramp_reach(double u, double d, double a, double j);
// A lower bound of ramp_reach(w, d, a, j) over every w >= u (with jerk it is not monotonic).
double ramp_reach_least(double u, double d, double a, double j);
// The lowest speed u can be brought down to within distance d.
double ramp_floor(double u, double d, double a, double j);

}  // namespace gantry
