// The controller and the card's inputs on the simulated card in virtual time: probes latch
// at the step where the switch closed, ON INPUT handlers cut the motion and run, homing
// sets the table base at the switches, a limit switch stops the tool and is named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/motion/path_limits.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

struct Machine {
  explicit Machine(SimWorld world = {}) : card(settings, false, world) {}
  Machine(SimWorld world, Settings s) : settings(std::move(s)), card(settings, false, world) {}
  Settings settings = default_settings();
  SimCard card;
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};

  double spu(int axis) const { return settings.axes[axis].steps_per_unit; }
  // The first whole step at or beyond `units` going down (a switch active at or below it).
  std::int64_t first_step_below(double units, int axis) const {
    return static_cast<std::int64_t>(std::floor(units * spu(axis)));
  }
  std::int64_t first_step_above(double units, int axis) const {
    return static_cast<std::int64_t>(std::ceil(units * spu(axis)));
  }
  // As part.sbp in `folder` ("": the working directory), the folder its files are written in.
  void run_to_end(const std::string& text, const std::string& folder = "") {
    const Outcome o =
        c.run(Script::from_text(text, folder.empty() ? "part.sbp" : folder + "/part.sbp"));
    ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : " " + o.errors[0].message);
    c.wait();
  }
};

constexpr int kZ = 2;

// One keypad step (VD's keypad step) along `axis`, `direction` +1 or -1.
JogRequest step_jog(int axis, int direction) {
  JogRequest j;
  j.direction[axis] = direction;
  j.step = true;
  return j;
}

TEST(Probe, StopsExactlyWhereTheSwitchClosed) {
  SimWorld w;
  w.probe_z = -0.3;  // the Z zero plate's surface: input 1 closes at or below it
  Machine m(w);
  m.run_to_end("PZ, -1, 0.5, 1\n");
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Idle) << s.message;
  const std::int64_t touch = m.first_step_below(-0.3, kZ);
  EXPECT_EQ(s.steps[kZ], touch);  // it came back to the step where the plate closed
  EXPECT_DOUBLE_EQ(m.c.modal().position[kZ], static_cast<double>(touch) / m.spu(kZ));
  EXPECT_TRUE(s.inputs[0]);  // resting on the plate
}

TEST(Probe, TcDigitizesAShapedPartIntoAFileThatFollowsIt) {
  SimWorld w;
  // A ramp rising 0.1 per inch of X, from -0.5 at X 0; nothing beyond X 2.4.
  w.probe_surface = [](double x, double) { return x > 2.4 ? -5.0 : -0.5 + 0.1 * x; };
  Machine m(w);
  const std::string dir = ::testing::TempDir();
  const std::string csv = dir + "/gantry_tc_points.csv", sbp = dir + "/gantry_tc_copy.sbp";
  std::remove(csv.c_str());
  std::remove(sbp.c_str());
  m.run_to_end("TC, " + csv + ", 0, 0, 3, 1, 1, -1, 0.5, 1\n", dir);
  EXPECT_EQ(m.c.state(), MachineState::Idle) << m.c.status().message;
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "x,y,z");
  int n = 0;
  while (std::getline(in, line)) {
    double x = 0, y = 0, z = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &x, &y, &z), 3) << line;
    // The step where the probe closed: within one step of the surface; the last column
    // found nothing and is at the bottom.
    const double surface = x > 2.4 ? -1 : -0.5 + 0.1 * x;
    EXPECT_NEAR(z, surface, 1.0 / m.spu(kZ) + 1e-4) << line;
    ++n;
  }
  EXPECT_EQ(n, 8);                                  // 4 x 2 points
  EXPECT_DOUBLE_EQ(m.c.modal().position[kZ], 0.5);  // back at safe Z
  // The same grid as a part file: the M3 moves pass through the points.
  m.run_to_end("TC, " + sbp + ", 0, 0, 3, 1, 1, -1, 0.5, 1\n", dir);
  std::ifstream part(sbp);
  std::stringstream text;
  text << part.rdbuf();
  EXPECT_NE(text.str().find("M3, 1, 0, -0.4"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("M3, 3, 1, -1"), std::string::npos) << text.str();
}

