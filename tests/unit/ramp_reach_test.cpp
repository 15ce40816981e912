// The S-curve reach in closed form (Cardano) against the Newton solver it replaced, kept here
// as the reference, and against the ramp distance it inverts; its least value over faster
// starts against a scan.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "gantry/motion/trapezoid.hpp"

namespace gantry {
namespace {

// ramp_reach before issue 27: Newton on q^3 + 2 u q - 2 d sqrt(j / 6) = 0 from above the root.
double newton_reach(double u, double d, double a, double j) {
  if (j <= 0) return std::sqrt(u * u + 2 * a * d);
  const double by_accel = std::sqrt(u * u + 4 * a * d / 3);
  const double p = 2 * u, c = 2 * d * std::sqrt(j / 6);
  double q = std::sqrt(by_accel - u);
  if (q * q * q + p * q - c <= 0) return by_accel;
  if (p > 0) q = std::min(q, c / p);
  for (int i = 0; i < 100; ++i) {
    const double step = (q * q * q + p * q - c) / (3 * q * q + p);
    q -= step;
    if (step <= 1e-14 * q) break;
  }
  return u + q * q;
}

// Speeds 0 to 50 units/s (a tenth of them from rest), distances 1e-7 to 20 units,
// accelerations 1 to 1000 units/s^2, jerks 1 to 1e6 units/s^3, log-uniform: inch and mm
// machines, from the tiniest chord to a long rapid.
struct Cases {
  std::mt19937 rng{27};
  std::uniform_real_distribution<double> unit{0, 1};
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, unit(rng)); }
  double u() { return unit(rng) < 0.1 ? 0 : log_uniform(1e-4, 50); }
  double d() { return log_uniform(1e-7, 20); }
  double a() { return log_uniform(1, 1000); }
  double j() { return log_uniform(1, 1e6); }
};

TEST(RampReach, TheClosedFormEqualsTheNewtonSolverWithinRounding) {
  Cases c;
  double worst = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    const double u = c.u(), d = c.d(), a = c.a(), j = c.j();
    const double v = ramp_reach(u, d, a, j), ref = newton_reach(u, d, a, j);
    worst = std::max(worst, std::abs(v - ref) / ref);
    // Within 1e-12 of the gain v - u, or 4e-16 of v where the gain is below rounding of v.
    ASSERT_LE(std::abs(v - ref), std::max(1e-12 * (ref - u), 4e-16 * ref))
        << u << " " << d << " " << a << " " << j;
  }
  std::printf("worst relative difference %.3g\n", worst);
}

TEST(RampReach, TheReachCoversExactlyTheDistance) {
  Cases c;
  for (int i = 0; i < 100'000; ++i) {
    const double u = c.u(), d = c.d(), a = c.a(), j = c.j();
    const double v = ramp_reach(u, d, a, j);
    ASSERT_GE(v, u);
    // Exactly d where the jerk or the acceleration binds, within rounding of the gain.
    ASSERT_NEAR(ramp_distance(u, v, a, j), d, 1e-12 * d + 1e-9 * d * u / (v - u + 1e-300))
        << u << " " << d << " " << a << " " << j;
  }
}

TEST(RampReach, TheLeastReachIsBelowTheReachFromEveryFasterStart) {
  Cases c;
  for (int i = 0; i < 2'000; ++i) {
    const double u = c.u(), d = c.d(), a = c.a(), j = c.j();
    const double least = ramp_reach_least(u, d, a, j);
    for (double w = u; w <= u + 100 * (ramp_reach(u, d, a, j) - u) + 1e-3; w = w * 1.01 + 1e-6)
      ASSERT_LE(least, ramp_reach(w, d, a, j) * (1 + 1e-12)) << u << " " << w << " " << d;
  }
  // Starting faster can reach a lower speed with jerk: the reason for ramp_reach_least.
  EXPECT_GT(ramp_reach(0, 0.02, 1000, 200), ramp_reach(0.1, 0.02, 1000, 200));
  EXPECT_EQ(ramp_reach_least(0.5, 0.02, 14, 0), ramp_reach(0.5, 0.02, 14, 0));
}

}  // namespace
}  // namespace gantry
