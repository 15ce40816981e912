// The controller on the simulated card in virtual time: pause, resume, stop, E-stop and
// keypad jogs at chosen machine times; positions to the step.
#include "gantry/machine/controller.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>  // remove
#include <fstream>
#include <random>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/job.hpp"
#include "gantry/session/activity_watch.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

struct Machine {
  Machine() = default;
  explicit Machine(Settings s) : settings(std::move(s)) {}
  Settings settings = default_settings();
  SimCard card{settings};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};

  std::int64_t steps(double units, int axis = 0) const {
    return std::llround(units * settings.axes[axis].steps_per_unit);
  }
  Outcome run(const std::string& text) { return c.run(Script::from_text(text, "part.sbp")); }
};

const char* kSquare =
    "MS, 2, 1\n"
    "M2, 4, 0\n"
    "M2, 4, 3\n"
    "M3, 1, 3, -0.25\n"
    "M2, 1, 1\n"
    "J2, 0.5, 0.5\n";

TEST(MachineStates, EveryRefusalSaysWhyAndTheDocsHoldTheTable) {
  for (int s = 0; s < kMachineStates; ++s)
    for (int r = 0; r < kRequests; ++r) {
      const Verdict v = decide(MachineState(s), Request(r));
      EXPECT_TRUE(v.next.has_value() != !v.refusal.empty())
          << state_name(MachineState(s)) << " / " << request_name(Request(r));
    }
  EXPECT_EQ(*decide(MachineState::EStop, Request::Acknowledge).next, MachineState::Idle);
  EXPECT_FALSE(decide(MachineState::EStop, Request::Run).next);
  EXPECT_FALSE(decide(MachineState::Running, Request::Jog).next);
  std::ifstream doc(std::string(GANTRY_SOURCE_DIR) + "/docs/controller.md");
  std::stringstream text;
  text << doc.rdbuf();
  EXPECT_NE(text.str().find(transition_table_markdown()), std::string::npos)
      << "docs/controller.md lacks the current table:\n"
      << transition_table_markdown();
}

TEST(Controller, RunsAFileToItsEnd) {
  Machine m;
  ASSERT_TRUE(m.run(kSquare));
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Idle);
  EXPECT_EQ(s.steps[0], m.steps(0.5));
  EXPECT_EQ(s.steps[1], m.steps(0.5, 1));
  EXPECT_EQ(s.steps[2], m.steps(-0.25, 2));
  EXPECT_DOUBLE_EQ(m.c.modal().position[0], 0.5);
}

TEST(Controller, AFileWithErrorsIsRefusedAndNothingMoves) {
  Machine m;
  const Outcome o = m.run("M2, 1, 1\nMX, 100\n");  // beyond the table
  EXPECT_FALSE(o);
  ASSERT_EQ(o.errors.size(), 1u);
  EXPECT_EQ(o.errors[0].loc.line, 2);
  EXPECT_NE(o.errors[0].message.find("soft limits"), std::string::npos);
  EXPECT_EQ(m.c.status().steps[0], 0);
  EXPECT_EQ(m.c.state(), MachineState::Idle);
}

TEST(Controller, TheSoftLimitCheckStartsFromWhereTheToolIs) {
  Machine m;
  ASSERT_TRUE(m.run("MX, 20\n"));
  m.c.wait();
  const Outcome o = m.run("SR\nMX, 5\n");  // 25 in: beyond the 24 in table
  EXPECT_FALSE(o);
  ASSERT_FALSE(o.errors.empty());
  EXPECT_EQ(o.errors[0].loc.line, 2);
}

TEST(Controller, PauseAndResumeAtRandomPointsEndExactlyWhereAFullRunEnds) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> when(0.05, 6.0);
  for (int trial = 0; trial < 8; ++trial) {
    Machine m;
    const double t = when(rng);
    m.c.schedule(Request::Pause, t);
    ASSERT_TRUE(m.run(kSquare));
    m.c.wait();
    ControllerStatus s = m.c.status();
    if (s.state == MachineState::Paused) {  // the pause came before the end
      EXPECT_EQ(s.phase, FeedPhase::Held);
      EXPECT_FALSE(m.run(kSquare));  // refused while paused
      ASSERT_TRUE(m.c.resume());
      m.c.wait();
      s = m.c.status();
    }
    EXPECT_EQ(s.state, MachineState::Idle) << "pause at " << t;
    EXPECT_EQ(s.steps[0], m.steps(0.5)) << "pause at " << t;
    EXPECT_EQ(s.steps[1], m.steps(0.5, 1)) << "pause at " << t;
    EXPECT_EQ(s.steps[2], m.steps(-0.25, 2)) << "pause at " << t;
    EXPECT_LE(m.card.kinematics().max_accel_ratio(), 1.0) << "pause at " << t;
    EXPECT_EQ(m.card.timing_violations(), 0u);
  }
}

TEST(Controller, AStopEndsTheFileWithThePositionOfThePulsesPlayed) {
  Machine m;
  m.c.schedule(Request::Stop, 1.0);
  ASSERT_TRUE(m.run(kSquare));
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Stopped);
  EXPECT_EQ(s.steps, m.card.steps());
  EXPECT_GT(s.steps[0], m.steps(1.0));
  EXPECT_LT(s.steps[0], m.steps(4.0));
  EXPECT_EQ(s.stopped_at.line, 2);  // in M2, 4, 0
  // The interpreter knows: a relative move from here lands exactly.
  const double x = static_cast<double>(s.steps[0]) / m.settings.axes[0].steps_per_unit;
  EXPECT_DOUBLE_EQ(m.c.modal().position[0], x);
  ASSERT_TRUE(m.run("MX, 2\n"));
  m.c.wait();
  EXPECT_EQ(m.c.status().steps[0], m.steps(2.0));
  EXPECT_EQ(m.c.state(), MachineState::Idle);
}

