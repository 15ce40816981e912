// Holds, halts and resumes on the path: positions to the step, speeds within the limits.
#include "gantry/step/motion_feeder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // GantryError
#include "gantry/hal/input_roles.hpp"  // InputTrip
#include "gantry/motion/lookahead_planner.hpp"
#include "gantry/settings/settings.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

Vec6 at(double x, double y, double z = 0) {
  Vec6 v = Vec6::Zero();
  v << x, y, z, 0, 0, 0;
  return v;
}

// The pipeline from canonical moves to the simulated card, with the feeder in the middle.
struct Rig {
  Settings settings = default_settings();
  SimCard card{settings};
  std::unique_ptr<StepGenerator> steps;
  std::unique_ptr<MotionFeeder> feeder;
  std::unique_ptr<LookAheadPlanner> planner;
  Vec6 pos = Vec6::Zero();

  Rig() {
    card.start(settings.card.pacer_hz());
    steps = std::make_unique<StepGenerator>(settings, card);
    feeder = std::make_unique<MotionFeeder>(*steps);
    planner = std::make_unique<LookAheadPlanner>(settings, *feeder);
  }
  void line(const Vec6& to, SpeedClass cls = SpeedClass::Move) {
    CanonMove m;
    m.from = pos;
    m.to = to;
    m.speed_class = cls;
    m.speeds = cls == SpeedClass::Move ? settings.speeds.move : settings.speeds.jog;
    planner->move(m);
    pos = to;
  }
  void output(int n, bool on) {
    CanonMove m;
    m.kind = MoveKind::Output;
    m.from = m.to = pos;
    m.output = n;
    m.output_on = on;
    planner->move(m);
  }
  void dwell(double s) {
    CanonMove m;
    m.kind = MoveKind::Dwell;
    m.from = m.to = pos;
    m.dwell_s = s;
    planner->move(m);
  }
  // A path with corners of every kind: slight, square, reversing, and short moves.
  void zigzag() {
    line(at(4, 0));
    line(at(4.5, 0.2));
    line(at(4.5, 3));
    line(at(1, 3, -0.5));
    line(at(1.02, 3.01, -0.5));
    line(at(3, 1, 0));
    line(at(0, 0), SpeedClass::Jog);
  }
  std::int64_t steps_of(double units, int axis) const {
    return std::llround(units * settings.axes[axis].steps_per_unit);
  }
  std::int64_t tick(double seconds) const {
    return std::llround(seconds * settings.card.pacer_hz());
  }
};

void expect_at(const Rig& r, const Vec6& p) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(r.card.steps()[i], r.steps_of(p[i], i)) << "axis " << i;
    EXPECT_EQ(r.steps->played_position()[i], r.card.steps()[i]) << "axis " << i;
  }
}

TEST(MotionFeeder, WithoutARequestPlaysExactlyAsTheStepGeneratorAlone) {
  Rig a;
  a.zigzag();
  a.planner->flush();
  Rig b;  // no feeder
  LookAheadPlanner direct(b.settings, *b.steps);
  b.planner.reset();
  CanonMove m;
  Vec6 p = Vec6::Zero();
  for (const Vec6& to : {at(4, 0), at(4.5, 0.2), at(4.5, 3), at(1, 3, -0.5), at(1.02, 3.01, -0.5),
                         at(3, 1, 0), at(0, 0)}) {
    m.from = p;
    m.to = to;
    m.speed_class = to == at(0, 0) ? SpeedClass::Jog : SpeedClass::Move;
    m.speeds = to == at(0, 0) ? b.settings.speeds.jog : b.settings.speeds.move;
    direct.move(m);
    p = to;
  }
  direct.flush();
  EXPECT_EQ(a.card.ticks_played(), b.card.ticks_played());
  EXPECT_EQ(a.feeder->phase(), FeedPhase::Playing);
}