TEST(Probe, GcodeG38ProbesOnTheSameInputAndLatches) {
  SimWorld w;
  w.probe_z = -0.3;
  {
    Machine m(w);
    m.run_to_end("G20\nG38.2 Z-1 F30\nG0 Z[#5063 + 0.5]\n");
    EXPECT_EQ(m.c.state(), MachineState::Idle) << m.c.status().message;
    // #5063, where the probe touched, is the step where the plate closed.
    const double touch = static_cast<double>(m.first_step_below(-0.3, kZ)) / m.spu(kZ);
    EXPECT_EQ(m.c.status().steps[kZ], std::llround((touch + 0.5) * m.spu(kZ)));
  }
  {
    Machine m(w);  // G38.2 short of the plate: an error on the live machine
    ASSERT_TRUE(m.c.run(Script::from_text("G20\nG38.2 Z-0.2 F30\nG0 X1\n", "part.sbp")));
    m.c.wait();
    EXPECT_EQ(m.c.state(), MachineState::Stopped);
    const Controller::Summary s = m.c.summary();
    ASSERT_TRUE(s.error);
    EXPECT_EQ(s.error->loc.line, 2);
    EXPECT_NE(s.error->message.find("without the switch closing"), std::string::npos)
        << s.error->message;
    EXPECT_EQ(m.c.status().steps[0], 0);  // G0 X1 never ran
  }
  {
    Machine m(w);  // G38.3 goes on
    m.run_to_end("G20\nG38.3 Z-0.2 F30\nG0 X1\n");
    EXPECT_EQ(m.c.state(), MachineState::Idle) << m.c.status().message;
    EXPECT_EQ(m.c.status().steps[0], std::llround(m.spu(0)));
  }
}

TEST(Probe, WithoutContactItEndsAtItsTarget) {
  SimWorld w;
  w.probe_z = -2;
  Machine m(w);
  m.run_to_end("PZ, -1, 0.5, 1\n");
  EXPECT_EQ(m.c.status().steps[kZ], std::llround(-1 * m.spu(kZ)));
  EXPECT_DOUBLE_EQ(m.c.modal().position[kZ], -1);
}

TEST(Probe, TheLatchIsReadByThePartFileAndAZeroFollows) {
  SimWorld w;
  w.probe_z = -0.3;
  Machine m(w);
  // FabMo's Z-zero pattern: probe, read %(3), zero there, pull up.
  m.run_to_end("PZ, -1, 0.5, 1\n&touch = %(3)\nZZ\nJZ, 0.5\nIF &touch > -0.31 THEN JX, 1\n");
  const ModalState st = m.c.modal();
  EXPECT_DOUBLE_EQ(st.position[kZ], 0.5);
  EXPECT_DOUBLE_EQ(st.position[0], 1);  // &touch was the plate's height, not the target
  EXPECT_NEAR(st.zero[kZ], static_cast<double>(m.first_step_below(-0.3, kZ)) / m.spu(kZ), 1e-12);
}

TEST(Probe, AnInputClosedAlreadyIsAnErrorAndNothingMoves) {
  SimWorld w;
  w.probe_z = 0.5;  // the plate is under the tool already
  Machine m(w);
  m.run_to_end("MX, 1\nPZ, -1, 0.5, 1\nMX, 2\n");
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Stopped);
  EXPECT_NE(s.message.find("input switch 1 is closed already"), std::string::npos) << s.message;
  EXPECT_EQ(s.stopped_at.line, 2);
  EXPECT_EQ(s.steps[0], std::llround(1 * m.spu(0)));
  EXPECT_EQ(s.steps[kZ], 0);
}

TEST(Probe, AnUnwiredInputIsRefusedByTheCheck) {
  Machine m;
  const Outcome o = m.c.run(Script::from_text("PZ, -1, 0.5, 2\n", "part.sbp"));
  EXPECT_FALSE(o);
  ASSERT_EQ(o.errors.size(), 1u);
  EXPECT_NE(o.errors[0].message.find("input switch 2 is not wired"), std::string::npos);
  EXPECT_EQ(m.c.status().steps[kZ], 0);
}

TEST(Probe, ParametersAreTargetsThenSpeedThenInput) {
  SimWorld w;
  w.probe_z = -5;  // never reached
  Machine m(w);
  m.run_to_end("P2, 1.5, 0.5, 1, 1\n");
  EXPECT_DOUBLE_EQ(m.c.modal().position[0], 1.5);
  EXPECT_DOUBLE_EQ(m.c.modal().position[1], 0.5);
}

// Input 3 (bit 8) closes at 0.5 s while MX, 10 runs at 2 in/s.
SimWorld switch3_closes_at(double t) {
  SimWorld w;
  w.input_events.push_back({t, 8, true});
  return w;
}