// A loop that moves nothing never waits on the motion queue, where a stop used to be seen:
// the stop is seen before every statement. The check refuses such a file (its statement
// budget), so the run here skips it, as a file that loops on a switch nobody sets would.
TEST(Controller, StopAndEStopEndALoopThatMovesNothing) {
  for (const Request r : {Request::Stop, Request::EStop}) {
    Machine m;
    ASSERT_TRUE(m.c.run(Script::from_text("MX, 0.5\nL:\nGOTO L\n", "loop.sbp"), true));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // looping by now
    EXPECT_TRUE(r == Request::Stop ? m.c.stop() : m.c.estop());
    m.c.wait();  // before the fix: for ever
    const Controller::Summary sum = m.c.summary();
    ASSERT_TRUE(sum.error);
    EXPECT_EQ(sum.error->loc.line == 2 || sum.error->loc.line == 3, true) << sum.error->loc.line;
    // The planner held the move for what would follow it: the tool is where its pulses are.
    EXPECT_EQ(m.c.status().steps, m.card.steps());
    EXPECT_EQ(m.c.state(), r == Request::Stop ? MachineState::Stopped : MachineState::EStop);
  }
}

// Issue 22 (and 25): after a stop the report said "executed 6 statements, 5 moves", the whole
// file the interpreter had read ahead. The summary counts what reached the card.
TEST(Controller, AfterAStopOrEStopTheSummaryCountsWhatReachedTheCard) {
  for (const Request r : {Request::Stop, Request::EStop}) {
    Machine m;
    ASSERT_TRUE(m.run(kSquare));  // read ahead whole: 6 statements, 5 moves
    m.c.wait();
    const Controller::Summary whole = m.c.summary();
    EXPECT_FALSE(whole.cut);
    EXPECT_EQ(whole.lines, 6u);
    EXPECT_EQ(whole.moves, 5u);
    m.c.schedule(r, 1.0);  // in M2, 4, 0: statement 2, move 1 (the counts go on from the last)
    ASSERT_TRUE(m.run(kSquare));
    m.c.wait();
    const Controller::Summary s = m.c.summary();
    EXPECT_TRUE(s.cut);
    EXPECT_EQ(s.lines, whole.lines + 2);
    EXPECT_EQ(s.moves, whole.moves + 1);
    ASSERT_TRUE(s.error.has_value());
    EXPECT_EQ(s.error->message, r == Request::Stop ? "stopped by the operator" : "E-stop");
  }
}

// --realtime: moves the planner released play out under a moving tool while the file loops
// with no motion; the card's queue runs dry while words are due. A real card underruns
// there, and so does the simulated one, saying how late the producer was (issue 22: it moved
// its clock forward, and the run was "done").
// Issue 26: a late job thread (here a loop with no motion right after moves, as a file that
// computes, or one about to ask a question) left the card dry mid-motion: the planner held
// the tail of the path (its stopping distance) until the job thread came back, and the card
// underran. Now the feeder holds the planner (grbl's invariant: what it holds ends at rest),
// and when the card needs words and no move has come it releases the held tail as planned:
// the tool slows to rest along the path, the stream ends there, and the file goes on.
TEST(Controller, InRealTimeALateJobThreadSlowsTheToolToRestInsteadOfAnUnderrun) {
  Settings settings = default_settings();
  settings.planner.lookahead = 4;  // some of the moves are released before the loop
  SimCard card{settings, true};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  std::string text = "MS, 2\n";
  // The planner holds the last 11 (its stopping distance) and releases 4, which play in
  // 0.1 s; the loop's 5 M statements take far longer (1.4 s on the 2-core CI machine).
  for (int k = 1; k <= 15; ++k) text += "MX, " + std::to_string(0.05 * k) + "\n";
  text += "&i = 0\nL:\n&i = &i + 1\nIF &i < 5000000 THEN GOTO L\nMX, 3\n";
  ASSERT_TRUE(c.run(Script::from_text(text, "part.sbp")));
  c.wait();
  const Controller::Summary s = c.summary();
  EXPECT_EQ(s.fault, CardFault::None) << (s.error ? s.error->message : "");
  EXPECT_FALSE(s.cut);
  EXPECT_FALSE(s.error.has_value()) << s.error->message;
  EXPECT_GT(s.starved_releases, 0u) << "the held tail went to the card while the loop ran";
  EXPECT_EQ(card.steps()[0], std::llround(3 * settings.axes[0].steps_per_unit));
  EXPECT_EQ(card.timing_violations(), 0u);
  EXPECT_EQ(card.kinematics().violations(), 0u) << "the slow-down is within the axes' limits";
}