TEST(MotionFeeder, AHoldMidMoveStopsOnThePathWithinTheAccelerationAndResumesExactly) {
  Rig r;
  r.feeder->request_hold(r.tick(1.0));  // 4 in at 2 in/s: cruising
  r.line(at(4, 0));
  r.planner->flush();
  ASSERT_EQ(r.feeder->phase(), FeedPhase::Held);
  const Steps6 held = r.steps->played_position();
  EXPECT_GT(held[0], r.steps_of(1.5, 0));
  EXPECT_LT(held[0], r.steps_of(3.0, 0));
  EXPECT_EQ(held[1], 0);
  EXPECT_TRUE(r.feeder->flush_kept());
  r.feeder->resume();
  EXPECT_EQ(r.feeder->phase(), FeedPhase::Playing);
  expect_at(r, at(4, 0));
  EXPECT_LE(r.card.kinematics().max_accel_ratio(), 1.0);
  EXPECT_LE(r.card.kinematics().max_velocity_ratio(), 1.0);
  EXPECT_EQ(r.card.timing_violations(), 0u);
}

// SB3 ramps start at the ramp speed u: cruising at v at time t the tool is at
// x = v t - (v - u)^2 / 2a, and slowing to rest takes v^2 / 2a more.
TEST(MotionFeeder, TheHoldStopsWithinTheStoppingDistanceOfTheSpeedItHad) {
  Rig h;
  const double t = 2.5, v = h.settings.speeds.move.xy, u = h.settings.ramps.move_ramp_speed.xy;
  const double a = 2 * (u + 1) / h.settings.ramps.move_ramp_rate;
  h.feeder->request_hold(h.tick(t));
  h.line(at(10, 0));
  h.planner->flush();
  ASSERT_EQ(h.feeder->phase(), FeedPhase::Held);
  const double got =
      static_cast<double>(h.steps->played_position()[0]) / h.settings.axes[0].steps_per_unit;
  const double expected = v * t - (v - u) * (v - u) / (2 * a) + v * v / (2 * a);
  EXPECT_NEAR(got, expected, 1.5 / h.settings.axes[0].steps_per_unit);
}

TEST(MotionFeeder, HoldsAtRandomPointsOfAPathWithCornersAllEndExactly) {
  Rig plain;
  plain.zigzag();
  plain.planner->flush();
  const double total = plain.card.time_s();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> when(0.0, total);
  for (int trial = 0; trial < 25; ++trial) {
    Rig r;
    const double t = when(rng);
    r.feeder->request_hold(r.tick(t));
    r.zigzag();
    r.planner->flush();
    ASSERT_EQ(r.feeder->phase(), FeedPhase::Held) << "hold at " << t;
    r.feeder->resume();
    expect_at(r, at(0, 0));
    EXPECT_LE(r.card.kinematics().max_accel_ratio(), 1.0) << "hold at " << t;
    EXPECT_LE(r.card.kinematics().max_velocity_ratio(), 1.0) << "hold at " << t;
    EXPECT_EQ(r.card.timing_violations(), 0u) << "hold at " << t;
  }
}

TEST(MotionFeeder, AHoldDuringADwellKeepsTheRestOfTheWait) {
  Rig plain;
  plain.line(at(1, 0));
  plain.dwell(2.0);
  plain.line(at(1, 1));
  plain.planner->flush();
  Rig r;
  r.line(at(1, 0));
  r.planner->flush();
  const double moved = r.card.time_s();
  Rig h;
  h.feeder->request_hold(h.tick(moved + 0.5));
  h.line(at(1, 0));
  h.dwell(2.0);
  h.line(at(1, 1));
  h.planner->flush();
  ASSERT_EQ(h.feeder->phase(), FeedPhase::Held);
  EXPECT_EQ(h.steps->played_position()[0], h.steps_of(1, 0));
  EXPECT_NEAR(h.card.time_s(), moved + 0.5, 1e-3);
  h.feeder->resume();
  expect_at(h, at(1, 1));
  // 1.5 s of the wait remained. The move after it starts from 0, not from the SB3 ramp
  // speed u it was planned from (a resume always starts from true rest): u / a longer,
  // less the u^2 / 2a it covers meanwhile, which the plan ran at the cruise speed v.
  const double u = h.settings.ramps.move_ramp_speed.xy, v = h.settings.speeds.move.xy;
  const double a = 2 * (u + 1) / h.settings.ramps.move_ramp_rate;
  EXPECT_NEAR(h.card.time_s(), plain.card.time_s() + u / a - u * u / (2 * a * v), 1e-4);
}

