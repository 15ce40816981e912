// The look-ahead planner: SB3's ramp statements, the junction and stop modes, look-ahead
// depth, bounded memory, and the limits on generated stress paths (checked analytically on
// the planned segments and, independently, by the simulated card's kinematics monitor).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gantry/canon/arc_geometry.hpp"
#include "gantry/motion/corner_speed.hpp"
#include "gantry/motion/lookahead_planner.hpp"
#include "gantry/motion/path_limits.hpp"
#include "gantry/step/step_generator.hpp"
#include "segment_builders.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::Collect;
using test::vec;

// Planned segments go both to the simulated card (through the step generator) and to a list.
struct CardRun {
  struct Tee : SegmentSink {
    SegmentSink *a, *b;
    void segment(const PlannedSegment& x) override { a->segment(x), b->segment(x); }
    void flush() override { a->flush(), b->flush(); }
  };
  explicit CardRun(const Settings& s) : card(s), steps(s, card) {
    card.start(s.card.pacer_hz());
    tee.a = &steps;
    tee.b = &planned;
  }
  SimCard card;
  StepGenerator steps;
  Collect planned;
  Tee tee;
};

CanonMove line(const Vec6& from, const Vec6& to, const Settings& s,
               SpeedClass cls = SpeedClass::Move) {
  CanonMove m;
  m.from = from;
  m.to = to;
  m.speed_class = cls;
  m.speeds = cls == SpeedClass::Move ? s.speeds.move : s.speeds.jog;
  return m;
}

CanonMove stop_here() {
  CanonMove m;
  m.kind = MoveKind::Stop;
  return m;
}

// Plans a polyline through `points` (one class) and returns the segments.
std::vector<PlannedSegment> plan(const Settings& s, const std::vector<Vec6>& points,
                                 SpeedClass cls = SpeedClass::Move) {
  Collect out;
  LookAheadPlanner p(s, out);
  for (size_t i = 1; i < points.size(); ++i) p.move(line(points[i - 1], points[i], s, cls));
  p.flush();
  return out.segs;
}

Settings fast_machine(double xy_speed) {  // room for SB3's 10 in/s statements
  Settings s = default_settings();
  for (int i = 0; i < 2; ++i) s.axes[i].max_speed = 12;
  s.speeds.move.xy = xy_speed;
  return s;
}

double deg(double d) {
  return d * M_PI / 180;
}

// Two 20-inch moves meeting at a turn of `turn_deg` in XY.
std::vector<Vec6> corner(double turn_deg) {
  return {vec(0, 0), vec(20, 0),
          vec(20 + 20 * std::cos(deg(turn_deg)), 20 * std::sin(deg(turn_deg)))};
}

double junction_speed(const std::vector<PlannedSegment>& segs, size_t k) {
  EXPECT_DOUBLE_EQ(segs[k].profile.v_exit, segs[k + 1].profile.v_entry);
  return segs[k].profile.v_exit;
}

// ---- SB3 mode: the command reference's ramp statements -------------------------------

TEST(Sb3Ramps, AnIsolatedMoveStartsAndEndsAtTheRampSpeed) {
  const Settings s = default_settings();
  const auto segs = plan(s, {vec(0), vec(10)});
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].profile.v_entry, 0.4);
  EXPECT_DOUBLE_EQ(segs[0].profile.v_exit, 0.4);
  EXPECT_DOUBLE_EQ(segs[0].profile.v_cruise, 2.0);
  EXPECT_DOUBLE_EQ(segs[0].profile.accel, 14.0);  // 2 (0.4 + 1) / 0.2
}

// Fact 138 after a move shorter than the minimum distance: the turn measured from 0.15 in
// back along the path is only 6 degrees here, but the corner itself turns 90 and ramps fully
// (it was taken at 0.77 in/s), and so does a reversal.
TEST(Sb3Ramps, Fact138_ACornerAfterAShortMoveStillRampsFully) {
  const Settings s = default_settings();
  const auto corner_after_short = plan(s, {vec(0), vec(1), vec(1, 0.1), vec(2, 0.1)});
  ASSERT_EQ(corner_after_short.size(), 3u);
  EXPECT_NEAR(junction_speed(corner_after_short, 1), 0.4, 1e-12);
  const auto reversal = plan(s, {vec(0), vec(1), vec(0.9), vec(1)});
  EXPECT_NEAR(junction_speed(reversal, 0), 0.4, 1e-12);
  EXPECT_NEAR(junction_speed(reversal, 1), 0.4, 1e-12);
}

