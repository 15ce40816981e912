// A pendant's events on the controller and the simulated card: step jogs to the step, the
// dead-man rule on a fake clock, a lost link stopping a jog at once, and the buttons.
#include "gantry/session/pendant_input.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "pendant_bench.hpp"  // Bench, FakeClock
#include "sim/sim_card.hpp"

namespace gantry::session {
namespace {

using namespace std::chrono_literals;

PendantEvent wheel(int axis, int delta, double step, double percent = 100) {
  PendantEvent e;
  e.kind = PendantEvent::Kind::Wheel;
  e.axis = axis;
  e.delta = delta;
  e.step = step;
  e.percent = percent;
  return e;
}

PendantEvent press(PendantButton b, int macro = 0) {
  PendantEvent e;
  e.kind = PendantEvent::Kind::Button;
  e.button = b;
  e.macro = macro;
  return e;
}

TEST(PendantInput, StepDetentsMoveExactlyTheirStepsEvenWhenTheyComeFasterThanTheJogs) {
  Bench b;
  b.in().handle(wheel(0, 3, 0.01));
  b.settle();
  EXPECT_EQ(b.c.status().steps[0], b.steps(0.03));
  for (int k = 0; k < 7; ++k) b.in().handle(wheel(1, 1, 0.1));  // quicker than they play
  b.in().handle(wheel(1, -2, 0.1));
  b.settle();
  EXPECT_EQ(b.c.status().steps[1], b.steps(0.5, 1));
  b.in().handle(wheel(0, -3, 0.001));
  b.in().handle(wheel(2, -1, 0.1));
  b.settle();
  const ControllerStatus s = b.c.status();
  EXPECT_EQ(s.steps[0], b.steps(0.027));
  EXPECT_EQ(s.steps[2], b.steps(-0.1, 2));
  EXPECT_EQ(s.state, MachineState::Idle);
}

TEST(PendantInput, NoWheelReportFor100MsEndsAContinuousJog) {
  Bench b(/*realtime=*/true);
  b.in().handle(wheel(0, 1, 0, 30));
  ASSERT_EQ(b.c.status().state, MachineState::Jogging) << b.last_told();
  for (int ms = 10; ms <= 300; ms += 10) {  // the wheel keeps turning for 300 ms
    b.clock.ms = ms;
    if (ms % 50 == 0) b.in().handle(wheel(0, 1, 0, 30));
    b.in().tick();
    ASSERT_EQ(b.c.status().state, MachineState::Jogging) << ms;
  }
  b.clock.ms = 399;  // 99 ms after the last report
  b.in().tick();
  EXPECT_EQ(b.c.status().state, MachineState::Jogging);
  b.clock.ms = 400;
  b.in().tick();
  EXPECT_EQ(b.c.status().state, MachineState::Idle);  // released: slowing to rest
  EXPECT_FALSE(b.in().jogging());
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_GT(b.c.status().steps[0], 0);
}

TEST(PendantInput, AContinuousJogRunsAtTheKnobsShareOfTheJogSpeed) {
  Settings s = default_settings();
  Bench fast(true, s), slow(true, s);
  fast.in().handle(wheel(0, 1, 0, 100));
  slow.in().handle(wheel(0, 1, 0, 30));
  std::this_thread::sleep_for(600ms);
  fast.in().handle({.kind = PendantEvent::Kind::Lost});
  slow.in().handle({.kind = PendantEvent::Kind::Lost});
  ASSERT_TRUE(fast.c.wait_for(5s));
  ASSERT_TRUE(slow.c.wait_for(5s));
  const double f = fast.c.status().machine[0], w = slow.c.status().machine[0];
  EXPECT_GT(w, 0);
  EXPECT_LT(w, 0.6 * f) << f << " " << w;
}

TEST(PendantInput, ALostLinkStopsTheJogAtOnce) {
  Bench b(true);
  b.in().handle(wheel(1, 1, 0, 100));
  ASSERT_EQ(b.c.status().state, MachineState::Jogging) << b.last_told();
  b.in().handle(wheel(0, 1, 0, 100));  // another way: released first
  EXPECT_EQ(b.c.status().state, MachineState::Idle);
  ASSERT_TRUE(b.c.wait_for(5s));
  b.in().handle(wheel(0, 1, 0, 100));
  ASSERT_EQ(b.c.status().state, MachineState::Jogging);
  std::this_thread::sleep_for(100ms);
  b.in().handle({.kind = PendantEvent::Kind::Lost});
  EXPECT_EQ(b.c.status().state, MachineState::Idle);  // no wait for the 100 ms
  EXPECT_FALSE(b.in().jogging());
  // A long step jog is cut too.
  ASSERT_TRUE(b.c.wait_for(5s));
  const double y0 = b.c.status().machine[1];
  b.in().handle(wheel(1, 5, 1.0));
  ASSERT_EQ(b.c.status().state, MachineState::Jogging);
  std::this_thread::sleep_for(50ms);
  b.in().handle({.kind = PendantEvent::Kind::Lost});
  EXPECT_EQ(b.c.status().state, MachineState::Idle);
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_LT(b.c.status().machine[1] - y0, 1.0);  // not the 5 steps
}

TEST(PendantInput, TheWheelIsRefusedWhileAFileRuns) {
  Bench b(true);
  ASSERT_TRUE(b.c.run(Script::from_text("MS, 0.5\nMX, 3\n", "part.sbp")));
  std::this_thread::sleep_for(50ms);
  b.in().handle(wheel(0, 1, 0.1));
  EXPECT_NE(b.last_told().find("a file is running"), std::string::npos) << b.last_told();
  const std::size_t told = b.told.size();
  b.in().handle(wheel(0, 1, 0.1));  // told once a second, not each detent
  b.in().handle(wheel(0, 1, 0, 100));
  EXPECT_EQ(b.told.size(), told);
  EXPECT_EQ(b.c.status().state, MachineState::Running);
  b.in().handle(press(PendantButton::StartPause));
  b.c.wait_for(5s);
  EXPECT_EQ(b.c.status().state, MachineState::Paused);
  b.in().handle(press(PendantButton::StartPause));
  EXPECT_EQ(b.c.status().state, MachineState::Running);
  b.in().handle(press(PendantButton::FeedPlus));
  b.in().handle(press(PendantButton::FeedPlus));
  EXPECT_NEAR(b.c.status().feed_override, 1.2, 1e-12);
  b.in().handle(press(PendantButton::Stop));
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_EQ(b.c.status().state, MachineState::Stopped);
  EXPECT_LT(b.c.status().machine[0], 3.0);
}

TEST(PendantInput, ButtonsRunTheirLinesAndMacrosTheirBindings) {
  Bench b;
  b.bindings.macros[2] = "MX, 1.25";
  b.in().handle(press(PendantButton::Macro, 3));
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_EQ(b.c.status().steps[0], b.steps(1.25));
  b.in().handle(press(PendantButton::Macro, 4));
  EXPECT_EQ(b.last_told(), "macro 4 is not bound (the profile's [pendant] section)");
  b.in().handle(press(PendantButton::SafeZ));
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_EQ(b.c.status().steps[2], b.steps(b.settings.cutter.safe_z, 2));
  b.in().handle(press(PendantButton::SpindleOnOff));
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_EQ(b.c.status().outputs & 1u, 1u);
  b.in().handle(press(PendantButton::SpindleOnOff));
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_EQ(b.c.status().outputs & 1u, 0u);
  b.in().handle(press(PendantButton::FeedMinus));
  EXPECT_NEAR(b.c.status().feed_override, 0.9, 1e-12);
  ASSERT_TRUE(b.c.estop());
  b.in().handle(press(PendantButton::Reset));
  EXPECT_EQ(b.c.status().state, MachineState::Idle);
  b.in().handle(press(PendantButton::Reset));
  EXPECT_EQ(b.last_told(), "reset: acknowledge: refused, there is no E-stop to acknowledge");
}

}  // namespace
// The profile's feed override bounds (WinCNC's override L and H) hold for the pendant's
// buttons, and for the controller whoever asks.
TEST(PendantInput, FeedButtonsKeepToTheProfilesOverrideBounds) {
  Settings s = default_settings();
  s.feed_override.min = 85;
  s.feed_override.max = 120;
  Bench b(false, s);
  for (int k = 0; k < 5; ++k) b.in().handle(press(PendantButton::FeedPlus));
  EXPECT_NEAR(b.c.status().feed_override, 1.2, 1e-12);
  for (int k = 0; k < 5; ++k) b.in().handle(press(PendantButton::FeedMinus));
  EXPECT_NEAR(b.c.status().feed_override, 0.85, 1e-12);
  b.in().handle(press(PendantButton::FeedPlus));  // from 85 % to the next ten
  EXPECT_NEAR(b.c.status().feed_override, 0.9, 1e-12);
  b.c.set_feed_override(2.0);  // any front end: the controller keeps to the bounds
  EXPECT_NEAR(b.c.status().feed_override, 1.2, 1e-12);
  b.c.set_feed_override(0.1);
  EXPECT_NEAR(b.c.status().feed_override, 0.85, 1e-12);
}

}  // namespace gantry::session
