// Trapezoid speed profiles and the path limits they are planned within.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gantry/canon/canon_move.hpp"
#include "gantry/motion/path_limits.hpp"
#include "gantry/motion/trapezoid.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

constexpr double kTight = 1e-12;

// Length of the deceleration phase, which Trapezoid does not store.
double decel_length(const Trapezoid& p) {
  return (p.v_cruise * p.v_cruise - p.v_exit * p.v_exit) / (2 * p.accel);
}

// ---------------------------------------------------------------------------------------
// Trapezoid::plan: phase speeds, times and lengths.

TEST(TrapezoidPlan, FullTrapezoidFromRestCruisesAtVmax) {
  const Trapezoid p = Trapezoid::plan(2.0, 0, 1.0, 0, 14);
  EXPECT_DOUBLE_EQ(p.length, 2.0);
  EXPECT_DOUBLE_EQ(p.accel, 14);
  EXPECT_DOUBLE_EQ(p.v_entry, 0);
  EXPECT_DOUBLE_EQ(p.v_cruise, 1.0);
  EXPECT_DOUBLE_EQ(p.v_exit, 0);
  EXPECT_NEAR(p.t_accel, 1.0 / 14, kTight);
  EXPECT_NEAR(p.t_decel, 1.0 / 14, kTight);
  EXPECT_NEAR(p.s_accel, 1.0 / 28, kTight);
  EXPECT_NEAR(p.s_cruise, 2.0 - 1.0 / 14, kTight);
  EXPECT_NEAR(p.t_cruise, 2.0 - 1.0 / 14, kTight);
  // Ramps of 1/14 s each plus the cruise: L / v + v / a for a rest-to-rest trapezoid.
  EXPECT_NEAR(p.duration(), 2.0 / 1.0 + 1.0 / 14, kTight);
}

TEST(TrapezoidPlan, TriangleFromRestPeaksAtSqrtAL) {
  // Ramps to 2 in/s would need 2 * 4 / 28 = 0.286 in; only 0.05 in is available.
  const Trapezoid p = Trapezoid::plan(0.05, 0, 2.0, 0, 14);
  const double peak = std::sqrt(14 * 0.05);  // v^2 = (2 a L + 0 + 0) / 2
  EXPECT_NEAR(p.v_cruise, peak, kTight);
  EXPECT_LT(p.v_cruise, 2.0);
  EXPECT_NEAR(p.s_cruise, 0, kTight);
  EXPECT_NEAR(p.t_cruise, 0, kTight);
  EXPECT_NEAR(p.s_accel, 0.025, kTight);
  EXPECT_NEAR(p.t_accel, peak / 14, kTight);
  EXPECT_NEAR(p.t_decel, peak / 14, kTight);
  EXPECT_NEAR(p.duration(), 2 * std::sqrt(0.05 / 14), kTight);
}

TEST(TrapezoidPlan, TrianglePeakWithEntryAndExitSpeedsFollowsFormula) {
  const double L = 0.1, ve = 0.3, vx = 0.5, a = 10;
  const Trapezoid p = Trapezoid::plan(L, ve, 5.0, vx, a);
  const double peak = std::sqrt((2 * a * L + ve * ve + vx * vx) / 2);  // sqrt(1.17)
  EXPECT_NEAR(peak, std::sqrt(1.17), kTight);
  EXPECT_NEAR(p.v_cruise, peak, kTight);
  EXPECT_DOUBLE_EQ(p.v_entry, ve);
  EXPECT_DOUBLE_EQ(p.v_exit, vx);
  EXPECT_NEAR(p.t_accel, (peak - ve) / a, kTight);
  EXPECT_NEAR(p.t_decel, (peak - vx) / a, kTight);
  EXPECT_NEAR(p.s_accel, (1.17 - 0.09) / 20, kTight);
  EXPECT_NEAR(decel_length(p), (1.17 - 0.25) / 20, kTight);
  EXPECT_NEAR(p.s_cruise, 0, 1e-12);
}