TEST(Sb3Ramps, ANinetyDegreeCornerRampsFullyDownToTheRampSpeed) {
  const auto segs = plan(default_settings(), corner(90));
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_NEAR(junction_speed(segs, 0), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(segs[0].profile.v_cruise, 2.0);
  EXPECT_DOUBLE_EQ(segs[1].profile.v_cruise, 2.0);
}

TEST(Sb3Ramps, ACornerOfMoreThan043RadiansAlwaysRampsFully) {
  const Settings s = fast_machine(1);  // slow: the graded criterion is above 0.75 rad
  EXPECT_NEAR(junction_speed(plan(s, corner(44)), 0), 0.4, 1e-12);
  EXPECT_GT(junction_speed(plan(s, corner(42)), 0), 0.4);
}

TEST(Sb3Ramps, AThreeDegreeCornerAtOneInchPerSecondDoesNotSlow) {
  EXPECT_DOUBLE_EQ(junction_speed(plan(fast_machine(1), corner(3)), 0), 1.0);
}

TEST(Sb3Ramps, AtTenInchesPerSecondASixDegreeCornerSlowsToTheSlowCornerSpeed) {
  const Settings s = fast_machine(10);
  const double v = junction_speed(plan(s, corner(6)), 0);
  // 65 % of the speed at the 5 deg criterion, falling linearly to the ramp speed at 0.75 rad.
  const double theta_c = deg(5), f = (0.75 - deg(6)) / (0.75 - theta_c);
  EXPECT_NEAR(v, 0.4 + (6.5 - 0.4) * f, 1e-9);
  EXPECT_LT(v, 6.5);
  // Below the criterion (4 deg) it does not slow; a larger slow-corner value slows less.
  EXPECT_DOUBLE_EQ(junction_speed(plan(s, corner(4)), 0), 10.0);
  Settings gentler = s;
  gentler.ramps.slow_corner = 80;
  EXPECT_GT(junction_speed(plan(gentler, corner(6)), 0), v);
}

TEST(Sb3Ramps, TheCriterionAngleFallsAsOneOverSpeed) {
  const Settings s = default_settings();
  EXPECT_NEAR(sb3_criterion_angle(10, s), deg(5), 1e-12);
  EXPECT_NEAR(sb3_criterion_angle(5, s), deg(10), 1e-12);
  EXPECT_DOUBLE_EQ(sb3_criterion_angle(1, s), 0.75);  // the full-ramp angle caps it
  Settings mm = s;
  mm.units = Units::Millimetres;
  EXPECT_NEAR(sb3_criterion_angle(254, mm), deg(5), 1e-12);
}

TEST(Sb3Ramps, AZSpeedChangeLargerThanTheZRampSpeedTriggersARamp) {
  // The manual's example: Z has to change speed from 2 to 1.3 in/s (0.7 > 0.4).
  Settings s = default_settings();
  s.speeds.move.z = 2;
  const std::vector<Vec6> path = {vec(0), vec(2, 0, 2), vec(4, 0, 3.3)};
  const auto segs = plan(s, path);
  const Vec6 u0 = (path[1] - path[0]).normalized(), u1 = (path[2] - path[1]).normalized();
  EXPECT_NEAR(segs[0].profile.v_cruise * u0[2], 2.0, 1e-12);
  EXPECT_NEAR(segs[1].profile.v_cruise * u1[2], 1.3, 1e-12);
  const double ramped = junction_speed(segs, 0);
  EXPECT_NEAR(ramped, rest_speed(u1, false, s), 1e-12);
  // A 3D threshold of 200 % (0.8 in/s) lets the same change pass without the full ramp.
  s.ramps.threshold_3d = 200;
  EXPECT_GT(junction_speed(plan(s, path), 0), 3 * ramped);
}

TEST(Sb3Ramps, MsInsideAFileForcesARampDownAndUpEvenOnAStraightLine) {
  const Settings s = default_settings();
  Collect out;
  LookAheadPlanner p(s, out);
  p.move(line(vec(0), vec(5), s));
  p.move(stop_here());
  p.move(line(vec(5), vec(10), s));
  p.flush();
  ASSERT_EQ(out.segs.size(), 2u);
  EXPECT_DOUBLE_EQ(junction_speed(out.segs, 0), 0.4);
  // Without the MS the line runs straight through at full speed.
  EXPECT_DOUBLE_EQ(junction_speed(plan(s, {vec(0), vec(5), vec(10)}), 0), 2.0);
}

TEST(Sb3Ramps, EveryJogRampsAtBothEnds) {
  EXPECT_DOUBLE_EQ(
      junction_speed(plan(default_settings(), {vec(0), vec(5), vec(10)}, SpeedClass::Jog), 0), 0.4);
}

TEST(Sb3Ramps, MovesShorterThanTheMinimumDistanceRunAtASteadySpeed) {
  // Tiny zig-zag segments: no segment speeds up and slows down within itself.
  std::vector<Vec6> pts = {vec(0)};
  for (int i = 1; i <= 200; ++i) pts.push_back(vec(0.05 * i, (i % 2) * 0.02));
  for (const PlannedSegment& seg : plan(default_settings(), pts)) {
    EXPECT_LE(seg.profile.v_cruise,
              std::max(seg.profile.v_entry, seg.profile.v_exit) * (1 + 1e-12));
  }
}

TEST(Sb3Ramps, AReversalAtTheRampSpeedStaysWithinTheCornerJump) {
  // Back and forth on X: at 0.4 in/s the reversal would change X's speed by 0.8; the corner
  // jump (0.11 x 8 = 0.88) allows it; a smaller jump halves the junction speed.
  Settings s = default_settings();
  EXPECT_NEAR(junction_speed(plan(s, {vec(0), vec(5), vec(1)}), 0), 0.4, 1e-12);
  s.planner.corner_jump = 0.05;  // 0.4 in/s
  EXPECT_NEAR(junction_speed(plan(s, {vec(0), vec(5), vec(1)}), 0), 0.2, 1e-12);
}

TEST(Sb3Ramps, SmallCirclesRunAtTheRampSpeed) {
  const Settings s = default_settings();
  auto top_speed = [&](double diameter) {
    CanonMove c = line(vec(5, 5), vec(5, 5), s);
    c.kind = MoveKind::Arc;
    c.center_x = 5 + diameter / 2;
    c.center_y = 5;
    c.sweep = 2 * M_PI;
    Collect out;
    LookAheadPlanner p(s, out);
    p.move(c);
    p.flush();
    double top = 0;
    for (const PlannedSegment& seg : out.segs) top = std::max(top, seg.profile.v_cruise);
    EXPECT_EQ(out.segs.back().to, vec(5, 5));
    return top;
  };
  EXPECT_LE(top_speed(0.2), 0.4 + 1e-12);  // below the 0.25 in small-circle diameter
  EXPECT_GT(top_speed(0.3), 0.4);
}

TEST(ArcChords, EqualChordsWithinTheToleranceEndingExactlyAtTheEnd) {
  const Settings s = default_settings();
  CanonMove quarter = line(vec(2, 1, 0), vec(1, 2, -0.5), s);  // centre (1, 1), r = 1, helix
  quarter.kind = MoveKind::Arc;
  quarter.center_x = 1;
  quarter.center_y = 1;
  quarter.sweep = M_PI / 2;
  const std::vector<Vec6> pts = arc_chords(quarter, 0.0005);
  const double step = 2 * std::acos(1 - 0.0005);
  EXPECT_EQ(pts.size(), static_cast<size_t>(std::ceil(M_PI / 2 / step)));
  EXPECT_EQ(pts.back(), quarter.to);
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_NEAR(std::hypot(pts[i][0] - 1, pts[i][1] - 1), 1, 1e-12);
    EXPECT_NEAR(pts[i][2], -0.5 * static_cast<double>(i + 1) / pts.size(), 1e-12);  // helix
  }
  quarter.sweep = -3 * M_PI / 2;  // the long way round, clockwise
  EXPECT_GT(arc_chords(quarter, 0.0005).size(), 2 * pts.size());
  EXPECT_EQ(arc_chords(quarter, 10).size(), 3u);  // a coarse tolerance: quarter turns
}