// A card fault's message said where the tool was by the card's own count: after a zero (or
// a restored session, a home) that is not where the readout and the file say it is.
TEST(Controller, ACardFaultSaysWhereTheToolIsInTheFilesCoordinates) {
  Settings settings = default_settings();
  SimWorld world;
  world.stall_at_s = 1.8;  // in the second move
  SimCard card{settings, false, world};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  ASSERT_TRUE(c.run(Script::from_text("MS, 2\nMX, 2\nZX\nMX, 3\n", "part.sbp")));
  c.wait();
  const Controller::Summary s = c.summary();
  ASSERT_EQ(s.fault, CardFault::Underrun);
  ASSERT_TRUE(s.error.has_value());
  const double card_x = static_cast<double>(card.steps()[0]) / settings.axes[0].steps_per_unit;
  ASSERT_GT(card_x, 2.05);
  ASSERT_LT(card_x, 4.95);
  EXPECT_DOUBLE_EQ(c.modal().position[0], card_x - 2);
  EXPECT_NE(s.error->message.find(fmt::format("the tool is at X={:.4f} Y=0.0000 Z=0.0000 (the "
                                              "pulses played)",
                                              card_x - 2)),
            std::string::npos)
      << s.error->message;
}

TEST(Controller, EStopStopsThePulsesAtOnceAndNeedsAcknowledging) {
  Machine m;
  m.c.schedule(Request::EStop, 1.0);
  ASSERT_TRUE(m.run(kSquare));
  m.c.wait();
  ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::EStop);
  EXPECT_EQ(s.phase, FeedPhase::Halted);
  EXPECT_EQ(s.steps, m.card.steps());
  // Cruising at 2 in/s at 1 s: no ramp down, so the tool is short of where a hold would be.
  EXPECT_GT(s.steps[0], m.steps(1.5));
  EXPECT_LT(s.steps[0], m.steps(2.0));
  const Outcome refused = m.run("MX, 1\n");
  EXPECT_FALSE(refused);
  EXPECT_NE(refused.reason.find("acknowledge"), std::string::npos);
  ASSERT_TRUE(m.c.acknowledge());
  EXPECT_EQ(m.c.state(), MachineState::Idle);
  ASSERT_TRUE(m.run("MX, 1\n"));
  m.c.wait();
  EXPECT_EQ(m.c.status().steps[0], m.steps(1.0));
  EXPECT_EQ(m.card.steps()[0], m.steps(1.0));
}

// An E-stop at rest has no activity to end, so nothing had cleared its stop request: the
// first jog or move after the acknowledgement was stopped before it began (the window's X+
// did nothing, once). Both play in full.
TEST(Controller, AfterAnEStopAtRestTheNextJogAndMovePlay) {
  Machine m;
  ASSERT_TRUE(m.run("MX, 1\n"));
  m.c.wait();
  ASSERT_TRUE(m.c.estop());
  m.c.wait();
  ASSERT_EQ(m.c.state(), MachineState::EStop);
  ASSERT_TRUE(m.c.acknowledge());
  JogRequest j;
  j.direction[0] = 1;
  j.step = true;
  j.step_size = 0.5;
  ASSERT_TRUE(m.c.jog(j));
  m.c.wait();
  EXPECT_EQ(m.c.status().steps[0], m.steps(1.5));
  ASSERT_TRUE(m.c.estop());
  m.c.wait();
  ASSERT_TRUE(m.c.acknowledge());
  ASSERT_TRUE(m.run("MX, 2\n"));
  m.c.wait();
  EXPECT_EQ(m.c.status().steps[0], m.steps(2.0));
  EXPECT_EQ(m.card.steps()[0], m.steps(2.0));
}

// Issue 25: on the real-time card, the move after an acknowledged E-stop plays at once. It
// froze for as long as the card had played before (the readout said "running" with X still):
// SimCard::start() must carry the wall clock's origin with the tick count. The two times are
// compared in one run, never against a fixed figure.
TEST(Controller, InRealTimeTheMoveAfterAnAcknowledgedEStopPlaysAtOnce) {
  Settings settings = default_settings();
  SimCard card{settings, true};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  ASSERT_TRUE(c.run(Script::from_text("MS, 2\nMX, 4\n", "part.sbp")));  // about 2 s
  c.wait();
  ASSERT_TRUE(c.run(Script::from_text("MX, 0\n", "part.sbp")));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(c.estop());
  c.wait();
  ASSERT_EQ(c.state(), MachineState::EStop);
  ASSERT_TRUE(c.acknowledge());
  const double played_before_s = card.time_s();
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(c.run(Script::from_text("MX, 3.9\n", "part.sbp")));  // a few tenths of an inch
  c.wait();
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(c.state(), MachineState::Idle);
  EXPECT_EQ(c.status().steps[0], std::llround(3.9 * settings.axes[0].steps_per_unit));
  EXPECT_GT(played_before_s, 2.0);
  EXPECT_LT(took_s, played_before_s / 2) << "the move waited for the ticks before the E-stop";
}

// Issue 25: the window's output lights never changed while a file ran (they showed the
// interpreter's state, which runs ahead). The status carries the outputs and TR's speed as the
// card plays them.
TEST(Controller, TheStatusShowsTheOutputsAndSpindleSpeedTheCardPlays) {
  Settings settings = default_settings();
  settings.spindle.pwm_bit = 30;  // TR's speed goes to the card (without: only recorded)
  Machine m(settings);
  m.c.schedule(Request::Pause, 1.0);
  ASSERT_TRUE(m.run("MS, 2\nTR, 12000\nSO, 1, 1\nSO, 3, 1\nMX, 4\nSO, 3, 0\nTR, 18000\nMX, 0\n"));
  m.c.wait();
  ControllerStatus s = m.c.status();
  ASSERT_EQ(s.state, MachineState::Paused);
  EXPECT_LT(s.machine[0], 4.0);  // held part-way along the first move
  EXPECT_EQ(s.outputs, 0b101u);  // switches 1 (the spindle) and 3, as played
  EXPECT_DOUBLE_EQ(s.spindle_rpm, 12000);
  ASSERT_TRUE(m.c.resume());
  m.c.wait();
  s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Idle);
  EXPECT_EQ(s.outputs, 0u);  // a file's end switches its outputs and the speed output off
  EXPECT_DOUBLE_EQ(s.spindle_rpm, 0);
  // An E-stop switches every output off, as the card's idle word does.
  m.c.schedule(Request::EStop, 0.5);
  ASSERT_TRUE(m.run("MX, 2\n"));
  m.c.wait();
  EXPECT_EQ(m.c.status().state, MachineState::EStop);
  EXPECT_EQ(m.c.status().outputs, 0u);
}

