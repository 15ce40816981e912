// Trapezoid planning and its closed-form inverse, used to place every step in time.
#include "gantry/motion/trapezoid.hpp"

#include <algorithm>  // min, max, clamp
#include <cmath>      // sqrt

namespace gantry {

Trapezoid Trapezoid::plan(double length, double v_entry, double v_max, double v_exit,
                          double accel) {
  Trapezoid p;
  p.length = length;
  p.accel = accel;
  p.v_entry = v_entry;
  p.v_exit = v_exit;
  if (length <= 0) return p;
  const double peak_sq = (2 * accel * length + v_entry * v_entry + v_exit * v_exit) / 2;
  const double peak = std::min(v_max, std::sqrt(peak_sq));
  p.v_cruise = std::max({peak, v_entry, v_exit});
  p.s_accel = (p.v_cruise * p.v_cruise - v_entry * v_entry) / (2 * accel);
  const double s_decel = (p.v_cruise * p.v_cruise - v_exit * v_exit) / (2 * accel);
  p.s_cruise = std::max(0.0, length - p.s_accel - s_decel);
  p.t_accel = (p.v_cruise - v_entry) / accel;
  p.t_decel = (p.v_cruise - v_exit) / accel;
  p.t_cruise = p.v_cruise > 0 ? p.s_cruise / p.v_cruise : 0;
  return p;
}

double Trapezoid::distance_at(double t) const {
  t = std::clamp(t, 0.0, duration());
  if (t <= t_accel) return v_entry * t + accel * t * t / 2;
  t -= t_accel;
  if (t <= t_cruise) return s_accel + v_cruise * t;
  t -= t_cruise;
  return std::min(length, s_accel + s_cruise + v_cruise * t - accel * t * t / 2);
}

// Each phase solves s = u t +/- a t^2 / 2 for t. The form t = 2 s / (u + sqrt(u^2 + 2 a s))
// is the same root as the textbook one but does not cancel when u is large and a t small.
// The deceleration phase is solved backwards from the end (remaining distance r, reached
// from v_exit accelerating), because sqrt(v^2 - 2 a s) cancels as the speed nears zero.
double Trapezoid::time_at(double s) const {
  s = std::clamp(s, 0.0, length);
  if (s <= s_accel) {
    const double d = v_entry + std::sqrt(v_entry * v_entry + 2 * accel * s);
    return d > 0 ? 2 * s / d : 0;
  }
  if (s <= s_accel + s_cruise) return t_accel + (s - s_accel) / v_cruise;
  const double r = std::max(0.0, length - s);
  const double d = v_exit + std::sqrt(v_exit * v_exit + 2 * accel * r);
  const double back = d > 0 ? 2 * r / d : 0;
  return duration() - std::min(t_decel, back);
}

double Trapezoid::speed_at(double t) const {
  t = std::clamp(t, 0.0, duration());
  if (t <= t_accel) return v_entry + accel * t;
  t -= t_accel;
  if (t <= t_cruise) return v_cruise;
  t -= t_cruise;
  return std::max(0.0, v_cruise - accel * t);
}

}  // namespace gantry