TEST(Outputs, AnOutputSwitchesAtRestBetweenTheMovesAroundIt) {
  const Settings s = default_settings();
  CardRun run(s);
  LookAheadPlanner p(s, run.tee);
  p.move(line(vec(0), vec(1), s));
  CanonMove on;
  on.kind = MoveKind::Output;
  on.from = on.to = vec(1);
  on.output = 2;
  on.output_on = true;
  p.move(on);
  p.move(line(vec(1), vec(2), s));
  p.flush();
  ASSERT_EQ(run.planned.segs.size(), 3u);
  EXPECT_EQ(run.planned.segs[0].profile.v_exit, 0.4);  // SB3 stops from the ramp speed
  EXPECT_EQ(run.planned.segs[1].output, 2);
  EXPECT_TRUE(run.planned.segs[1].output_on);
  // Onward along X, the stop's jump down and the start's jump up cancel: 0.4 to 0.4.
  EXPECT_EQ(run.planned.segs[2].profile.v_entry, 0.4);
  EXPECT_EQ(run.card.steps()[0], std::llround(2 * s.axes[0].steps_per_unit));
  EXPECT_EQ(run.card.timing_violations(), 0u);
}

// A reversal around an output (found by shared/corpus/nist_singleLines.sbp): stopping from
// the ramp speed and starting again with no time between was one jump of twice the ramp
// speed, 3.5 times Z's acceleration limit by the card's own measure.
TEST(Outputs, AReversalAroundAnOutputStaysWithinTheAcceleration) {
  const Settings s = default_settings();
  CardRun run(s);
  LookAheadPlanner p(s, run.tee);
  CanonMove down = line(vec(0), vec(0, 0, -0.8), s, SpeedClass::Jog);
  p.move(down);
  CanonMove on;
  on.kind = MoveKind::Output;
  on.from = on.to = vec(0, 0, -0.8);
  on.output = 1;
  on.output_on = true;
  p.move(on);
  p.move(line(vec(0, 0, -0.8), vec(0, 0, -0.2), s));
  p.flush();
  EXPECT_LE(run.card.kinematics().max_accel_ratio(), 1.0);
  EXPECT_EQ(run.card.timing_violations(), 0u);
}