TEST(TrapezoidPlan, FullTrapezoidWithEntryAndExitSpeeds) {
  const double L = 1.0, ve = 0.4, vm = 1.5, vx = 0.2, a = 14;
  const Trapezoid p = Trapezoid::plan(L, ve, vm, vx, a);
  EXPECT_DOUBLE_EQ(p.v_cruise, vm);
  EXPECT_NEAR(p.t_accel, (vm - ve) / a, kTight);
  EXPECT_NEAR(p.t_decel, (vm - vx) / a, kTight);
  const double sa = (vm * vm - ve * ve) / (2 * a);
  const double sd = (vm * vm - vx * vx) / (2 * a);
  EXPECT_NEAR(p.s_accel, sa, kTight);
  EXPECT_NEAR(p.s_cruise, L - sa - sd, kTight);
  EXPECT_NEAR(p.t_cruise, (L - sa - sd) / vm, kTight);
  EXPECT_NEAR(p.duration(), (vm - ve) / a + (L - sa - sd) / vm + (vm - vx) / a, kTight);
}

TEST(TrapezoidPlan, EntryAtVmaxHasNoAccelerationPhase) {
  const Trapezoid p = Trapezoid::plan(1.0, 1.0, 1.0, 0, 10);
  EXPECT_DOUBLE_EQ(p.v_cruise, 1.0);
  EXPECT_DOUBLE_EQ(p.t_accel, 0);
  EXPECT_DOUBLE_EQ(p.s_accel, 0);
  EXPECT_NEAR(p.t_decel, 0.1, kTight);
  EXPECT_NEAR(p.s_cruise, 0.95, kTight);
}

TEST(TrapezoidPlan, ConstantSpeedWhenEntryExitAndVmaxAgree) {
  const Trapezoid p = Trapezoid::plan(0.5, 2.0, 2.0, 2.0, 14);
  EXPECT_DOUBLE_EQ(p.v_cruise, 2.0);
  EXPECT_DOUBLE_EQ(p.t_accel, 0);
  EXPECT_DOUBLE_EQ(p.t_decel, 0);
  EXPECT_DOUBLE_EQ(p.s_cruise, 0.5);
  EXPECT_DOUBLE_EQ(p.duration(), 0.25);
  EXPECT_DOUBLE_EQ(p.speed_at(0.1), 2.0);
}

TEST(TrapezoidPlan, ExitOnlyReachableByAcceleratingAllTheWay) {
  // 0 -> 1 in/s needs exactly 1 / (2 * 10) = 0.05 in: no room for anything else.
  const Trapezoid p = Trapezoid::plan(0.05, 0, 3.0, 1.0, 10);
  EXPECT_NEAR(p.v_cruise, 1.0, 1e-9);
  EXPECT_NEAR(p.t_accel, 0.1, 1e-9);
  EXPECT_NEAR(p.t_decel, 0, 1e-9);
  EXPECT_NEAR(p.duration(), 0.1, 1e-9);
}

TEST(TrapezoidPlan, ZeroLengthIsAnEmptyProfile) {
  const Trapezoid p = Trapezoid::plan(0, 0, 2.0, 0, 14);
  EXPECT_DOUBLE_EQ(p.duration(), 0);
  EXPECT_DOUBLE_EQ(p.v_cruise, 0);
  EXPECT_DOUBLE_EQ(p.s_accel, 0);
  EXPECT_DOUBLE_EQ(p.s_cruise, 0);
  EXPECT_DOUBLE_EQ(p.distance_at(0), 0);
  EXPECT_DOUBLE_EQ(p.distance_at(1), 0);
  EXPECT_DOUBLE_EQ(p.time_at(0), 0);
  EXPECT_DOUBLE_EQ(p.time_at(1), 0);
  EXPECT_DOUBLE_EQ(p.speed_at(0), 0);
}

// ---------------------------------------------------------------------------------------
// Properties over a set of profiles: full, triangle, with and without end speeds.

struct ProfileCase {
  const char* name;
  double length, v_entry, v_max, v_exit, accel;
};

void PrintTo(const ProfileCase& c, std::ostream* os) {
  *os << c.name;
}

class TrapezoidProfile : public ::testing::TestWithParam<ProfileCase> {
 protected:
  Trapezoid plan() const {
    const ProfileCase& c = GetParam();
    return Trapezoid::plan(c.length, c.v_entry, c.v_max, c.v_exit, c.accel);
  }
};