TEST(OnInput, AnInstantStopCutsTheMoveAndTheHandlerRuns) {
  Machine m(switch3_closes_at(0.5));
  m.run_to_end(
      "ON INPUT(3, 1) GOTO hit\n"
      "MX, 10\n"
      "MY, 1\n"
      "END\n"
      "hit:\n"
      "&x = %(1)\n"
      "MY, 2\n"
      "IF &x = %(1) THEN MZ, -0.125\n");
  const ControllerStatus s = m.c.status();
  const ModalState st = m.c.modal();
  EXPECT_EQ(s.state, MachineState::Idle) << s.message;
  EXPECT_GT(st.position[0], 0.1);
  EXPECT_LT(st.position[0], 2);
  EXPECT_DOUBLE_EQ(st.position[0], static_cast<double>(s.steps[0]) / m.spu(0));
  EXPECT_DOUBLE_EQ(st.position[1], 2);  // the handler's line ran; MY, 1 never did
  EXPECT_DOUBLE_EQ(st.position[kZ], -0.125);
  EXPECT_EQ(s.steps[1], std::llround(2 * m.spu(1)));
}

TEST(OnInput, ARampedStopComesToRestPastTheEdgeWithinTheRamp) {
  Machine instant(switch3_closes_at(0.5)), ramped(switch3_closes_at(0.5));
  const char* body = "MX, 10\nMY, 1\nEND\nhit:\nMY, 2\n";
  instant.run_to_end(std::string("ON INPUT(3, 1) GOTO hit\n") + body);
  ramped.run_to_end(std::string("ON INPUT(3, 3) GOTO hit\n") + body);
  const double at_edge = instant.c.modal().position[0];
  const double at_rest = ramped.c.modal().position[0];
  EXPECT_GT(at_rest, at_edge);  // it ramped down past the point of the edge
  // Braking from the move speed at the move ramp's acceleration, once the block in which
  // the card saw the edge has played (the simulated card reports edges block by block).
  const Settings& s = ramped.settings;
  const double v = s.speeds.move.xy;
  const double a =
      std::min(ramp_accel(s.ramps.move_ramp_speed.xy, s.ramps.move_ramp_rate), s.axes[0].max_accel);
  const double block_s = 4096 / s.card.pacer_hz();
  EXPECT_GT(at_rest - at_edge, v * v / (2 * a));
  EXPECT_LT(at_rest - at_edge, v * v / (2 * a) + v * block_s);
  EXPECT_DOUBLE_EQ(ramped.c.modal().position[1], 2);
}

TEST(OnInput, AHandlerFiresOnceAndAGosubReturnsAfterTheCutStatement) {
  SimWorld w = switch3_closes_at(0.3);
  w.input_events.push_back({2.0, 8, false});
  w.input_events.push_back({2.5, 8, true});  // closes again: no handler left
  Machine m(w);
  m.run_to_end(
      "&hits = 0\n"
      "ON INPUT(3, 1) GOSUB count\n"
      "MX, 10\n"
      "MY, 1\n"
      "MX, 0\n"
      "MY, 0.5\n"
      "END\n"
      "count:\n"
      "&hits = &hits + 1\n"
      "MZ, -&hits\n"
      "RETURN\n");
  const ModalState st = m.c.modal();
  EXPECT_DOUBLE_EQ(st.position[kZ], -1);  // one hit only
  EXPECT_DOUBLE_EQ(st.position[0], 0);    // the file went on after MX, 10 was cut
  EXPECT_DOUBLE_EQ(st.position[1], 0.5);
}

TEST(OnInput, AnEdgeIsNeededNotALevel) {
  Machine m(switch3_closes_at(0.1));  // closed before the handler is armed
  m.run_to_end("MX, 0.5\nON INPUT(3, 1) GOTO hit\nMX, 2\nEND\nhit:\nMY, 2\n");
  EXPECT_DOUBLE_EQ(m.c.modal().position[0], 2);
  EXPECT_DOUBLE_EQ(m.c.modal().position[1], 0);
}

TEST(Homing, TheTableBaseIsSetWhereEachSwitchCloses) {
  SimWorld w;
  // Proximity switches on input 3 (bit 8): X and Y at or below, Z at or above.
  w.home_switch[0] = -1.2345;
  w.home_switch[1] = -0.5;
  w.home_switch[kZ] = 0.75;
  w.home_above[kZ] = true;
  Machine m(w);
  m.run_to_end("C3\n");
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Idle) << s.message;
  const ModalState st = m.c.modal();
  // Table base 0 (homing.at) is exactly the step where each switch closed.
  EXPECT_NEAR(st.machine_origin[0], static_cast<double>(m.first_step_below(-1.2345, 0)) / m.spu(0),
              1e-12);
  EXPECT_NEAR(st.machine_origin[1], static_cast<double>(m.first_step_below(-0.5, 1)) / m.spu(1),
              1e-12);
  EXPECT_NEAR(st.machine_origin[kZ], static_cast<double>(m.first_step_above(0.75, kZ)) / m.spu(kZ),
              1e-12);
  // It ends backed off the switches, which are open again.
  EXPECT_FALSE(s.inputs[2]);
  const double back = m.settings.homing.back_off;
  EXPECT_NEAR(st.position[0] + st.zero[0], back, 1e-12);
  EXPECT_NEAR(st.position[1] + st.zero[1], back, 1e-12);
  EXPECT_NEAR(st.position[kZ] + st.zero[kZ], -back, 1e-12);
}

