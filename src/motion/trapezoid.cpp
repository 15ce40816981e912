// Profile planning and its inverse, used to place every step in time.
#include "gantry/motion/trapezoid.hpp"

#include <algorithm>  // min, max, clamp
#include <cmath>      // sqrt, abs

namespace gantry {
namespace {

// Distance along an S-curve ramp at x = t / T in [0, 1]: the integral of the smoothstep.
double smooth_distance(double u, double dv, double T, double x) {
  return u * x * T + dv * T * (x * x * x - x * x * x * x / 2);
}
double smooth_speed(double u, double dv, double x) {
  return u + dv * x * x * (3 - 2 * x);
}

// The time in [0, T] at which a ramp from u by dv has covered s: Newton from the middle,
// kept inside a shrinking bracket (the distance rises with time), bisecting where Newton
// would leave it (near a start from rest the speed, Newton's slope, is nearly 0).
double smooth_time_at(double u, double dv, double T, double s) {
  double lo = 0, hi = T, t = T / 2;
  for (int i = 0; i < 200 && hi - lo > 1e-14 * T; ++i) {
    const double f = smooth_distance(u, dv, T, t / T) - s;
    if (f == 0) return t;
    (f < 0 ? lo : hi) = t;
    const double v = smooth_speed(u, dv, t / T);
    const double next = v > 0 ? t - f / v : lo;
    if (next > lo && next < hi && std::abs(next - t) <= 1e-15 * T) return next;
    t = next > lo && next < hi ? next : (lo + hi) / 2;
  }
  return t;
}

}  // namespace

double ramp_time(double u, double v, double a, double j) {
  const double dv = std::abs(v - u);
  if (j <= 0) return dv / a;
  return std::max(1.5 * dv / a, std::sqrt(6 * dv / j));
}

double ramp_distance(double u, double v, double a, double j) {
  if (j <= 0) return std::abs(v * v - u * u) / (2 * a);
  return (u + v) / 2 * ramp_time(u, v, a, j);
}

// With jerk, a ramp's distance is the larger of its accel-limited one, 0.75 |v^2 - u^2| / a,
// and its jerk-limited one, (u + v) / 2 sqrt(6 |v - u| / j); both grow with the higher speed.
// Speeding up from u by w = q^2 within d, the jerk-limited one gives
//     (u + q^2 / 2) q sqrt(6 / j) = d   <=>   q^3 + 2 u q - 2 d sqrt(j / 6) = 0,
// a cubic with one real root. The reach is the lower of the two speeds, so only a root below
// q = sqrt(by_accel - u) matters. Newton starts from the lower of that and c / 2u (the root
// without its q^3 term), both above the root; the cubic is convex and rising for q > 0, so
// it descends onto the root without overshooting.
double ramp_reach(double u, double d, double a, double j) {
  if (j <= 0) return std::sqrt(u * u + 2 * a * d);
  const double by_accel = std::sqrt(u * u + 4 * a * d / 3);
  const double p = 2 * u, c = 2 * d * std::sqrt(j / 6);
  double q = std::sqrt(by_accel - u);
  if (q * q * q + p * q - c <= 0) return by_accel;  // the acceleration limit binds first
  if (p > 0) q = std::min(q, c / p);  // also above the root; close to it when u dominates
  for (int i = 0; i < 100; ++i) {
    const double step = (q * q * q + p * q - c) / (3 * q * q + p);
    q -= step;
    if (step <= 1e-14 * q) break;
  }
  return u + q * q;
}

// The jerk-limited reach is not monotonic in u: with w = v - u, (u + w / 2) sqrt(6 w / j) = d
// gives dw/du = -2w / (u + 3w/2), so dv/du = (u - w/2) / (u + 3w/2): while w > 2u, starting
// faster reaches a lower top speed (the larger change takes longer). w falls as u rises, so
// past the turn, w = 2u, where 2u sqrt(12 u / j) = d, i.e. u*^3 = d^2 j / 48 and v = 3 u*, the
// reach rises for good. Below u*, its least value over the speeds from u on is 3 u*; the
// accel-limited reach always rises, so the least of the two is at least the lower of them.
double ramp_reach_least(double u, double d, double a, double j) {
  if (j <= 0 || 48 * u * u * u >= d * d * j) return ramp_reach(u, d, a, j);
  return std::min(std::sqrt(u * u + 4 * a * d / 3), 3 * std::cbrt(d * d * j / 48));
}

// Slowing from u by w = q^2, the jerk-limited distance (u - q^2 / 2) q sqrt(6 / j) first
// grows (to w = 2u/3) and then falls: stopping outright can be shorter than slowing almost
// to rest. The floor is the lowest speed of the unbroken range of feasible speeds below u,
// so every speed between it and u is reachable too: the first root of
// q^3 - 2 u q + 2 d sqrt(j / 6) = 0 (found by bisection where the cubic falls).
double ramp_floor(double u, double d, double a, double j) {
  const double by_accel = std::sqrt(std::max(0.0, u * u - (j <= 0 ? 2 : 4.0 / 3) * a * d));
  if (j <= 0) return by_accel;
  const double c = 2 * d * std::sqrt(j / 6);
  auto f = [&](double q) { return q * q * q - 2 * u * q + c; };
  double lo = 0, hi = std::sqrt(2 * u / 3);
  if (f(hi) > 0) return by_accel;  // the jerk never binds before the speed reaches 0
  for (int i = 0; i < 60; ++i) {
    const double mid = (lo + hi) / 2;
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return std::max(by_accel, u - lo * lo);
}

Trapezoid Trapezoid::plan(double length, double v_entry, double v_max, double v_exit, double accel,
                          double jerk) {
  Trapezoid p;
  p.length = length;
  p.accel = accel;
  p.jerk = jerk;
  p.v_entry = v_entry;
  p.v_exit = v_exit;
  if (length <= 0) return p;
  const double low = std::max(v_entry, v_exit);
  if (jerk <= 0) {
    const double peak_sq = (2 * accel * length + v_entry * v_entry + v_exit * v_exit) / 2;
    p.v_cruise = std::max(low, std::min(v_max, std::sqrt(peak_sq)));
  } else {
    // The highest peak whose two ramps fit: regula falsi (Illinois) on the rising excess.
    auto excess = [&](double v) {
      return ramp_distance(v_entry, v, accel, jerk) + ramp_distance(v, v_exit, accel, jerk) -
             length;
    };
    double lo = low, hi = std::max(low, v_max);
    double f_lo = excess(lo), f_hi = excess(hi);
    if (f_hi <= 0 || f_lo >= 0) {
      p.v_cruise = f_hi <= 0 ? hi : lo;
    } else {
      int side = 0;
      for (int i = 0; i < 100 && hi - lo > 1e-13 * hi; ++i) {
        const double v = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        const double f = excess(v);
        if (f <= 0) {
          lo = v, f_lo = f;
          if (side == -1) f_hi /= 2;
          side = -1;
        } else {
          hi = v, f_hi = f;
          if (side == 1) f_lo /= 2;
          side = 1;
        }
        if (f == 0) break;
      }
      p.v_cruise = lo;  // the ramps fit at lo
    }
  }
  p.t_accel = ramp_time(v_entry, p.v_cruise, accel, jerk);
  p.t_decel = ramp_time(p.v_cruise, v_exit, accel, jerk);
  p.s_accel = ramp_distance(v_entry, p.v_cruise, accel, jerk);
  const double s_decel = ramp_distance(p.v_cruise, v_exit, accel, jerk);
  p.s_cruise = std::max(0.0, length - p.s_accel - s_decel);
  p.t_cruise = p.v_cruise > 0 ? p.s_cruise / p.v_cruise : 0;
  return p;
}

double Trapezoid::distance_at(double t) const {
  t = std::clamp(t, 0.0, duration());
  if (t <= t_accel && t_accel > 0) {
    if (jerk > 0) return smooth_distance(v_entry, v_cruise - v_entry, t_accel, t / t_accel);
    return v_entry * t + accel * t * t / 2;
  }
  t -= t_accel;
  if (t <= t_cruise) return s_accel + v_cruise * t;
  t -= t_cruise;
  if (jerk > 0 && t_decel > 0)
    return std::min(length, s_accel + s_cruise +
                                smooth_distance(v_cruise, v_exit - v_cruise, t_decel, t / t_decel));
  return std::min(length, s_accel + s_cruise + v_cruise * t - accel * t * t / 2);
}

// Linear ramps: each phase solves s = u t +/- a t^2 / 2 for t. The form
// t = 2 s / (u + sqrt(u^2 + 2 a s)) is the same root as the textbook one but does not cancel
// when u is large and a t small. The deceleration phase is solved backwards from the end
// (remaining distance r, reached from v_exit accelerating), because sqrt(v^2 - 2 a s)
// cancels as the speed nears zero. S-curve ramps: see smooth_time_at.
double Trapezoid::time_at(double s) const {
  s = std::clamp(s, 0.0, length);
  if (s <= s_accel) {
    if (jerk > 0) return smooth_time_at(v_entry, v_cruise - v_entry, t_accel, s);
    const double d = v_entry + std::sqrt(v_entry * v_entry + 2 * accel * s);
    return d > 0 ? 2 * s / d : 0;
  }
  if (s <= s_accel + s_cruise) return t_accel + (s - s_accel) / v_cruise;
  const double r = std::max(0.0, length - s);
  if (jerk > 0) {
    // Backwards from the end: a ramp from v_exit up to v_cruise, mirrored in time.
    return duration() - smooth_time_at(v_exit, v_cruise - v_exit, t_decel, r);
  }
  const double d = v_exit + std::sqrt(v_exit * v_exit + 2 * accel * r);
  const double back = d > 0 ? 2 * r / d : 0;
  return duration() - std::min(t_decel, back);
}

double Trapezoid::speed_at(double t) const {
  t = std::clamp(t, 0.0, duration());
  if (t <= t_accel && t_accel > 0) {
    if (jerk > 0) return smooth_speed(v_entry, v_cruise - v_entry, t / t_accel);
    return v_entry + accel * t;
  }
  t -= t_accel;
  if (t <= t_cruise) return v_cruise;
  t -= t_cruise;
  if (jerk > 0)
    return t_decel > 0 ? smooth_speed(v_cruise, v_exit - v_cruise, t / t_decel) : v_exit;
  return std::max(0.0, v_cruise - accel * t);
}

}  // namespace gantry