TEST_P(TrapezoidProfile, PhaseLengthsSumToTheLength) {
  const Trapezoid p = plan();
  EXPECT_NEAR(p.s_accel + p.s_cruise + decel_length(p), GetParam().length, 1e-12);
  EXPECT_GE(p.s_accel, 0);
  EXPECT_GE(p.s_cruise, 0);
  EXPECT_GE(decel_length(p), -1e-15);
}

TEST_P(TrapezoidProfile, PhaseTimesMatchSpeedChangesAndSumToDuration) {
  const Trapezoid p = plan();
  const ProfileCase& c = GetParam();
  EXPECT_NEAR(p.t_accel, (p.v_cruise - c.v_entry) / c.accel, 1e-12);
  EXPECT_NEAR(p.t_decel, (p.v_cruise - c.v_exit) / c.accel, 1e-12);
  EXPECT_NEAR(p.t_cruise * p.v_cruise, p.s_cruise, 1e-12);
  EXPECT_DOUBLE_EQ(p.duration(), p.t_accel + p.t_cruise + p.t_decel);
  // Mean speed of each ramp is the mean of its end speeds.
  EXPECT_NEAR(p.s_accel, (c.v_entry + p.v_cruise) / 2 * p.t_accel, 1e-12);
  EXPECT_NEAR(decel_length(p), (c.v_exit + p.v_cruise) / 2 * p.t_decel, 1e-12);
}

TEST_P(TrapezoidProfile, CruiseIsVmaxOrTheTrianglePeak) {
  const Trapezoid p = plan();
  const ProfileCase& c = GetParam();
  const double peak =
      std::sqrt((2 * c.accel * c.length + c.v_entry * c.v_entry + c.v_exit * c.v_exit) / 2);
  EXPECT_NEAR(p.v_cruise, std::min(c.v_max, peak), 1e-12);
  EXPECT_LE(p.v_cruise, c.v_max);
}

TEST_P(TrapezoidProfile, DistanceAtPhaseBoundariesAndEnds) {
  const Trapezoid p = plan();
  EXPECT_DOUBLE_EQ(p.distance_at(0), 0);
  EXPECT_NEAR(p.distance_at(p.t_accel), p.s_accel, 1e-12);
  EXPECT_NEAR(p.distance_at(p.t_accel + p.t_cruise), p.s_accel + p.s_cruise, 1e-12);
  EXPECT_NEAR(p.distance_at(p.duration()), p.length, 1e-12);
  EXPECT_DOUBLE_EQ(p.distance_at(-1.0), 0);                         // clamped
  EXPECT_NEAR(p.distance_at(p.duration() + 1.0), p.length, 1e-12);  // clamped
}

TEST_P(TrapezoidProfile, TimeAtPhaseBoundariesAndStart) {
  const Trapezoid p = plan();
  EXPECT_DOUBLE_EQ(p.time_at(0), 0);
  EXPECT_DOUBLE_EQ(p.time_at(-1.0), 0);  // clamped
  EXPECT_NEAR(p.time_at(p.s_accel), p.t_accel, 1e-9);
  EXPECT_NEAR(p.time_at(p.s_accel + p.s_cruise), p.t_accel + p.t_cruise, 1e-9);
}

TEST_P(TrapezoidProfile, TimeAtTheFullLengthIsTheDuration) {
  const Trapezoid p = plan();
  EXPECT_NEAR(p.time_at(p.length), p.duration(), 1e-9);
  EXPECT_NEAR(p.time_at(p.length + 1.0), p.duration(), 1e-9);  // clamped
  EXPECT_NEAR(p.time_at(p.distance_at(p.duration())), p.duration(), 1e-9);
}

TEST_P(TrapezoidProfile, TimeAtInvertsDistanceAtEverywhere) {
  const Trapezoid p = plan();
  constexpr int kSamples = 4000;  // every sample but the exact end, checked on its own
  for (int i = 0; i < kSamples; ++i) {
    const double t = p.duration() * i / kSamples;
    ASSERT_NEAR(p.time_at(p.distance_at(t)), t, 1e-9) << "t = " << t;
  }
}