TEST(Controller, AContinuousJogRampsDownOnReleaseAtTheKeypadRampRate) {
  Machine m;
  const double hold_s = 1.0;
  m.c.schedule(Request::JogRelease, hold_s);
  JogRequest j;
  j.direction[0] = 1;
  ASSERT_TRUE(m.c.jog(j));
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Idle);
  // Move speed v (slow keypad), ramp from the ramp speed u at the keypad rate: by 1 s the
  // tool cruises; it stops v^2 / 2a after the release.
  const double v = m.settings.speeds.move.xy, u = m.settings.ramps.move_ramp_speed.xy;
  const double a = 2 * (u + 1) / m.settings.ramps.keypad_ramp_rate;
  const double expected = v * hold_s - (v - u) * (v - u) / (2 * a) + v * v / (2 * a);
  EXPECT_NEAR(s.machine[0], expected, 2.0 / m.settings.axes[0].steps_per_unit);
  EXPECT_EQ(s.steps[1], 0);
}

// Issue 25: after an E-stop and ack, a released jog read "idle" while it slowed to rest, and
// the console's key thread waited in wait() there, deaf to every key (even !). The status says
// whether anything is under way (settled) and counts the activities ended, so a front end
// polls and never waits; an E-stop while the jog slows acts at once.
TEST(Controller, AReleasedJogSlowingToRestIsNotSettledAndAnEStopThenActsAtOnce) {
  using namespace std::chrono_literals;
  Settings settings = default_settings();
  settings.ramps.keypad_ramp_rate = 20;  // a long ramp down: seconds
  SimCard card{settings, true};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  session::ActivityWatch watch;
  ASSERT_TRUE(c.run(Script::from_text("MS, 2\nMX, 1\n", "part.sbp")));
  std::this_thread::sleep_for(100ms);
  ASSERT_TRUE(c.estop());
  ASSERT_TRUE(c.wait_for(5s));
  ControllerStatus s = c.status();
  EXPECT_EQ(s.state, MachineState::EStop);
  EXPECT_TRUE(s.settled);
  EXPECT_EQ(s.activities_ended, 1u);
  EXPECT_TRUE(watch.ended(s));
  EXPECT_FALSE(watch.ended(c.status()));  // once per end
  ASSERT_TRUE(c.acknowledge());
  JogRequest j;
  j.direction[0] = 1;
  ASSERT_TRUE(c.jog(j));
  EXPECT_FALSE(c.status().settled);
  std::this_thread::sleep_for(400ms);
  ASSERT_TRUE(c.jog_release());
  s = c.status();
  EXPECT_EQ(s.state, MachineState::Idle);  // released: idle at once ...
  EXPECT_FALSE(s.settled);                 // ... but still slowing to rest
  EXPECT_FALSE(watch.ended(s));
  EXPECT_FALSE(c.wait_for(100ms));
  const double x = c.status().machine[0];
  std::this_thread::sleep_for(100ms);
  EXPECT_GT(c.status().machine[0], x);  // still moving
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(c.estop());
  ASSERT_TRUE(c.wait_for(2s));  // the pulses stop at once, not at the end of the ramp
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 1s);
  s = c.status();
  EXPECT_EQ(s.state, MachineState::EStop);
  EXPECT_TRUE(s.settled);
  EXPECT_EQ(s.activities_ended, 2u);
  EXPECT_TRUE(watch.ended(s));
  const double stopped = s.machine[0];
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(c.status().machine[0], stopped);
}

TEST(Controller, AContinuousJogStopsAtTheSoftLimit) {
  Machine m;
  JogRequest j;
  j.direction[0] = 1;
  j.direction[1] = 1;  // diagonal: Y (18 in) limits first
  j.fast = true;
  ASSERT_TRUE(m.c.jog(j));
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.steps[1], m.steps(m.settings.axes[1].max, 1));
  EXPECT_EQ(s.steps[0], m.steps(m.settings.axes[1].max, 0));
  EXPECT_FALSE(m.c.jog(j));  // at the limit that way
}

TEST(Controller, AThousandFixedStepsNeverDrift) {
  Machine m;
  JogRequest j;
  j.step = true;
  j.fast = true;
  const double d = m.settings.display.keypad_step;
  for (int cycle = 0; cycle < 10; ++cycle) {  // 50 presses out, 50 back: 1,000 in all
    for (int dir : {1, -1}) {
      j.direction[0] = dir;
      for (int k = 0; k < 50; ++k) {
        ASSERT_TRUE(m.c.jog(j)) << cycle << " " << k;
        m.c.wait();
      }
      EXPECT_EQ(m.c.status().steps[0], dir > 0 ? m.steps(50 * d) : 0) << cycle;
    }
  }
  EXPECT_EQ(m.card.steps()[0], 0);
}