TEST(MotionFeeder, AnOutputAfterAHoldIsKeptForTheResume) {
  Rig h;
  h.feeder->request_hold(h.tick(0.2));
  h.line(at(2, 0));
  h.output(1, true);
  h.line(at(2, 2));
  h.planner->flush();
  ASSERT_EQ(h.feeder->phase(), FeedPhase::Held);
  EXPECT_LT(h.steps->played_position()[0], h.steps_of(1, 0));
  h.feeder->resume();
  expect_at(h, at(2, 2));
}

TEST(MotionFeeder, AHaltStopsThePulsesAtOnceAndTheCountIsWhatPlayed) {
  Rig h;
  h.feeder->request_halt(h.tick(1.0));
  h.line(at(4, 0));
  h.planner->flush();
  ASSERT_EQ(h.feeder->phase(), FeedPhase::Halted);
  const Steps6 played = h.steps->played_position();
  EXPECT_EQ(played[0], h.card.steps()[0]);
  // At 1.0 s the move is cruising at 2 in/s: no ramp down, the count is where it was.
  const double x = static_cast<double>(played[0]) / h.settings.axes[0].steps_per_unit;
  Rig plain;
  plain.line(at(4, 0));
  plain.planner->flush();
  EXPECT_GT(x, 1.0);
  EXPECT_LT(x, 2.0);
  // A fresh start from where the tool is lands exactly.
  h.feeder->discard();
  EXPECT_EQ(h.feeder->phase(), FeedPhase::Playing);
  h.pos = at(x, 0);
  h.planner = std::make_unique<LookAheadPlanner>(h.settings, *h.feeder);
  h.line(at(0.5, 0.5));
  h.planner->flush();
  EXPECT_EQ(h.card.steps()[0], h.steps_of(0.5, 0));
  EXPECT_EQ(h.card.steps()[1], h.steps_of(0.5, 1));
  EXPECT_EQ(h.steps->played_position()[0], h.steps_of(0.5, 0));
}

TEST(MotionFeeder, DiscardAfterAHoldLeavesTheToolWhereItStopped) {
  Rig h;
  h.feeder->request_hold(h.tick(0.8));
  h.line(at(4, 0));
  h.line(at(4, 4));
  h.planner->flush();
  ASSERT_EQ(h.feeder->phase(), FeedPhase::Held);
  const Steps6 stopped = h.steps->played_position();
  h.feeder->discard();
  EXPECT_EQ(h.steps->played_position(), stopped);
  EXPECT_EQ(h.card.steps()[0], stopped[0]);
  EXPECT_EQ(h.feeder->phase(), FeedPhase::Playing);
}

// A card that faults while a resume replays the kept path: the rest is abandoned and its
// flush counted, so the job waiting for it is released (before, the fault escaped the
// feeder thread and ended the process).
TEST(MotionFeeder, ACardFaultWhileResumingAbandonsTheRestAndCountsItsFlush) {
  Rig h;
  h.feeder->request_hold(h.tick(0.2));
  h.line(at(2, 0));
  h.planner->flush();
  ASSERT_EQ(h.feeder->phase(), FeedPhase::Held);
  const std::uint64_t flushes = h.feeder->flushes_completed();
  const InputTrip estop{1u << 5, 1u << 5};  // input bit 5, active high
  h.card.set_trips(estop, {});
  h.card.set_switch(5, true);
  EXPECT_THROW(h.feeder->resume(), GantryError);
  EXPECT_EQ(h.card.fault(), CardFault::EStop);
  EXPECT_EQ(h.feeder->flushes_completed(), flushes + 1);
  EXPECT_LT(h.card.steps()[0], h.steps_of(2, 0));
}

}  // namespace
}  // namespace gantry
