// The steps of an axis turning or oscillating on its own (see independent_axis.hpp).
#include "gantry/step/independent_axis.hpp"

#include <algorithm>  // max
#include <cmath>      // sqrt, acos, ceil, floor

namespace gantry {

IndependentAxis::IndependentAxis(const IndependentMotion& m, double steps_per_unit, double tick_s,
                                 std::int64_t start_tick)
    : motion_(m), t0_(start_tick), turning_(m.speed != 0) {
  if (turning_) {
    positive_ = m.speed > 0;
    v_ = std::abs(m.speed) * steps_per_unit * tick_s;
    a_ = m.accel * steps_per_unit * tick_s * tick_s;
  } else {
    positive_ = m.travel > 0;
    d_ = std::abs(m.travel) * steps_per_unit;
    w_ = 2 * M_PI * m.frequency * tick_s;
    n_ = d_ > 0.5 ? static_cast<int>(std::ceil(d_ - 0.5)) : 0;  // k - 1/2 < D
  }
}

double IndependentAxis::crossing(int k) const {
  return std::acos(std::clamp(1 - (2.0 * k - 1) / d_, -1.0, 1.0));
}

std::optional<IndependentAxis::Step> IndependentAxis::next() const {
  if (turning_) {
    const double u = static_cast<double>(taken_) + 0.5;
    const double u1 = v_ * v_ / (2 * a_);
    double t;
    if (stopping_ && u > us_) {
      if (u > ue_) return std::nullopt;
      t = ts_ + (vs_ - std::sqrt(std::max(0.0, vs_ * vs_ - 2 * a_ * (u - us_)))) / a_;
    } else {
      t = u <= u1 ? std::sqrt(2 * u / a_) : v_ / a_ + (u - u1) / v_;
    }
    return Step{static_cast<double>(t0_) + t, positive_};
  }
  if (n_ == 0 || (stopping_ && cycle_ > last_cycle_)) return std::nullopt;
  const double cycle = 2 * M_PI * static_cast<double>(cycle_);
  if (in_cycle_ < n_)  // out
    return Step{static_cast<double>(t0_) + (cycle + crossing(in_cycle_ + 1)) / w_, positive_};
  const int k = 2 * n_ - in_cycle_;  // back
  return Step{static_cast<double>(t0_) + (cycle + 2 * M_PI - crossing(k)) / w_, !positive_};
}

void IndependentAxis::taken() {
  if (turning_) {
    ++taken_;
  } else if (++in_cycle_ == 2 * n_) {
    in_cycle_ = 0;
    ++cycle_;
  }
}

void IndependentAxis::stop_from(std::int64_t tick) {
  if (stopping_) return;
  stopping_ = true;
  if (!turning_) {
    // Mid-cycle it finishes the cycle; at its start point it stops there.
    last_cycle_ = in_cycle_ == 0 ? cycle_ - 1 : cycle_;
    return;
  }
  ts_ = std::max(0.0, static_cast<double>(tick - t0_));
  const double t1 = v_ / a_;
  if (ts_ < t1) {
    vs_ = a_ * ts_;
    us_ = a_ * ts_ * ts_ / 2;
  } else {
    vs_ = v_;
    us_ = v_ * v_ / (2 * a_) + v_ * (ts_ - t1);
  }
  ue_ = us_ + vs_ * vs_ / (2 * a_);
}

}  // namespace gantry