TEST(Controller, RequestsOutOfTurnAreRefusedWithAReason) {
  Machine m;
  EXPECT_NE(m.c.resume().reason.find("nothing is paused"), std::string::npos);
  EXPECT_NE(m.c.pause().reason.find("nothing is running"), std::string::npos);
  EXPECT_NE(m.c.acknowledge().reason.find("no E-stop"), std::string::npos);
  EXPECT_FALSE(m.c.jog_release());
}

}  // namespace
}  // namespace gantry

namespace gantry {
namespace {

TEST(Controller, TypedLinesKeepTheirValuesAndOutputsAFileDoesNot) {
  Machine m;
  ASSERT_TRUE(m.c.run_typed(Script::from_text("SO, 1, 1\nVS, 3\n", "console")));
  m.c.wait();
  EXPECT_EQ(m.c.modal().outputs, 1u);
  EXPECT_DOUBLE_EQ(m.c.modal().speeds.move.xy, 3);
  ASSERT_TRUE(m.run("SO, 2, 1\nVS, 1\n"));
  m.c.wait();
  EXPECT_EQ(m.c.modal().outputs, 0u);               // a file's end turns them off
  EXPECT_DOUBLE_EQ(m.c.modal().speeds.move.xy, 3);  // and undoes its VS
}

TEST(Controller, ProgressGivesTheLineTheMachineTimeAndWhatRemains) {
  Machine m;
  ASSERT_TRUE(m.run(kSquare));
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.lines, 6u);
  EXPECT_EQ(s.line, 6u);
  EXPECT_EQ(s.playing_line, 6);  // the last motion played was line 6's jog
  EXPECT_NEAR(s.elapsed_s, m.card.time_s(), 1e-9);
  EXPECT_LT(s.remaining_s, 0.01 * s.elapsed_s);  // the estimate was the cycle time
}

// Issue 25: a typed line that runs a file (the window's "Start at line" types FG) showed
// "line 25 of 1", the one typed line's progress; the file's lines are what count.
TEST(Controller, ATypedLineThatRunsAFileShowsTheFilesProgress) {
  Machine m;
  // In the working folder: a typed line's files are read only from there.
  const std::string file = "gantry_typed_fg_progress.sbp";
  std::ofstream(file) << kSquare;
  const Outcome o =
      m.c.run_typed(Script::from_text("FG, \"" + file + "\", , , , , , , , , 3", "console"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : o.errors[0].message);
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.lines, 6u);
  EXPECT_EQ(s.line, 6u);
  EXPECT_EQ(s.playing_line, 6);
  std::remove(file.c_str());
}

// Issue 25: the motion of a called file carries the run's line that called it; the reader,
// which the progress followed, is past it by the time the card plays that motion.
TEST(Controller, TheMotionOfACalledFileCarriesTheLineThatCalledIt) {
  Machine m;
  const std::string sub = "gantry_called_line_sub.sbp";
  std::ofstream(sub) << "M2, 1, 1\nM2, 2, 1\n";
  ASSERT_TRUE(m.run("MS, 2, 1\nM2, 0.5, 0\nFP, \"" + sub + "\"\n&past = 1\n"));
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.line, 4u);
  ASSERT_TRUE(s.playing_file);
  EXPECT_EQ(*s.playing_file, sub);
  EXPECT_EQ(s.playing_line, 2);
  EXPECT_EQ(s.playing_caller_line, 3);
  std::remove(sub.c_str());
}

}  // namespace
}  // namespace gantry