TEST_P(TrapezoidProfile, DistanceAtInvertsTimeAtEverywhere) {
  const Trapezoid p = plan();
  constexpr int kSamples = 4000;
  for (int i = 0; i <= kSamples; ++i) {
    const double s = p.length * i / kSamples;
    ASSERT_NEAR(p.distance_at(p.time_at(s)), s, 1e-9) << "s = " << s;
  }
}

TEST_P(TrapezoidProfile, DistanceIsMonotonic) {
  const Trapezoid p = plan();
  double prev = -1;
  for (int i = 0; i <= 2000; ++i) {
    const double s = p.distance_at(p.duration() * i / 2000);
    ASSERT_GE(s, prev) << "sample " << i;
    prev = s;
  }
}

TEST_P(TrapezoidProfile, SpeedStartsAndEndsAtTheEndSpeeds) {
  const Trapezoid p = plan();
  EXPECT_NEAR(p.speed_at(0), GetParam().v_entry, 1e-12);
  EXPECT_NEAR(p.speed_at(p.duration()), GetParam().v_exit, 1e-9);
}

TEST_P(TrapezoidProfile, SpeedIsContinuousAcrossPhaseBoundaries) {
  const Trapezoid p = plan();
  const double a = GetParam().accel;
  const double eps = 1e-9;
  for (double b : {p.t_accel, p.t_accel + p.t_cruise}) {
    EXPECT_NEAR(p.speed_at(b - eps), p.speed_at(b + eps), 2 * a * eps + 1e-12) << "at " << b;
    EXPECT_NEAR(p.speed_at(b), p.v_cruise, 1e-9) << "at " << b;
  }
}

TEST_P(TrapezoidProfile, SpeedNeverJumpsAndStaysWithinVmax) {
  const Trapezoid p = plan();
  const double a = GetParam().accel;
  constexpr int kSamples = 5000;
  const double dt = p.duration() / kSamples;
  double prev = p.speed_at(0);
  for (int i = 1; i <= kSamples; ++i) {
    const double v = p.speed_at(dt * i);
    ASSERT_LE(std::abs(v - prev), a * dt * (1 + 1e-9) + 1e-12) << "sample " << i;
    ASSERT_LE(v, GetParam().v_max + 1e-12);
    ASSERT_GE(v, 0);
    prev = v;
  }
}