// C3 runs the shipped parts/macros/C3.sbp (found from any folder), which names the switch.
TEST(Homing, AMissingSwitchStopsWithAnError) {
  Machine m;  // no switches in this world
  m.run_to_end("C3\n");
  const ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Stopped);
  EXPECT_NE(s.message.find("C3: the Z proximity switch did not close within $home_search_z"),
            std::string::npos)
      << s.message;
}

TEST(LimitSwitch, StopsTheToolNamesTheSwitchAndOnlyAJogAwayIsAllowed) {
  SimWorld w;
  w.max_switch[0] = 5;
  Machine m(w);
  m.run_to_end("MX, 10\nMY, 1\n");
  ControllerStatus s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Stopped);
  EXPECT_NE(s.message.find("X high limit switch (input bit 3)"), std::string::npos) << s.message;
  EXPECT_EQ(s.steps[0], m.first_step_above(5, 0));  // the step that closed it, no further
  EXPECT_EQ(s.steps[1], 0);
  EXPECT_DOUBLE_EQ(m.c.modal().position[0], static_cast<double>(s.steps[0]) / m.spu(0));

  const Outcome again = m.c.run(Script::from_text("MY, 1\n", "part.sbp"));
  EXPECT_FALSE(again);
  EXPECT_NE(again.reason.find("X high limit switch is closed"), std::string::npos);
  EXPECT_FALSE(m.c.jog(step_jog(0, +1)));  // towards the switch
  ASSERT_TRUE(m.c.jog(step_jog(0, -1)));
  m.c.wait();
  s = m.c.status();
  EXPECT_EQ(s.state, MachineState::Idle);
  EXPECT_EQ(s.steps[0], m.first_step_above(5, 0) - std::llround(0.1 * m.spu(0)));
  m.run_to_end("MY, 1\n");  // off the switch: files run again
  EXPECT_DOUBLE_EQ(m.c.modal().position[1], 1);
}

// ---- VN: limit switches off, inputs in limit and stop modes (docs/controller.md)

TEST(LimitSwitch, AnInputInALimitModeStopsTheToolAndIsNamed) {
  Settings s = default_settings();
  s.inputs.switch_bits[4] = 10;  // input 5 on bit 10, a normally-open limit switch
  s.switches.input_modes[4] = 1;
  SimWorld w;
  w.input_events.push_back({1.0, 10, true});
  Machine m(w, s);
  m.run_to_end("MX, 10\nMY, 1\n");
  ControllerStatus st = m.c.status();
  EXPECT_EQ(st.state, MachineState::Stopped);
  EXPECT_NE(st.message.find("the limit switch on input 5"), std::string::npos) << st.message;
  // The card stopped at the word where it closed, 1 s in: the tool is where those steps left it.
  EXPECT_GT(st.steps[0], 0);
  EXPECT_LT(st.steps[0], std::llround(2 * m.spu(0)));
  EXPECT_DOUBLE_EQ(m.c.modal().position[0], static_cast<double>(st.steps[0]) / m.spu(0));
  const Outcome again = m.c.run(Script::from_text("MY, 1\n", "part.sbp"));
  EXPECT_FALSE(again);
  EXPECT_NE(again.reason.find("the limit switch on input 5 is active: jog off it"),
            std::string::npos)
      << again.reason;
  // It has no axis: the keypad may go either way (SB3's override).
  ASSERT_TRUE(m.c.jog(step_jog(0, -1)));
  m.c.wait();
  EXPECT_EQ(m.c.status().state, MachineState::Idle);
}