namespace gantry {
namespace {

// An operator at a console: SK hands them the keypad.
struct KeypadIO : ScriptedIO {
  KeypadIO() : ScriptedIO(true, {}) {}
  KeypadAnswer keypad(std::string_view message, const SourceLoc&) override {
    messages.emplace_back(message);
    return KeypadAnswer::Jog;
  }
  std::vector<std::string> messages;
};

struct KeypadMachine {
  Settings settings = default_settings();
  SimCard card{settings};
  KeypadIO io;
  PersistentStore store;
  Controller c{settings, card, io, store};
  std::int64_t steps(double units, int axis = 0) const {
    return std::llround(units * settings.axes[axis].steps_per_unit);
  }
};

const char* kZeroAtTheKeypad =
    "MX, 1\n"
    "SK, \"Jog to the corner, then close the keypad\"\n"
    "ZY\n"
    "MY, 0.5\n"
    "MX, 2\n";

TEST(Controller, SkWaitsWhileTheOperatorJogsThenTheFileGoesOnFromThere) {
  KeypadMachine m;
  const Outcome o = m.c.run(Script::from_text(kZeroAtTheKeypad, "part.sbp"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : ": " + o.errors[0].message);
  m.c.wait();
  ASSERT_EQ(m.c.state(), MachineState::Keypad);
  EXPECT_EQ(m.c.status().steps[0], m.steps(1));  // the moves before SK have played
  ASSERT_EQ(m.io.messages.size(), 1u);
  EXPECT_EQ(m.io.messages[0], "Jog to the corner, then close the keypad");
  EXPECT_FALSE(m.c.run(Script::from_text("MX, 3\n", "other.sbp")));
  JogRequest j;
  j.step = true;
  j.direction[1] = 1;
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(m.c.jog(j)) << k;
    m.c.wait();
    EXPECT_EQ(m.c.state(), MachineState::Keypad) << k;
  }
  const double d = m.settings.display.keypad_step;
  EXPECT_EQ(m.c.status().steps[1], m.steps(3 * d, 1));
  ASSERT_TRUE(m.c.resume());  // closes the keypad
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Idle);
  EXPECT_EQ(s.steps[0], m.steps(2));
  EXPECT_EQ(s.steps[1], m.steps(3 * d + 0.5, 1));  // ZY zeroed Y where the jogs left it
  EXPECT_EQ(m.card.steps()[1], m.steps(3 * d + 0.5, 1));
}

TEST(Controller, AStopAtSkEndsTheFileWhereTheToolIs) {
  KeypadMachine m;
  const Outcome o = m.c.run(Script::from_text(kZeroAtTheKeypad, "part.sbp"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : ": " + o.errors[0].message);
  m.c.wait();
  ASSERT_EQ(m.c.state(), MachineState::Keypad);
  JogRequest j;
  j.step = true;
  j.direction[0] = -1;
  ASSERT_TRUE(m.c.jog(j));
  m.c.wait();
  EXPECT_FALSE(m.c.pause());  // refused, with a reason
  ASSERT_TRUE(m.c.stop());
  m.c.wait();
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Stopped);
  EXPECT_EQ(s.steps[0], m.steps(1 - m.settings.display.keypad_step));
  EXPECT_EQ(s.steps[1], 0);  // MY never ran
  // After a stop the location is the pulses played (not the jog's commanded end).
  EXPECT_DOUBLE_EQ(m.c.modal().position[0],
                   static_cast<double>(s.steps[0]) / m.settings.axes[0].steps_per_unit);
}

TEST(Controller, SkWithoutAKeypadGoesOnOnlyWhenTheOperatorSaysSo) {
  Machine m;  // --yes: SK goes on without jogging
  const Outcome o = m.run(kZeroAtTheKeypad);
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : ": " + o.errors[0].message);
  m.c.wait();
  EXPECT_EQ(m.c.state(), MachineState::Idle);
  EXPECT_EQ(m.c.status().steps[1], m.steps(0.5, 1));
  // Nobody at the machine: the check refuses the file at SK, before anything moves.
  Settings settings = default_settings();
  PersistentStore store;
  JobOptions opt;
  opt.operator_present = false;
  const std::vector<Diagnostic> errors =
      check_program(Script::from_text(kZeroAtTheKeypad, "part.sbp"), settings, store, opt).kept();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].loc.line, 2);
  EXPECT_NE(errors[0].message.find("SK hands the keypad to the operator (\"Jog to"),
            std::string::npos)
      << errors[0].message;
}

}  // namespace
}  // namespace gantry