TEST_P(TrapezoidProfile, SpeedIsTheDerivativeOfDistance) {
  const Trapezoid p = plan();
  const double h = 1e-7;
  for (int i = 1; i < 200; ++i) {
    const double t = p.duration() * i / 200;
    const double numeric = (p.distance_at(t + h) - p.distance_at(t - h)) / (2 * h);
    ASSERT_NEAR(numeric, p.speed_at(t), 1e-5) << "t = " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Profiles, TrapezoidProfile,
    ::testing::Values(ProfileCase{"full_from_rest", 2.0, 0, 1.0, 0, 14},
                      ProfileCase{"triangle_from_rest", 0.05, 0, 2.0, 0, 14},
                      ProfileCase{"full_entry_exit", 1.0, 0.4, 1.5, 0.2, 14},
                      ProfileCase{"triangle_entry_exit", 0.1, 0.3, 5.0, 0.5, 10},
                      ProfileCase{"entry_at_vmax", 1.0, 1.0, 1.0, 0, 10},
                      ProfileCase{"exit_at_vmax", 1.0, 0, 1.0, 1.0, 10},
                      ProfileCase{"long_fast", 24.0, 0, 6.0, 0, 14},
                      ProfileCase{"tiny", 1e-4, 0, 2.0, 0, 14},
                      ProfileCase{"rotary_degrees", 90.0, 0, 45.0, 0, 360},
                      ProfileCase{"high_entry_short", 0.01, 2.0, 3.0, 1.95, 14}),
    [](const ::testing::TestParamInfo<ProfileCase>& info) { return info.param.name; });

// ---------------------------------------------------------------------------------------
// path_limits, ramp_accel, nominal_path_speed.

CanonMove line(const Vec6& from, const Vec6& to, const GroupSpeeds& speeds,
               SpeedClass cls = SpeedClass::Move) {
  CanonMove m;
  m.from = from;
  m.to = to;
  m.speeds = speeds;
  m.speed_class = cls;
  return m;
}

Vec6 vec(double x, double y = 0, double z = 0, double a = 0, double b = 0, double c = 0) {
  Vec6 v;
  v << x, y, z, a, b, c;
  return v;
}

// Per-axis speeds when moving along `delta` at path speed `speed`.
Vec6 axis_speeds(const Vec6& delta, double speed) {
  return delta / delta.norm() * speed;
}

TEST(RampAccel, DefaultsGiveFourteen) {
  EXPECT_DOUBLE_EQ(ramp_accel(0.4, 0.2), 14.0);
}

TEST(RampAccel, FollowsTwoTimesRampSpeedPlusOneOverRate) {
  EXPECT_DOUBLE_EQ(ramp_accel(0, 1), 2.0);
  EXPECT_DOUBLE_EQ(ramp_accel(1, 0.5), 8.0);
  EXPECT_DOUBLE_EQ(ramp_accel(0.4, 0.4), 7.0);
  // The definition: from v_r, the speed grows by 2 over `rate` at that acceleration.
  const double vr = 0.7, rate = 0.3, a = ramp_accel(vr, rate);
  EXPECT_NEAR((vr + 2) * (vr + 2) - vr * vr, 2 * a * rate, 1e-12);
}

TEST(PathLimits, PureXMoveGetsTheXySpeed) {
  const Settings s = default_settings();
  const PathLimits lim = path_limits(line(vec(1), vec(4), s.speeds.move), s);
  EXPECT_DOUBLE_EQ(lim.length, 3.0);
  EXPECT_DOUBLE_EQ(lim.speed, s.speeds.move.xy);
  EXPECT_DOUBLE_EQ(lim.speed, 2.0);
  EXPECT_DOUBLE_EQ(lim.accel, 14.0);
}

TEST(PathLimits, PureNegativeYJogGetsTheJogXySpeed) {
  const Settings s = default_settings();
  const PathLimits lim = path_limits(line(vec(0, 5), vec(0, 1), s.speeds.jog, SpeedClass::Jog), s);
  EXPECT_DOUBLE_EQ(lim.length, 4.0);
  EXPECT_DOUBLE_EQ(lim.speed, 6.0);
}

TEST(PathLimits, DiagonalXyVectorSpeedIsTheXySpeed) {
  const Settings s = default_settings();
  const Vec6 delta = vec(3, -4);
  const PathLimits lim = path_limits(line(vec(0, 5), vec(0, 5) + delta, s.speeds.move), s);
  EXPECT_DOUBLE_EQ(lim.length, 5.0);
  EXPECT_DOUBLE_EQ(lim.speed, 2.0);
  const Vec6 v = axis_speeds(delta, lim.speed);
  EXPECT_NEAR(v[0], 1.2, 1e-12);
  EXPECT_NEAR(v[1], -1.6, 1e-12);
  EXPECT_NEAR(std::hypot(v[0], v[1]), 2.0, 1e-12);
}

TEST(PathLimits, XyzMoveIsSlowedSoZKeepsItsSpeed) {
  const Settings s = default_settings();  // move xy = 2, z = 0.5
  const Vec6 delta = vec(1, 1, -1);
  const PathLimits lim = path_limits(line(Vec6::Zero(), delta, s.speeds.move), s);
  EXPECT_NEAR(lim.length, std::sqrt(3.0), 1e-12);
  const Vec6 v = axis_speeds(delta, lim.speed);
  EXPECT_NEAR(std::abs(v[2]), 0.5, 1e-12);              // Z binds
  EXPECT_NEAR(lim.speed, 0.5 * std::sqrt(3.0), 1e-12);  // path speed
  EXPECT_LT(std::hypot(v[0], v[1]), 2.0);               // XY below its speed
  EXPECT_NEAR(std::hypot(v[0], v[1]), 0.5 * std::sqrt(2.0), 1e-12);
}

TEST(PathLimits, XyzMoveWithShallowZKeepsTheXySpeed) {
  const Settings s = default_settings();
  const Vec6 delta = vec(3, 4, 0.1);
  const PathLimits lim = path_limits(line(Vec6::Zero(), delta, s.speeds.move), s);
  const Vec6 v = axis_speeds(delta, lim.speed);
  EXPECT_NEAR(std::hypot(v[0], v[1]), 2.0, 1e-12);  // XY binds
  EXPECT_LT(std::abs(v[2]), 0.5);
  EXPECT_GT(lim.speed, 2.0);  // the path (with Z) is a little faster than its XY part
}

TEST(PathLimits, ZOnlyMoveGetsTheZSpeedOfItsClass) {
  const Settings s = default_settings();
  EXPECT_DOUBLE_EQ(path_limits(line(vec(0, 0, 1), vec(0, 0, -1), s.speeds.move), s).speed, 0.5);
  EXPECT_DOUBLE_EQ(
      path_limits(line(vec(0, 0, 1), vec(0, 0, -1), s.speeds.jog, SpeedClass::Jog), s).speed, 3.0);
}

TEST(PathLimits, RotaryMoveGetsItsGroupSpeed) {
  const Settings s = default_settings();
  const PathLimits lim = path_limits(line(Vec6::Zero(), vec(0, 0, 0, 0, -90), s.speeds.move), s);
  EXPECT_DOUBLE_EQ(lim.length, 90.0);
  EXPECT_DOUBLE_EQ(lim.speed, 10.0);  // move b
}

TEST(PathLimits, UsesTheMovesOwnSpeedsNotTheProfileDefaults) {
  const Settings s = default_settings();
  GroupSpeeds slow = s.speeds.move;
  slow.xy = 0.25;
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), vec(2), slow), s).speed, 0.25);
}

