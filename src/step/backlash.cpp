// Backlash compensation: takeup steps at each reversal, placed on the move's own profile.
#include "gantry/step/backlash.hpp"

#include <algorithm>  // clamp, max, min
#include <cmath>      // abs, llround

#include "gantry/motion/trapezoid.hpp"   // Trapezoid
#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

void Backlash::configure(const Settings& s) {
  for (int i = 0; i < kAxisCount; ++i) {
    Axis& a = axes_[i];
    const double spu = std::abs(s.axes[i].steps_per_unit);
    a.slack = std::llround(s.axes[i].backlash * spu);
    a.offset = std::clamp<std::int64_t>(a.offset, 0, a.slack);
    // The corner jump; a planner that allows none still takes the slack, at 1 % of max_speed.
    a.speed = std::max(s.planner.corner_jump, 0.01) * s.axes[i].max_speed * spu;
  }
}

double Backlash::motor_step_time(const Trapezoid& p, double from, double to, std::int64_t count,
                                 bool positive, std::int64_t takeup, double speed,
                                 std::int64_t q) {
  const double sign = positive ? 1.0 : -1.0;
  // The load's k-th step, as StepPlacement places it: where it crosses the half step before.
  auto load_time = [&](std::int64_t k) {
    const double crossing = static_cast<double>(count) + sign * (static_cast<double>(k) - 0.5);
    const double f = to == from ? 0.0 : std::clamp((crossing - from) / (to - from), 0.0, 1.0);
    return p.time_at(f * p.length);
  };
  if (takeup == 0) return load_time(q);
  const double t_b = static_cast<double>(takeup) / speed;  // the slack is taken by then
  if (q > takeup) {
    const double t = load_time(q - takeup);
    if (t >= t_b) return t;
  }
  // Within the takeup: the motor's steps past the count, m(t), rise with t; find where m
  // crosses q - 1/2 by bisection (to a nanosecond, far below a tick).
  auto motor = [&](double t) {
    const double x = p.length > 0 ? from + (to - from) * p.distance_at(t) / p.length : to;
    return sign * (x - static_cast<double>(count)) + std::min(speed * t, static_cast<double>(takeup));
  };
  const double want = static_cast<double>(q) - 0.5;
  double lo = 0, hi = t_b;
  if (motor(lo) >= want) return lo;
  while (hi - lo > 1e-9) {
    const double mid = (lo + hi) / 2;
    (motor(mid) >= want ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace gantry