TEST(LimitSwitch, VnTurnsThemOffForTheAxisSwitchesAndTheInputsAlike) {
  Settings s = default_settings();
  s.inputs.switch_bits[4] = 10;
  s.switches.input_modes[4] = 1;
  SimWorld w;
  w.max_switch[0] = 5;                        // X's own high limit switch at 5
  w.input_events.push_back({1.0, 10, true});  // and input 5 closing
  Machine m(w, s);
  m.run_to_end("VN, 0\nMX, 10\n");
  const ControllerStatus st = m.c.status();
  EXPECT_EQ(st.state, MachineState::Idle) << st.message;
  EXPECT_EQ(st.steps[0], std::llround(10 * m.spu(0)));  // past both
  EXPECT_FALSE(m.c.modal().position[0] < 10);
}

TEST(StopSwitch, PausesTheFileStopsTheSpindleAndHoldsItWhileActive) {
  Settings s = default_settings();
  s.inputs.switch_bits[5] = 9;  // input 6 on bit 9, a normally-open stop switch
  s.switches.input_modes[5] = 3;
  SimWorld w;
  w.input_events.push_back({1.0, 9, true});  // pressed 1 s into the run
  Machine m(w, s);
  const int out1 = s.outputs.aux_bits[0];
  ASSERT_TRUE(m.c.run(Script::from_text("SO, 1, 1\nMX, 10\n", "part.sbp")));
  m.c.wait();
  ControllerStatus st = m.c.status();
  ASSERT_EQ(st.state, MachineState::Paused) << st.message;
  EXPECT_EQ(st.phase, FeedPhase::Held);
  EXPECT_NE(st.message.find("the stop switch on input 6 paused the file"), std::string::npos)
      << st.message;
  const std::int64_t held = st.steps[0];
  EXPECT_GT(held, std::llround(1.5 * m.spu(0)));  // 1 s at up to 2 in/s, then a ramp down
  EXPECT_LT(held, std::llround(4 * m.spu(0)));
  EXPECT_EQ(m.card.last_word() >> out1 & 1u, 0u);  // output 1 (the spindle) off at rest
  const Outcome early = m.c.resume();
  EXPECT_FALSE(early);
  EXPECT_NE(early.reason.find("the stop switch on input 6 is active: release it first"),
            std::string::npos)
      << early.reason;
  EXPECT_EQ(m.c.status().steps[0], held);  // nothing moved

  m.card.set_switch(9, false);  // released
  ASSERT_TRUE(m.c.resume());
  m.c.wait();
  st = m.c.status();
  EXPECT_EQ(st.state, MachineState::Idle) << st.message;
  EXPECT_EQ(st.steps[0], std::llround(10 * m.spu(0)));  // resumed exactly
  EXPECT_FALSE(m.c.summary().error);                    // the file ran to its end

  m.card.set_switch(9, true);  // pressed at rest: nothing starts
  const Outcome run = m.c.run(Script::from_text("MY, 1\n", "part.sbp"));
  EXPECT_FALSE(run);
  EXPECT_NE(run.reason.find("the stop switch on input 6 is active"), std::string::npos);
  EXPECT_FALSE(m.c.jog(step_jog(1, +1)));
}

TEST(StopSwitch, InputFourIsTheStopSwitchWhenItIsNotTheEStop) {
  Settings s = default_settings();
  s.inputs.switch_bits[3] = 11;  // a standard tool: input 4 a remote stop, wired NC
  SimWorld w;
  Machine m(w, s);
  // Normally closed and not wired in the simulation: it reads open, so it is active.
  const Outcome refused = m.c.run(Script::from_text("MX, 1\n", "part.sbp"));
  EXPECT_FALSE(refused);
  EXPECT_NE(refused.reason.find("the stop switch on input 4 is active"), std::string::npos)
      << refused.reason;
  m.card.set_switch(11, true);  // closed: released
  m.run_to_end("MX, 1\n");
  EXPECT_EQ(m.c.status().state, MachineState::Idle);
}

}  // namespace
}  // namespace gantry

namespace gantry {
namespace {

TEST(PauseUntil, TheLiveMachineWaitsForTheSwitchAsTimePasses) {
  SimWorld w;
  w.input_events.push_back({1.25, 8, true});  // input 3 closes at 1.25 s
  Machine m(w);
  m.run_to_end("MX, 0.5\nPAUSE UNTIL 3, 1\nMY, 0.5\n");
  EXPECT_DOUBLE_EQ(m.c.modal().position[1], 0.5);
  // The wait ended within one 10 ms dwell of the switch, then MY played.
  const double my = 0.5 / m.settings.speeds.move.xy;  // at least its cruise time
  EXPECT_GT(m.card.time_s(), 1.25 + my * 0.9);
  EXPECT_LT(m.card.time_s(), 1.25 + 0.01 + 2 * my + 0.5);
}

}  // namespace
}  // namespace gantry