// ---- a start right after a stop (issue 21) -------------------------------------------------

// A sync (PAUSE, a probe that touched nothing, an input read) flushes the planner: the
// machine stops from the ramp speed, and the next move starts on the card's next tick.
// Z stops going up at 0.4 in/s; its corner jump is 0.11 x 4 = 0.44 in/s, so going down it
// may start at 0.44 - 0.4 = 0.04 in/s at once (the stop and the start are one change of Z's
// speed), where it used to start at 0.4: a jump of 0.8 in/s, 2.8 x Z's acceleration by the
// card's measure.
TEST(StartAfterStop, AReversalRightAfterASyncStartsWithinTheCornerJump) {
  const Settings s = default_settings();
  CardRun run(s);
  LookAheadPlanner p(s, run.tee);
  p.move(line(vec(0), vec(0, 0, 1), s));
  p.flush();
  p.move(line(vec(0, 0, 1), vec(0, 0, 0.5), s));
  p.flush();
  ASSERT_EQ(run.planned.segs.size(), 2u);
  EXPECT_DOUBLE_EQ(run.planned.segs[0].profile.v_exit, 0.4);
  EXPECT_NEAR(run.planned.segs[1].profile.v_entry, 0.04, 1e-12);
  EXPECT_DOUBLE_EQ(run.planned.segs[1].profile.v_exit, 0.4);
  EXPECT_LE(run.card.kinematics().max_accel_ratio(), 1.001);
  EXPECT_EQ(run.card.kinematics().violations(), 0u);
  EXPECT_EQ(run.card.timing_violations(), 0u);
}

TEST(StartAfterStop, OnwardRightAfterASyncStartsAtTheRampSpeed) {
  const Settings s = default_settings();
  Collect out;
  LookAheadPlanner p(s, out);
  p.move(line(vec(0), vec(0, 0, 1), s));
  p.flush();
  p.move(line(vec(0, 0, 1), vec(0, 0, 1.5), s));
  p.flush();
  ASSERT_EQ(out.segs.size(), 2u);
  EXPECT_DOUBLE_EQ(out.segs[1].profile.v_entry, 0.4);
}

// A dwell lets the axis use its acceleration as well: Z reverses at its full ramp speed after
// (0.8 - 0.44) / 16 = 22.5 ms, and after 10 ms at 0.04 + 16 x 0.01 = 0.2 in/s.
TEST(StartAfterStop, ADwellBetweenLetsTheReversalStartFaster) {
  const Settings s = default_settings();
  const std::pair<double, double> cases[] = {{0.0, 0.04}, {0.01, 0.2}, {0.0225, 0.4}, {1.0, 0.4}};
  for (const auto& [dwell, entry] : cases) {
    SCOPED_TRACE(dwell);
    CardRun run(s);
    LookAheadPlanner p(s, run.tee);
    p.move(line(vec(0), vec(0, 0, 1), s));
    CanonMove wait;
    wait.kind = MoveKind::Dwell;
    wait.from = wait.to = vec(0, 0, 1);
    wait.dwell_s = dwell;
    p.move(wait);
    p.move(line(vec(0, 0, 1), vec(0, 0, 0.5), s));
    p.flush();
    ASSERT_EQ(run.planned.segs.size(), 3u);
    EXPECT_NEAR(run.planned.segs[2].profile.v_entry, entry, 1e-9);
    EXPECT_LE(run.card.kinematics().max_accel_ratio(), 1.001);
    EXPECT_EQ(run.card.kinematics().violations(), 0u);
  }
}