TEST(PathLimits, AxisMaxSpeedCapsAPureMove) {
  Settings s = default_settings();
  s.axes[0].max_speed = 1.5;  // below the jog xy speed of 6
  const PathLimits lim = path_limits(line(Vec6::Zero(), vec(2), s.speeds.jog, SpeedClass::Jog), s);
  EXPECT_DOUBLE_EQ(lim.speed, 1.5);
}

TEST(PathLimits, AxisMaxSpeedCapsItsShareOfADiagonal) {
  Settings s = default_settings();
  s.axes[0].max_speed = 1.5;
  const Vec6 delta = vec(1, 1);
  const PathLimits lim = path_limits(line(Vec6::Zero(), delta, s.speeds.jog, SpeedClass::Jog), s);
  const Vec6 v = axis_speeds(delta, lim.speed);
  EXPECT_NEAR(v[0], 1.5, 1e-12);  // X at its limit
  EXPECT_NEAR(lim.speed, 1.5 * std::sqrt(2.0), 1e-12);
}

TEST(PathLimits, AxisMaxSpeedBindsForASmallShareToo) {
  Settings s = default_settings();
  s.axes[2].max_speed = 0.1;  // Z is a fifth of the path
  const Vec6 delta = vec(1, 0, 0.2);
  const PathLimits lim = path_limits(line(Vec6::Zero(), delta, s.speeds.move), s);
  EXPECT_NEAR(axis_speeds(delta, lim.speed)[2], 0.1, 1e-12);
  EXPECT_NEAR(lim.speed, 0.1 * std::sqrt(1.04) / 0.2, 1e-12);
}

TEST(PathLimits, AxisMaxSpeedOfAnIdleAxisDoesNotLimit) {
  Settings s = default_settings();
  s.axes[2].max_speed = 0.01;  // Z does not move
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), vec(1, 0), s.speeds.move), s).speed, 2.0);
}

TEST(PathLimits, AccelIsTheRampAccelOfTheGroup) {
  const Settings s = default_settings();
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), vec(1), s.speeds.move), s).accel, 14.0);
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), vec(0, 0, 1), s.speeds.move), s).accel, 14.0);
}

TEST(PathLimits, JogUsesTheJogRampValues) {
  Settings s = default_settings();
  s.ramps.jog_ramp_rate = 0.4;  // -> 2 * 1.4 / 0.4 = 7
  s.ramps.move_ramp_rate = 0.2;
  const Vec6 to = vec(1);
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), to, s.speeds.jog, SpeedClass::Jog), s).accel,
                   7.0);
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), to, s.speeds.move), s).accel, 14.0);
  s.ramps.jog_ramp_speed.xy = 1.0;  // -> 2 * 2 / 0.4 = 10
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), to, s.speeds.jog, SpeedClass::Jog), s).accel,
                   10.0);
}

