// Windowed velocity and acceleration reconstruction from step times.
#include "sim/kinematics_monitor.hpp"

#include <algorithm>  // max
#include <cmath>      // abs, ceil

namespace gantry {

KinematicsMonitor::KinematicsMonitor(const std::array<AxisLimits, kAxisCount>& limits,
                                     double tick_s, double window_s)
    : limits_(limits),
      tick_s_(tick_s),
      window_ticks_(
          std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(window_s / tick_s)))) {}

void KinematicsMonitor::on_step(int axis, std::int64_t tick, bool positive) {
  Window& w = axes_[axis];
  if (w.open && positive == w.positive) {
    ++w.intervals;
    w.last = tick;
    if (w.last - w.first < window_ticks_) return;
  }
  if (w.open) close(axis);
  w.open = true;
  w.positive = positive;
  w.first = w.last = tick;
  w.intervals = 0;
}

void KinematicsMonitor::close(int axis) {
  Window& w = axes_[axis];
  w.open = false;
  if (w.intervals == 0 || w.last == w.first) return;
  const AxisLimits& lim = limits_[axis];
  const double dt = static_cast<double>(w.last - w.first) * tick_s_;
  const double v =
      (w.positive ? 1.0 : -1.0) * static_cast<double>(w.intervals) / (lim.steps_per_unit * dt);
  const double mid = static_cast<double>(w.first + w.last) / 2 * tick_s_;
  const double v_ratio = std::abs(v) / lim.max_speed;
  w.max_v_ratio = std::max(w.max_v_ratio, v_ratio);
  check(axis, w.first, false, v_ratio);
  if (w.have_prev && mid > w.prev_mid) {
    const double beyond_jump = std::max(0.0, std::abs(v - w.prev_v) - lim.max_jump);
    const double a_ratio = beyond_jump / (mid - w.prev_mid) / lim.max_accel;
    w.max_a_ratio = std::max(w.max_a_ratio, a_ratio);
    check(axis, w.first, true, a_ratio);
  }
  w.have_prev = true;
  w.prev_v = v;
  w.prev_mid = mid;
}

void KinematicsMonitor::check(int axis, std::int64_t tick, bool accel, double ratio) {
  if (ratio <= kTolerance) return;
  ++violation_count_;
  if (violations_.size() < 16) violations_.push_back({tick, axis, accel, ratio});
}

void KinematicsMonitor::finish() {
  for (int i = 0; i < kAxisCount; ++i)
    if (axes_[i].open) close(i);
}

double KinematicsMonitor::max_velocity_ratio() const {
  double r = 0;
  for (const Window& w : axes_) r = std::max(r, w.max_v_ratio);
  return r;
}

double KinematicsMonitor::max_accel_ratio() const {
  double r = 0;
  for (const Window& w : axes_) r = std::max(r, w.max_a_ratio);
  return r;
}

}  // namespace gantry