// Each axis keeps its own jump. X and Y stop at 0.4 / sqrt 2 = 0.283 in/s each going +X +Y;
// going back -X -Y each may start at 0.88 - 0.283 = 0.597 in/s, 0.845 along the path: the
// ramp speed binds. Straight up instead, X and Y stop and Z has its whole 0.44 in/s.
TEST(StartAfterStop, EachAxisKeepsItsOwnJump) {
  const Settings s = default_settings();
  Collect out;
  LookAheadPlanner p(s, out);
  p.move(line(vec(0), vec(1, 1), s));
  p.flush();
  p.move(line(vec(1, 1), vec(0.5, 0.5), s));
  p.flush();
  ASSERT_EQ(out.segs.size(), 2u);
  EXPECT_DOUBLE_EQ(out.segs[1].profile.v_entry, 0.4);
  const Vec6 stopped = vec(0.4, 0.4) / std::sqrt(2.0);
  EXPECT_NEAR(start_after_stop(stopped, vec(-1, -1) / std::sqrt(2.0), 0, s),
              (0.88 - 0.4 / std::sqrt(2.0)) * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(start_after_stop(stopped, vec(0, 0, 1), 0, s), 0.44, 1e-12);
}

// ---- junction and stop modes -------------------------------------------------------------

TEST(JunctionMode, ARightAngleCornerFollowsTheJunctionDeviationFormula) {
  Settings s = default_settings();
  s.planner.mode = PlannerMode::Junction;
  s.planner.corner_jump = 1;  // out of the way
  const double v = junction_speed(plan(s, corner(90)), 0);
  // sin(h) = cos 45 deg; R = delta sin h / (1 - sin h); the turn's acceleration is what X
  // and Y have left after the moves' own 14 in/s^2 along them: 20 - 14 = 6 in/s^2 each,
  // along du = (-1, 1)/sqrt 2, so a_turn = 6 sqrt 2.
  const double sin_h = std::cos(deg(45));
  const double r = 0.002 * sin_h / (1 - sin_h);
  EXPECT_NEAR(v, std::sqrt(6 * std::sqrt(2.0) * r), 1e-12);
  // Straight on: no slowing; from and to rest: 0.
  const auto straight = plan(s, {vec(0), vec(5), vec(10)});
  EXPECT_DOUBLE_EQ(junction_speed(straight, 0), 2.0);
  EXPECT_DOUBLE_EQ(straight.front().profile.v_entry, 0.0);
  EXPECT_DOUBLE_EQ(straight.back().profile.v_exit, 0.0);
}

TEST(StopMode, EveryMoveStartsAndEndsAtRest) {
  Settings s = default_settings();
  s.planner.mode = PlannerMode::Stop;
  const auto segs = plan(s, {vec(0), vec(5), vec(10), vec(10, 4)});
  for (const PlannedSegment& seg : segs) {
    EXPECT_DOUBLE_EQ(seg.profile.v_entry, 0.0);
    EXPECT_DOUBLE_EQ(seg.profile.v_exit, 0.0);
  }
}

// ---- look-ahead ------------------------------------------------------------------------

TEST(LookAhead, TinySegmentsStillReachFullSpeedBecauseItLooksAheadFarEnoughToStop) {
  // 0.0005 in segments at 6 in/s jog: stopping takes 6^2 / (2 x 14) = 1.29 in, 2571 segments,
  // far more than the 64 moves asked for: the planner holds what stopping needs.
  Settings s = default_settings();
  s.planner.lookahead = 64;
  std::vector<Vec6> pts;
  for (int i = 0; i <= 12000; ++i) pts.push_back(vec(1 + i * 0.0005));
  Collect out;
  LookAheadPlanner p(s, out);
  for (size_t i = 1; i < pts.size(); ++i) p.move(line(pts[i - 1], pts[i], s, SpeedClass::Move));
  p.flush();
  double top = 0;
  for (const PlannedSegment& seg : out.segs) top = std::max(top, seg.profile.v_cruise);
  EXPECT_DOUBLE_EQ(top, 2.0);
  EXPECT_GE(p.most_held(), 280u);  // 2^2 / 28 = 0.143 in = 286 segments
  EXPECT_LE(p.most_held(), 64u * 64u + 1);
}

TEST(LookAhead, MemoryIsBoundedWhateverTheFileLength) {
  Settings s = default_settings();
  s.planner.lookahead = 16;
  Collect out;
  LookAheadPlanner p(s, out);
  Vec6 at = vec(1, 1);
  for (int i = 0; i < 100000; ++i) {
    const Vec6 next = at + vec(1e-5 * (1 + i % 3), 1e-5 * (i % 2));
    p.move(line(at, next, s));
    at = next;
  }
  p.flush();
  EXPECT_LE(p.most_held(), 16u * 64u + 1);
  EXPECT_EQ(out.segs.back().to, at);
}

// ---- limits on stress paths --------------------------------------------------------------

struct Stress {
  const char* name;
  std::vector<CanonMove> moves;
};

std::vector<Stress> stress_paths(const Settings& s) {
  std::vector<Stress> out;
  auto add = [&](const char* name, std::vector<Vec6> pts, SpeedClass cls) {
    Stress st{name, {}};
    pts.insert(pts.begin(), Vec6::Zero());  // the machine starts at the origin
    for (size_t i = 1; i < pts.size(); ++i) st.moves.push_back(line(pts[i - 1], pts[i], s, cls));
    out.push_back(std::move(st));
  };
  std::vector<Vec6> zig = {vec(1, 1)};
  for (int i = 1; i <= 400; ++i) zig.push_back(vec(1 + 0.05 * i, 1 + (i % 2) * 0.5));
  add("zig-zag", zig, SpeedClass::Move);
  add("zig-zag jog", zig, SpeedClass::Jog);
  std::vector<Vec6> tiny = {vec(1, 1)};
  for (int i = 1; i <= 3000; ++i)
    tiny.push_back(tiny.back() + vec(0.002 * std::cos(i * 0.05), 0.002 * std::sin(i * 0.05)));
  add("tiny segments", tiny, SpeedClass::Move);
  std::vector<Vec6> arcs = {vec(1, 8)};  // semicircles of alternating sense, as chords
  for (int k = 0; k < 6; ++k) {
    const double r = 0.2 + 0.3 * k;
    const bool up = k % 2 == 0;
    const Vec6 c = arcs.back() + vec(r, 0);
    for (int i = 1; i <= 90; ++i) {
      const double t = up ? M_PI - M_PI * i / 90 : M_PI + M_PI * i / 90;
      arcs.push_back(c + vec(r * std::cos(t), r * std::sin(t)));
    }
  }
  add("tangent arcs", arcs, SpeedClass::Move);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(1, 20), y(1, 15), z(-1, 1), r(-90, 90);
  std::vector<Vec6> rnd = {vec(5, 5)};
  for (int i = 0; i < 200; ++i) rnd.push_back(vec(x(rng), y(rng), z(rng), r(rng), r(rng), r(rng)));
  add("random 6-axis", rnd, SpeedClass::Move);
  add("random 6-axis jog", rnd, SpeedClass::Jog);
  return out;
}

struct Case {
  PlannerMode mode;
  double corner_jump;
  double jerk = 0;
};

class StressLimits : public ::testing::TestWithParam<Case> {
 protected:
  Settings settings() const {
    Settings s = default_settings();
    s.planner.mode = GetParam().mode;
    s.planner.corner_jump = GetParam().corner_jump;
    s.planner.jerk = GetParam().jerk;
    return s;
  }
};

// Planned segments checked against the limits exactly: speeds and accelerations along
// each path and per axis, every corner's instant speed change (the stop at the end too),
// reachability of each exit from its entry, and an unbroken path from `start`.
void expect_within_limits(const std::vector<PlannedSegment>& segs, const Settings& s, Vec6 start) {
  Vec6 prev_v = Vec6::Zero();
  auto within_jump = [&](const Vec6& v, size_t k) {
    for (int i = 0; i < kAxisCount; ++i)
      ASSERT_LE(std::abs(v[i] - prev_v[i]),
                s.planner.corner_jump * s.axes[i].max_speed * (1 + 1e-9) + 1e-12)
          << "corner before segment " << k << ", axis " << i;
  };
  for (size_t k = 0; k < segs.size(); ++k) {
    const PlannedSegment& seg = segs[k];
    const Trapezoid& t = seg.profile;
    ASSERT_EQ(seg.from, start) << k;
    start = seg.to;
    if (seg.dwell_s > 0 || seg.output > 0) {  // at rest
      within_jump(Vec6::Zero(), k);
      prev_v = Vec6::Zero();
      continue;
    }
    const Vec6 u = (seg.to - seg.from) / t.length;
    ASSERT_GT(t.v_cruise, 0) << k;
    ASSERT_TRUE(t.jerk == s.planner.jerk || t.jerk == 0);  // a hold's ramps are linear
    ASSERT_LE(ramp_distance(t.v_entry, t.v_exit, t.accel, t.jerk), t.length * (1 + 1e-9) + 1e-12)
        << k;
    within_jump(t.v_entry * u, k);
    for (int i = 0; i < kAxisCount; ++i) {
      ASSERT_LE(t.v_cruise * std::abs(u[i]), s.axes[i].max_speed * (1 + 1e-12)) << k;
      ASSERT_LE(t.accel * std::abs(u[i]), s.axes[i].max_accel * (1 + 1e-12)) << k;
    }
    prev_v = t.v_exit * u;
  }
  within_jump(Vec6::Zero(), segs.size());
}

TEST_P(StressLimits, PlannedSegmentsKeepEveryLimit) {
  const Settings s = settings();
  for (const Stress& st : stress_paths(s)) {
    SCOPED_TRACE(st.name);
    Collect out;
    LookAheadPlanner p(s, out);
    for (const CanonMove& m : st.moves) p.move(m);
    p.flush();
    ASSERT_EQ(out.segs.size(), st.moves.size());
    for (size_t k = 0; k < out.segs.size(); ++k) {
      EXPECT_EQ(out.segs[k].to, st.moves[k].to);
      const PathLimits lim = path_limits(st.moves[k], s);
      ASSERT_LE(out.segs[k].profile.v_cruise, lim.speed * (1 + 1e-12)) << k;
      ASSERT_LE(out.segs[k].profile.accel, lim.accel * (1 + 1e-12)) << k;
    }
    expect_within_limits(out.segs, s, Vec6::Zero());
  }
}

// Feed hold at random points of each path, then resume: the machine comes to rest within
// the limits, goes on from rest, and ends exactly where the path ends.
TEST_P(StressLimits, FeedholdAndResumeAnywhereKeepTheLimitsAndThePath) {
  Settings s = settings();
  s.planner.lookahead = 2;  // moves go out early, so the hold finds the machine moving
  std::mt19937 rng(3);
  int moving_holds = 0;
  for (const Stress& st : stress_paths(s)) {
    SCOPED_TRACE(st.name);
    std::uniform_int_distribution<size_t> when(1, st.moves.size() - 1);
    const size_t hold_at = when(rng), resume_at = std::min(st.moves.size(), hold_at + 5);
    CardRun run(s);
    Collect& planned = run.planned;
    SimCard& card = run.card;
    LookAheadPlanner p(s, run.tee);
    for (size_t k = 0; k < st.moves.size(); ++k) {
      if (k == hold_at) {
        const size_t before = planned.segs.size();
        p.feedhold();
        EXPECT_TRUE(p.holding());
        if (planned.segs.size() > before) {  // it was moving: it slowed to rest
          ++moving_holds;
          EXPECT_EQ(planned.segs.back().profile.v_exit, 0.0);
        }
      }
      if (k == resume_at) p.resume();
      p.move(st.moves[k]);
    }
    p.resume();
    p.flush();
    card.drain();
    expect_within_limits(planned.segs, s, Vec6::Zero());
    EXPECT_EQ(planned.segs.back().to, st.moves.back().to);
    EXPECT_EQ(card.timing_violations(), 0u);
    EXPECT_LE(card.kinematics().max_velocity_ratio(), 1.0001);
    EXPECT_LE(card.kinematics().max_accel_ratio(), 1.001);
    for (int i = 0; i < kAxisCount; ++i)
      EXPECT_EQ(card.steps()[i], std::llround(st.moves.back().to[i] * s.axes[i].steps_per_unit));
  }
  if (GetParam().mode != PlannerMode::Stop && GetParam().corner_jump > 0) {  // else: corners stop
    EXPECT_GE(moving_holds, 4);
  }
}

// Feed override changes every move not yet sent, and never passes an axis's limit.
TEST_P(StressLimits, FeedOverrideTakesEffectAtOnceWithinTheLimits) {
  const Settings s = settings();
  for (double factor : {0.1, 0.5, 1.5, 2.0}) {
    for (const Stress& st : stress_paths(s)) {
      SCOPED_TRACE(st.name);
      SCOPED_TRACE(factor);
      Collect out;
      LookAheadPlanner p(s, out);
      const size_t change_at = st.moves.size() / 2;
      for (size_t k = 0; k < st.moves.size(); ++k) {
        if (k == change_at) p.feed_override(factor);
        p.move(st.moves[k]);
      }
      p.flush();
      expect_within_limits(out.segs, s, Vec6::Zero());
      // The last move runs at the new speed (or the machine's limit).
      const PathLimits lim = path_limits(st.moves.back(), s);
      EXPECT_LE(out.segs.back().profile.v_cruise,
                std::min(lim.machine_speed,
                         factor * nominal_path_speed(st.moves.back().to - st.moves.back().from,
                                                     st.moves.back().speeds)) *
                    (1 + 1e-12));
    }
  }
}

TEST_P(StressLimits, TheCardSeesEveryAxisWithinItsLimits) {
  const Settings s = settings();
  for (const Stress& st : stress_paths(s)) {
    SCOPED_TRACE(st.name);
    SimCard card(s);
    card.start(s.card.pacer_hz());
    StepGenerator steps(s, card);
    LookAheadPlanner p(s, steps);
    for (const CanonMove& m : st.moves) p.move(m);
    p.flush();
    card.drain();
    EXPECT_EQ(card.timing_violations(), 0u);
    EXPECT_LE(card.kinematics().max_velocity_ratio(), 1.0001);
    EXPECT_LE(card.kinematics().max_accel_ratio(), 1.001);
    EXPECT_NEAR(card.time_s(), p.planned_time(), 5e-6 * static_cast<double>(st.moves.size()));
    for (int i = 0; i < kAxisCount; ++i)
      EXPECT_EQ(card.steps()[i], std::llround(st.moves.back().to[i] * s.axes[i].steps_per_unit))
          << "axis " << i;
  }
}

TEST_P(StressLimits, PlanningIsDeterministic) {
  const Settings s = settings();
  const Stress st = stress_paths(s)[2];
  auto run = [&] {
    Collect out;
    LookAheadPlanner p(s, out);
    for (const CanonMove& m : st.moves) p.move(m);
    p.flush();
    return out.segs;
  };
  const auto a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].profile.v_entry, b[k].profile.v_entry);
    EXPECT_EQ(a[k].profile.v_cruise, b[k].profile.v_cruise);
    EXPECT_EQ(a[k].profile.v_exit, b[k].profile.v_exit);
  }
}