TEST(PathLimits, AccelIsCappedByAxisMaxAccel) {
  Settings s = default_settings();
  s.axes[0].max_accel = 7;
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), vec(1), s.speeds.move), s).accel, 7.0);
}

TEST(PathLimits, AccelIsCappedByTheAxisShareOfADiagonal) {
  Settings s = default_settings();
  s.axes[0].max_accel = 7;
  const Vec6 delta = vec(1, 1);
  const PathLimits lim = path_limits(line(Vec6::Zero(), delta, s.speeds.move), s);
  EXPECT_NEAR(lim.accel, 7 * std::sqrt(2.0), 1e-12);  // below the group's 14
  EXPECT_NEAR(axis_speeds(delta, lim.accel)[0], 7.0, 1e-12);
}

TEST(PathLimits, EachGroupGetsItsOwnRampAccelOnASharedPath) {
  const Settings s = default_settings();
  const Vec6 delta = vec(1, 0, 1);  // half the path is XY, half Z
  const PathLimits lim = path_limits(line(Vec6::Zero(), delta, s.speeds.move), s);
  EXPECT_NEAR(lim.accel, 14 * std::sqrt(2.0), 1e-12);
  const Vec6 a = axis_speeds(delta, lim.accel);  // acceleration of each axis
  EXPECT_NEAR(a[0], 14.0, 1e-12);
  EXPECT_NEAR(a[2], 14.0, 1e-12);
  EXPECT_LE(a[0], s.axes[0].max_accel);
  EXPECT_LE(a[2], s.axes[2].max_accel);
}

TEST(PathLimits, ZMaxAccelBindsOnASharedPath) {
  Settings s = default_settings();
  s.axes[2].max_accel = 10;
  const Vec6 delta = vec(1, 0, 1);
  const PathLimits lim = path_limits(line(Vec6::Zero(), delta, s.speeds.move), s);
  EXPECT_NEAR(lim.accel, 10 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(axis_speeds(delta, lim.accel)[2], 10.0, 1e-12);
}

TEST(PathLimits, ZeroLengthMoveHasNoLimits) {
  const Settings s = default_settings();
  const PathLimits lim = path_limits(line(vec(1, 2, 3), vec(1, 2, 3), s.speeds.move), s);
  EXPECT_DOUBLE_EQ(lim.length, 0);
  EXPECT_DOUBLE_EQ(lim.speed, 0);
  EXPECT_DOUBLE_EQ(lim.accel, 0);
}

TEST(NominalPathSpeed, PureAndDiagonalXyGetTheXySpeed) {
  const GroupSpeeds g{2.0, 0.5, 10, 10, 10};
  EXPECT_DOUBLE_EQ(nominal_path_speed(vec(3), g), 2.0);
  EXPECT_DOUBLE_EQ(nominal_path_speed(vec(0, -3), g), 2.0);
  EXPECT_DOUBLE_EQ(nominal_path_speed(vec(3, 4), g), 2.0);
}

TEST(NominalPathSpeed, ZBindsOnASteepXyzMove) {
  const GroupSpeeds g{2.0, 0.5, 10, 10, 10};
  EXPECT_NEAR(nominal_path_speed(vec(1, 1, 1), g), 0.5 * std::sqrt(3.0), 1e-12);
  EXPECT_DOUBLE_EQ(nominal_path_speed(vec(0, 0, -2), g), 0.5);
}

TEST(NominalPathSpeed, RotaryAndZeroMoves) {
  const GroupSpeeds g{2.0, 0.5, 10, 20, 30};
  EXPECT_DOUBLE_EQ(nominal_path_speed(vec(0, 0, 0, 0, 0, 5), g), 30.0);
  EXPECT_DOUBLE_EQ(nominal_path_speed(vec(0, 0, 0, 0, 7), g), 20.0);
  EXPECT_DOUBLE_EQ(nominal_path_speed(Vec6::Zero(), g), 0);
}

TEST(NominalPathSpeed, IgnoresAxisLimitsThatPathLimitsApplies) {
  Settings s = default_settings();
  s.axes[0].max_speed = 1.0;
  const Vec6 delta = vec(2);
  EXPECT_DOUBLE_EQ(nominal_path_speed(delta, s.speeds.move), 2.0);
  EXPECT_DOUBLE_EQ(path_limits(line(Vec6::Zero(), delta, s.speeds.move), s).speed, 1.0);
}

TEST(NominalPathSpeed, AgreesWithPathLimitsWhenNoAxisLimitBinds) {
  const Settings s = default_settings();
  for (const Vec6& d :
       {vec(1, 2, 0.3), vec(-2, 0.5, -0.2), vec(0.1, 0, 0, 3), vec(0, 0, 1, 0, 2)}) {
    EXPECT_DOUBLE_EQ(nominal_path_speed(d, s.speeds.move),
                     path_limits(line(Vec6::Zero(), d, s.speeds.move), s).speed)
        << d.transpose();
  }
}

}  // namespace
}  // namespace gantry

