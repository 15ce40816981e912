// The end-of-run report on the simulated card: a run whose motion broke an axis's limits is
// never called done (issue 21). The card's kinematics monitor measures what was played;
// the report turns it into the status, a violation count and the exit code.
#include <gtest/gtest.h>

#include <string>

#include "cli/report.hpp"
#include "gantry/motion/lookahead_planner.hpp"
#include "gantry/step/step_generator.hpp"
#include "segment_builders.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::vec;

// A jog along X, planned with `planner_settings` and played on a card that checks `machine`.
RunReport jog_on_card(const Settings& machine, const Settings& planner_settings) {
  SimCard card(machine);
  card.start(machine.card.pacer_hz());
  StepGenerator steps(machine, card);
  LookAheadPlanner planner(planner_settings, steps);
  CanonMove jog;
  jog.to = vec(20);
  jog.speed_class = SpeedClass::Jog;
  jog.speeds = planner_settings.speeds.jog;
  planner.move(jog);
  planner.flush();
  RunReport r;
  add_card_checks(r, card);
  return r;
}

// The card checks with no corner jump, so that every change of speed counts as acceleration:
// with one, the monitor lets a sustained excess up to the jump per 10 ms window pass
// (docs/planner.md, "The checker"). Junction mode starts and ends at rest, without a jump.
Settings strict_machine() {
  Settings s = default_settings();
  s.planner.mode = PlannerMode::Junction;
  s.planner.corner_jump = 0;
  return s;
}

TEST(RunReport, AMachineWithinItsLimitsIsDone) {
  const Settings s = strict_machine();
  const RunReport r = jog_on_card(s, s);
  EXPECT_LE(r.max_accel_ratio, 1.001);
  EXPECT_LE(r.max_velocity_ratio, 1.001);
  EXPECT_EQ(r.kinematic_violations, 0u);
  EXPECT_STREQ(run_status(r), "done");
  EXPECT_EQ(exit_code(r), 0);
  EXPECT_EQ(to_json(r)["status"], "done");
}

// A broken planner: it believes X may accelerate at 60 in/s^2 and ramps the jog at 56
// (2 (0.4 + 1) / 0.05), while the machine's X takes 20. The card measures 2.8 times the
// limit, and the report says so.
TEST(RunReport, AccelerationBeyondTheMachineIsAViolationNotDone) {
  const Settings machine = strict_machine();
  Settings broken = machine;
  broken.axes[0].max_accel = 60;
  broken.ramps.jog_ramp_rate = 0.05;
  const RunReport r = jog_on_card(machine, broken);
  EXPECT_NEAR(r.max_accel_ratio, 56.0 / 20, 0.1);
  EXPECT_GT(r.kinematic_violations, 0u);
  EXPECT_EQ(r.timing_violations, 0u);
  EXPECT_STREQ(run_status(r), "violation");
  EXPECT_EQ(exit_code(r), 1);
  const nlohmann::ordered_json j = to_json(r);
  EXPECT_EQ(j["status"], "violation");
  EXPECT_EQ(j["kinematic_violations"], r.kinematic_violations);
  const std::string text = to_text(r);
  EXPECT_NE(text.find("status     violation"), std::string::npos) << text;
  EXPECT_NE(text.find("axis X: acceleration"), std::string::npos) << text;
}

// Speed too: the broken planner runs X's jog at 12 in/s where the machine's X takes 8.
TEST(RunReport, SpeedBeyondTheMachineIsAViolationNotDone) {
  const Settings machine = strict_machine();
  Settings broken = machine;
  broken.axes[0].max_speed = 12;
  broken.speeds.jog.xy = 12;
  const RunReport r = jog_on_card(machine, broken);
  EXPECT_NEAR(r.max_velocity_ratio, 12.0 / 8, 0.01);
  EXPECT_GT(r.kinematic_violations, 0u);
  EXPECT_STREQ(run_status(r), "violation");
  EXPECT_EQ(exit_code(r), 1);
  EXPECT_NE(to_text(r).find("axis X: velocity"), std::string::npos) << to_text(r);
}

TEST(RunReport, AnErrorOutranksAViolation) {
  RunReport r;
  r.kinematic_violations = 3;
  r.errors.push_back({SourceLoc{}, Severity::Error, "stopped"});
  EXPECT_STREQ(run_status(r), "error");
  EXPECT_EQ(exit_code(r), 1);
}

}  // namespace
}  // namespace gantry