// Semicircles of alternating sense as arc moves, from the origin.
std::vector<CanonMove> tangent_arc_moves(const Settings& s) {
  std::vector<CanonMove> out = {line(vec(0), vec(1, 8), s)};
  for (int k = 0; k < 8; ++k) {
    const double r = 0.05 + 0.2 * k;
    CanonMove m = line(out.back().to, out.back().to + vec(2 * r, 0, -0.01), s);
    m.kind = MoveKind::Arc;
    m.center_x = m.from[0] + r;
    m.center_y = m.from[1];
    m.sweep = k % 2 ? M_PI : -M_PI;  // over the top, then under
    out.push_back(m);
  }
  return out;
}

TEST_P(StressLimits, ArcsRunAsChordsWithinTheToleranceAndTheLimits) {
  const Settings s = settings();
  const std::vector<CanonMove> moves = tangent_arc_moves(s);
  CardRun run(s);
  Collect& planned = run.planned;
  SimCard& card = run.card;
  LookAheadPlanner p(s, run.tee);
  for (const CanonMove& m : moves) p.move(m);
  p.flush();
  card.drain();
  expect_within_limits(planned.segs, s, Vec6::Zero());
  // Every chord end lies on its arc; every chord's middle within the tolerance of it.
  size_t k = 1;  // after the first line
  for (size_t a = 1; a < moves.size(); ++a) {
    const CanonMove& m = moves[a];
    const double r = arc_radius(m);
    for (; k < planned.segs.size() && planned.segs[k].from != m.to; ++k) {
      const PlannedSegment& c = planned.segs[k];
      const Vec6 mid = (c.from + c.to) / 2;
      EXPECT_NEAR(std::hypot(c.to[0] - m.center_x, c.to[1] - m.center_y), r, 1e-9);
      EXPECT_LE(r - std::hypot(mid[0] - m.center_x, mid[1] - m.center_y),
                s.planner.chord_tolerance + 1e-12);
      // Clockwise from the left end goes over the top; counter-clockwise, under.
      EXPECT_GE((c.to[1] - m.center_y) * (m.sweep < 0 ? 1 : -1), -1e-9);
    }
  }
  EXPECT_EQ(planned.segs.back().to, moves.back().to);
  EXPECT_LE(card.kinematics().max_velocity_ratio(), 1.0001);
  EXPECT_LE(card.kinematics().max_accel_ratio(), 1.001);
  for (int i = 0; i < kAxisCount; ++i)
    EXPECT_EQ(card.steps()[i], std::llround(moves.back().to[i] * s.axes[i].steps_per_unit));
}