namespace gantry {
namespace {

// S-curve ramps: the speed is continuous, the acceleration within a and continuous (0 at
// the ends of each ramp), the jerk within j; time_at inverts distance_at.
struct SCase {
  double length, v_entry, v_max, v_exit, accel, jerk;
};

class SCurveProfile : public ::testing::TestWithParam<SCase> {};

TEST_P(SCurveProfile, AccelerationAndJerkStayWithinTheirLimits) {
  const SCase c = GetParam();
  const Trapezoid p = Trapezoid::plan(c.length, c.v_entry, c.v_max, c.v_exit, c.accel, c.jerk);
  EXPECT_NEAR(p.s_accel + p.s_cruise + ramp_distance(p.v_cruise, p.v_exit, p.accel, p.jerk),
              c.length, 1e-9);
  EXPECT_LE(p.v_cruise, c.v_max + 1e-12);
  EXPECT_NEAR(p.distance_at(p.duration()), c.length, 1e-9);
  const int n = 20000;
  const double dt = p.duration() / n;
  double prev_a = 0;
  for (int i = 1; i < n; ++i) {
    const double t = i * dt;
    const double a = (p.speed_at(t + dt / 2) - p.speed_at(t - dt / 2)) / dt;
    ASSERT_LE(std::abs(a), c.accel * (1 + 1e-3)) << t;
    if (i > 1) {
      ASSERT_LE(std::abs(a - prev_a) / dt, c.jerk * 1.01) << t;
    }
    prev_a = a;
    const double s = p.distance_at(t);
    ASSERT_NEAR(p.time_at(s), t, 1e-9) << t;
  }
  EXPECT_NEAR(p.speed_at(p.t_accel * 0.999), p.v_cruise, 1e-3 * p.v_cruise + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SCurveProfile,
    ::testing::Values(SCase{2.0, 0, 2.0, 0, 14, 200},        // reaches cruise, accel-limited
                      SCase{2.0, 0, 2.0, 0, 14, 20},         // jerk-limited ramps
                      SCase{0.05, 0, 2.0, 0, 14, 200},       // no cruise
                      SCase{1.0, 0.4, 3.0, 1.2, 14, 500},    // moving entry and exit
                      SCase{0.3, 1.5, 1.5, 0.2, 10, 300}));  // slowing only

TEST(RampHelpers, ReachAndFloorInvertTheRampDistance) {
  for (double j : {0.0, 50.0, 500.0}) {
    const double v = ramp_reach(0.4, 0.3, 14, j);
    EXPECT_NEAR(ramp_distance(0.4, v, 14, j), 0.3, 1e-9) << j;
    const double w = ramp_floor(2.0, 0.05, 14, j);
    EXPECT_NEAR(ramp_distance(w, 2.0, 14, j), 0.05, 1e-9) << j;
    EXPECT_EQ(ramp_floor(0.5, 10, 14, j), 0.0);  // room to stop
  }
  EXPECT_DOUBLE_EQ(ramp_reach(0, 0.5, 14, 0), std::sqrt(14.0));
}

}  // namespace
}  // namespace gantry