namespace gantry {
namespace {

TEST(Controller, SingleStepHoldsAfterEachStatementWithItsMotionPlayed) {
  Machine m;
  m.c.set_single_step(true);
  ASSERT_TRUE(m.run("MX, 1\n&a = 2\nMY, &a\nMX, 3\n"));
  const std::vector<std::array<double, 2>> after = {{1, 0}, {1, 0}, {1, 2}};
  for (const auto& [x, y] : after) {
    m.c.wait();
    const ControllerStatus s = m.c.status();
    ASSERT_EQ(s.state, MachineState::Paused);
    EXPECT_EQ(s.steps[0], m.steps(x));
    EXPECT_EQ(s.steps[1], m.steps(y, 1));
    ASSERT_TRUE(m.c.resume());
  }
  m.c.wait();  // the last statement holds too; a stop there ends the file
  EXPECT_EQ(m.c.state(), MachineState::Paused);
  ASSERT_TRUE(m.c.stop());
  m.c.wait();
  EXPECT_EQ(m.c.status().steps[0], m.steps(3));
  m.c.set_single_step(false);
  ASSERT_TRUE(m.run("MX, 0\n"));
  m.c.wait();
  EXPECT_EQ(m.c.state(), MachineState::Idle);
  EXPECT_EQ(m.c.status().steps[0], 0);
}

TEST(Controller, AFeedOverrideReachesTheMovesOfTheFileRunning) {
  // Halved from the file's first statement on (while it runs) plans as halved before it.
  enum When { kNever, kBefore, kWhileRunning };
  auto time_of = [](When when) {
    Machine m;
    if (when == kBefore) m.c.set_feed_override(0.5);
    if (when == kWhileRunning)
      m.c.on_progress([&](std::size_t done, std::size_t) {
        if (done == 1) m.c.set_feed_override(0.5);
      });
    EXPECT_TRUE(m.run("MS, 1\nMX, 10\nMX, 0\n"));
    m.c.wait();
    EXPECT_EQ(m.c.status().steps[0], 0);
    return m.c.summary().planned_time_s;
  };
  const double full = time_of(kNever), live = time_of(kWhileRunning);
  EXPECT_GT(live, 1.8 * full);  // 20 in at 0.5 in/s instead of 1 in/s, ramps aside
  EXPECT_NEAR(live, time_of(kBefore), 1e-9);
}

// MI beside the path: Z oscillates out 0.1 in and back at 2.5 Hz while X and Y cut a square.
const char* kOscillating =
    "MS, 2, 1\n"
    "MZ, 1\n"
    "MI, Z, 1, , 2.5, 0.1\n"
    "M2, 4, 0\n"
    "M2, 4, 3\n"
    "M2, 0, 3\n"
    "MI, Z\n"
    "MX, 0\n";

TEST(Controller, AnOscillatingAxisRestsWithEveryPauseBackWhereItStarted) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> when(1.5, 6.5);  // after MZ, before the end
  for (int trial = 0; trial < 6; ++trial) {
    Machine m;
    const double t = when(rng);
    m.c.schedule(Request::Pause, t);
    ASSERT_TRUE(m.run(kOscillating));
    m.c.wait();
    ControllerStatus s = m.c.status();
    ASSERT_EQ(s.state, MachineState::Paused) << "pause at " << t;
    // Held: the path at rest, and Z finished its cycle, back at the start exactly.
    EXPECT_EQ(s.steps[2], m.steps(1.0, 2)) << "pause at " << t;
    EXPECT_EQ(m.card.steps()[2], m.steps(1.0, 2)) << "pause at " << t;
    ASSERT_TRUE(m.c.resume());
    m.c.wait();
    s = m.c.status();
    EXPECT_EQ(s.state, MachineState::Idle) << "pause at " << t;
    EXPECT_EQ(s.steps[0], 0) << "pause at " << t;
    EXPECT_EQ(s.steps[1], m.steps(3.0, 1)) << "pause at " << t;
    EXPECT_EQ(s.steps[2], m.steps(1.0, 2)) << "pause at " << t;
    EXPECT_LE(m.card.kinematics().max_accel_ratio(), 1.0) << "pause at " << t;
    EXPECT_LE(m.card.kinematics().max_velocity_ratio(), 1.0) << "pause at " << t;
    EXPECT_EQ(m.card.timing_violations(), 0u);
  }
}

TEST(Controller, ATurningAxisEndsWhereItsPulsesLeftItAndTheFileAfterKnowsIt) {
  Machine m;
  ASSERT_TRUE(m.run("MI, B, 1, 45\nMX, 2\nMI, B\n"));
  m.c.wait();
  ControllerStatus s = m.c.status();
  ASSERT_EQ(s.state, MachineState::Idle);
  EXPECT_GT(s.steps[4], m.steps(45, 4));  // over a second at 45 deg/s
  const double b = static_cast<double>(s.steps[4]) / m.settings.axes[4].steps_per_unit;
  EXPECT_DOUBLE_EQ(m.c.modal().position[4], b);
  ASSERT_TRUE(m.run("MB, 0\n"));  // back from there, to the step
  m.c.wait();
  EXPECT_EQ(m.c.status().steps[4], 0);
  EXPECT_EQ(m.card.steps()[4], 0);
}

TEST(Controller, StopAndEStopEndATurningAxisWithThePositionOfThePulsesPlayed) {
  for (const Request r : {Request::Stop, Request::EStop}) {
    Machine m;
    m.c.schedule(r, 1.0);
    ASSERT_TRUE(m.run("MI, B, 1, 45\nMX, 4\nMI, B\n"));
    m.c.wait();
    if (r == Request::EStop) {
      ASSERT_TRUE(m.c.acknowledge());
    }
    const ControllerStatus s = m.c.status();
    EXPECT_EQ(s.steps, m.card.steps()) << request_name(r);
    EXPECT_GT(s.steps[4], m.steps(30, 4)) << request_name(r);
    const double b = static_cast<double>(s.steps[4]) / m.settings.axes[4].steps_per_unit;
    EXPECT_DOUBLE_EQ(m.c.modal().position[4], b) << request_name(r);
    EXPECT_FALSE(m.c.modal().independent) << request_name(r);
    ASSERT_TRUE(m.run("MB, 0\n"));  // nothing turns on its own any more
    m.c.wait();
    EXPECT_EQ(m.card.steps()[4], 0) << request_name(r);
  }
}

// A pin trace: every change of the output word, with its tick.
std::vector<std::pair<std::uint64_t, std::uint32_t>> read_trace(const std::string& path) {
  std::ifstream in(path);
  std::string comment, word;
  std::getline(in, comment);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> out;
  std::uint64_t tick = 0;
  while (in >> tick >> word)
    out.emplace_back(tick, static_cast<std::uint32_t>(std::stoul(word, nullptr, 16)));
  return out;
}

TEST(Controller, SwitchFourComesOnWithTheWarningAndGoesOffWhenTheMotionEnds) {
  const std::string trace = testing::TempDir() + "gantry_warning.trace";
  const Settings settings = default_settings();  // SW 2 s, SO 4,-1
  InterpreterOptions options;
  options.warn_before_motion = true;  // as on a real card
  ScriptedIO io{true, {}};
  PersistentStore store;
  std::uint64_t end_tick = 0;
  {
    SimCard card{settings, false, {}, trace};
    Controller c{settings, card, io, store, options};
    ASSERT_TRUE(c.run(Script::from_text("MX, 1\n", "part.sbp")));
    c.wait();
    EXPECT_EQ(c.status().steps[0], std::llround(settings.axes[0].steps_per_unit));
    EXPECT_FALSE(c.status().warning);
    end_tick = card.ticks_played();
  }
  const std::uint32_t out4 = 1u << settings.outputs.aux_bits[3];
  const std::uint32_t step_x = 1u << settings.pins[0].step_bit;
  constexpr std::uint64_t kNone = UINT64_MAX;
  std::uint64_t on = kNone, first_step = kNone, last_step = 0, off = kNone;
  for (const auto& [tick, word] : read_trace(trace)) {
    if ((word & out4) && on == kNone) on = tick;
    if ((word & step_x) && first_step == kNone) first_step = tick;
    if (word & step_x) last_step = tick;
    if (on != kNone && !(word & out4) && off == kNone) off = tick;
  }
  // The machine waits the 2 s with switch 4 on, then moves; the switch goes off after the
  // last step, as the run ends.
  const auto wait = static_cast<std::uint64_t>(std::llround(2 * settings.card.pacer_hz()));
  ASSERT_NE(on, kNone);
  EXPECT_GE(first_step, on + wait);
  EXPECT_LE(first_step, on + wait + wait / 400);  // the first step of the ramp: within 5 ms
  EXPECT_GT(off, last_step);
  EXPECT_LE(off, end_tick);
  std::remove(trace.c_str());
}

TEST(Controller, AStopLeavesTheCardsOutputsAsTheFileEndLeavesThem) {
  // Output 1 (mode 0) goes off as the stopped file ends, output 2 (mode 1) stays on: on the
  // card as in the interpreter, although the stop dropped the rest of the motion stream.
  Settings settings = default_settings();
  settings.switches.output_modes[1] = 1;
  ScriptedIO io{true, {}};
  PersistentStore store;
  SimCard card{settings};
  Controller c{settings, card, io, store};
  c.schedule(Request::Stop, 1.0);
  ASSERT_TRUE(c.run(Script::from_text("SO, 1, 1\nSO, 2, 1\nMX, 10\n", "part.sbp")));
  c.wait();
  ASSERT_EQ(c.state(), MachineState::Stopped);
  EXPECT_EQ(card.last_word() >> settings.outputs.aux_bits[0] & 1u, 0u);
  EXPECT_EQ(card.last_word() >> settings.outputs.aux_bits[1] & 1u, 1u);
  EXPECT_EQ(c.modal().outputs, 2u);
}

TEST(Controller, APauseSwitchesOffTheOutputsOfVnModesTwoAndFiveUntilResume) {
  // Output 1 in mode 2 (the file turns it on), output 2 in mode 5 (on as the file starts),
  // output 3 in mode 0 (stays on through the pause). The trace gives every change of the word.
  const std::string trace = testing::TempDir() + "gantry_pause_outputs.trace";
  Settings settings = default_settings();
  settings.switches.output_modes[0] = 2;
  settings.switches.output_modes[1] = 5;
  ScriptedIO io{true, {}};
  PersistentStore store;
  const int bit1 = settings.outputs.aux_bits[0], bit2 = settings.outputs.aux_bits[1],
            bit3 = settings.outputs.aux_bits[2];
  {
    SimCard card{settings, false, {}, trace};
    Controller c{settings, card, io, store};
    c.schedule(Request::Pause, 1.5);
    ASSERT_TRUE(c.run(Script::from_text("SO, 1, 1\nSO, 3, 1\nMX, 4\n", "part.sbp")));
    c.wait();
    ASSERT_EQ(c.state(), MachineState::Paused);
    const std::uint32_t held = card.last_word();
    EXPECT_EQ(held >> bit1 & 1u, 0u);
    EXPECT_EQ(held >> bit2 & 1u, 0u);
    EXPECT_EQ(held >> bit3 & 1u, 1u);
    ASSERT_TRUE(c.resume());
    c.wait();
    EXPECT_EQ(c.status().steps[0], std::llround(4 * settings.axes[0].steps_per_unit));
    EXPECT_EQ(card.last_word() & ((1u << bit1) | (1u << bit2) | (1u << bit3)), 0u);  // the end
  }
  {  // the card is gone: its trace is complete
    // Output 1's level, change by change: on, off for the pause, on at resume, off at the end.
    std::ifstream in(trace);
    std::string levels, comment;
    std::getline(in, comment);
    std::uint64_t tick = 0, off_at = 0, on_again = 0;
    std::string word;
    while (in >> tick >> word) {
      const bool on = (std::stoul(word, nullptr, 16) >> bit1 & 1u) != 0;
      if (levels.empty() || levels.back() != (on ? '1' : '0')) {
        levels += on ? '1' : '0';
        if (levels.size() == 3) off_at = tick;
        if (levels.size() == 4) on_again = tick;
      }
    }
    EXPECT_EQ(levels, "01010");
    EXPECT_GT(off_at, 1.5 * settings.card.pacer_hz());  // once at rest, after the pause
    EXPECT_GT(on_again, off_at);
  }
  std::remove(trace.c_str());
}

TEST(Controller, FgWithoutAStartLineResumesOnceWhereTheLastRunStopped) {
  const std::string path = testing::TempDir() + "gantry_fg_resume.sbp";
  std::ofstream(path) << "MS, 2\nMX, 4\nMY, 3\nMX, 0\n";
  Settings settings = default_settings();
  SimCard card{settings};
  std::string printed;
  ScriptedIO io{true, {}, &printed};
  PersistentStore store;
  InterpreterOptions options;
  options.allowed_folders = {testing::TempDir()};  // typed lines reach the working directory
  Controller c{settings, card, io, store, options};
  c.schedule(Request::Stop, 3.0);  // in MY, 3 (line 3)
  ASSERT_TRUE(c.run_typed(Script::from_text("FP, " + path + "\n", "console")));
  c.wait();
  ASSERT_EQ(c.state(), MachineState::Stopped);
  EXPECT_EQ(c.status().stopped_at.line, 3);
  ASSERT_TRUE(c.run_typed(Script::from_text("FG, " + path + "\n", "console")));
  c.wait();
  EXPECT_NE(printed.find("FG: from line 3, where the last run of"), std::string::npos) << printed;
  EXPECT_EQ(c.state(), MachineState::Idle);
  EXPECT_EQ(c.status().steps[0], 0);
  EXPECT_EQ(c.status().steps[1], std::llround(3 * settings.axes[1].steps_per_unit));
  printed.clear();
  ASSERT_TRUE(c.run_typed(Script::from_text("FG, " + path + "\n", "console")));  // from line 1
  c.wait();
  EXPECT_EQ(printed.find("FG: from line"), std::string::npos) << printed;
  std::remove(path.c_str());
}

}  // namespace
}  // namespace gantry