INSTANTIATE_TEST_SUITE_P(
    Modes, StressLimits,
    ::testing::Values(Case{PlannerMode::SB3, 0.11}, Case{PlannerMode::Junction, 0.11},
                      Case{PlannerMode::Stop, 0.11},
                      // No corner jump: the monitor's plain check.
                      Case{PlannerMode::SB3, 0}, Case{PlannerMode::Junction, 0},
                      // S-curve ramps.
                      Case{PlannerMode::Junction, 0.11, 200}, Case{PlannerMode::SB3, 0, 500}),
    [](const auto& info) {
      return std::string(planner_mode_name(info.param.mode)) +
             (info.param.corner_jump > 0 ? "" : "_no_jump") + (info.param.jerk > 0 ? "_jerk" : "");
    });

TEST(Outputs, AnOutputDuringAHoldWaitsForTheHeldMovesAheadOfIt) {
  Settings s = default_settings();
  s.planner.lookahead = 2;
  Collect out;
  LookAheadPlanner p(s, out);
  for (int i = 0; i < 40; ++i) p.move(line(vec(i * 0.5), vec((i + 1) * 0.5), s));
  p.feedhold();
  const Vec6 held_from = out.segs.back().to;
  CanonMove on;
  on.kind = MoveKind::Output;
  on.output = 1;
  on.output_on = true;
  on.from = on.to = vec(20);
  p.move(on);
  p.move(line(vec(20), vec(21), s));
  EXPECT_EQ(out.segs.back().to, held_from);  // nothing went out while held
  p.resume();
  p.flush();
  size_t output_at = 0;
  for (size_t k = 0; k < out.segs.size(); ++k)
    if (out.segs[k].output) output_at = k;
  ASSERT_GT(output_at, 0u);
  EXPECT_EQ(out.segs[output_at - 1].to, vec(20));  // after every move before it
  EXPECT_EQ(out.segs[output_at + 1].to, vec(21));
  expect_within_limits(out.segs, s, Vec6::Zero());
}

}  // namespace
}  // namespace gantry
