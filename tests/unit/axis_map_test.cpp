// Axis mapping on the simulated card: an axis on another driver channel (the channel that
// steps and its direction level on the pin trace), a slaved axis on two channels, a rotary
// axis's wrapped position, and squaring a slaved gantry at homing with its two switches
// placed unequally.
#include <gtest/gtest.h>
#include <unistd.h>

#include "pin_trace.hpp"
#include "segment_builders.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/step/step_generator.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::channel_pulses;
using test::direction_runs;
using test::read_trace;
using test::segment;
using test::vec;
namespace fs = std::filesystem;

std::string trace_path(const char* name) {
  return (fs::temp_directory_path() /
          (std::string("gantry_axismap_") + name + "_" + std::to_string(getpid()) + ".trace"))
      .string();
}

Settings quiet() {
  Settings s = default_settings();
  s.outputs.charge_pump_bit = -1;
  return s;
}

// Channel 1 drives Z and channel 3 drives X, whose direction line is inverted (high for
// plus): X's steps come out on channel 3's step bit (2) and its direction bit (10) is high
// going plus, low going minus; Z's on channel 1's (0, 8). The simulated card decodes each
// channel in its axis's units and limits: X at 6 in/s on channel 3 is within X's 8 in/s
// (read as Z, 4 in/s, it would not be).
TEST(AxisMap, AnAxisStepsOnTheChannelItIsMappedToWithThatChannelsDirectionInvert) {
  Settings s = quiet();
  s.drivers.channel_axis = {2, 1, 0, 3, 4, 5};  // "ZYXABC"
  s.pins[2].invert_dir = true;
  ASSERT_TRUE(settings_problems(s).empty()) << settings_problems(s)[0];
  const std::string path = trace_path("channel");
  double velocity_ratio = 0;
  std::uint64_t violations = 0;
  Steps6 card_steps{};
  {
    SimCard card(s, false, {}, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    gen.segment(segment(vec(0), vec(1.0), 0, 6, 0, 40));
    gen.segment(segment(vec(1.0), vec(0.5), 0, 6, 0, 40));
    gen.segment(segment(vec(0.5), vec(0.5, 0, 0.2), 0, 2, 0, 14));
    gen.flush();
    velocity_ratio = card.kinematics().velocity_ratio(2);
    violations = card.timing_violations();
    card_steps = card.steps();
  }
  const auto trace = read_trace(path);
  fs::remove(path);
  const std::int64_t x1 = std::llround(1.0 * s.axes[0].steps_per_unit),
                     x2 = std::llround(0.5 * s.axes[0].steps_per_unit),
                     z = std::llround(0.2 * s.axes[2].steps_per_unit);
  // Channel 3 (step bit 2, direction bit 10, inverted): X out and back.
  const auto x = channel_pulses(trace, 2, 10, true);
  const auto runs = direction_runs(x);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0], std::make_pair(true, static_cast<int>(x1)));
  EXPECT_EQ(runs[1], std::make_pair(false, static_cast<int>(x1 - x2)));
  // The raw direction level: high while X goes plus (the first pulse), low going minus.
  for (const auto& [tick, w] : trace)
    if (tick == x.front().tick) {
      EXPECT_NE(w & (1u << 10), 0u);
    }
  for (const auto& [tick, w] : trace)
    if (tick == x.back().tick) {
      EXPECT_EQ(w & (1u << 10), 0u);
    }
  // Channel 1 (step bit 0, direction bit 8): Z only.
  const auto zc = channel_pulses(trace, 0, 8);
  EXPECT_EQ(static_cast<std::int64_t>(zc.size()), z);
  for (const auto& p : zc) EXPECT_TRUE(p.positive);
  EXPECT_EQ(card_steps[2], x2);  // channel 3's motor
  EXPECT_EQ(card_steps[0], z);   // channel 1's motor
  EXPECT_EQ(violations, 0u);
  EXPECT_GT(velocity_ratio, 0.7);  // X's 6 of 8 in/s, reconstructed from the steps
  EXPECT_LE(velocity_ratio, 1.0);
}

// Y on channels 2 and 5 (drivers.channels "XYZAYC"), channel 5's direction inverted: both
// motors step together, each direction line at its own level.
TEST(AxisMap, ASlavedAxisStepsBothItsChannelsEachWithItsOwnDirectionInvert) {
  Settings s = quiet();
  s.drivers.channel_axis = {0, 1, 2, 3, 1, 5};
  s.pins[4].invert_dir = true;
  ASSERT_TRUE(settings_problems(s).empty()) << settings_problems(s)[0];
  const std::string path = trace_path("slaved");
  Steps6 card_steps{};
  std::uint64_t violations = 0;
  {
    SimCard card(s, false, {}, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    gen.segment(segment(vec(0), vec(0, 0.3), 0, 2, 0, 14));
    gen.segment(segment(vec(0, 0.3), vec(0, 0.1), 0, 2, 0, 14));
    gen.flush();
    card_steps = card.steps();
    violations = card.timing_violations();
  }
  const auto trace = read_trace(path);
  fs::remove(path);
  const std::int64_t out = std::llround(0.3 * s.axes[1].steps_per_unit),
                     back = std::llround(0.1 * s.axes[1].steps_per_unit);
  const auto first = channel_pulses(trace, 1, 9), second = channel_pulses(trace, 4, 12, true);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t k = 0; k < first.size(); ++k) {
    EXPECT_EQ(first[k].tick, second[k].tick);
    EXPECT_EQ(first[k].positive, second[k].positive);
  }
  EXPECT_EQ(direction_runs(first),
            (std::vector<std::pair<bool, int>>{{true, static_cast<int>(out)},
                                               {false, static_cast<int>(out - back)}}));
  // The two direction lines are opposite levels (one inverted) whenever Y steps.
  for (const auto& [tick, w] : trace)
    if (tick == first.front().tick) {
      EXPECT_NE(((w >> 9) ^ (w >> 12)) & 1u, 0u);
    }
  EXPECT_EQ(card_steps[1], back);  // both motors
  EXPECT_EQ(card_steps[4], back);
  EXPECT_EQ(violations, 0u);
}

TEST(AxisMap, ChannelsMayNameAnAxisTwiceButNotThriceNorLeaveOneInUseOut) {
  Settings s = default_settings();
  s.drivers.channel_axis = {0, 1, 2, 3, 1, 5};
  EXPECT_TRUE(settings_problems(s).empty());
  s.drivers.channel_axis = {0, 1, 2, 1, 1, 5};
  ASSERT_EQ(settings_problems(s).size(), 1u);
  EXPECT_EQ(settings_problems(s)[0],
            "drivers.channels names Y 3 times: an axis has one driver channel, or two (a slaved "
            "axis)");
  s.drivers.channel_axis = {0, 0, 2, 3, 4, 5};  // Y, in use, has none
  ASSERT_EQ(settings_problems(s).size(), 1u);
  EXPECT_NE(settings_problems(s)[0].find("names no driver channel for Y"), std::string::npos);
  s.drivers.channel_axis = {0, 1, 2, 3, 4, 5};
  s.homing.square_input[1] = 5;  // squaring needs two channels
  ASSERT_EQ(settings_problems(s).size(), 1u);
  EXPECT_NE(settings_problems(s)[0].find("homing.y.square_input"), std::string::npos);
}

// A rotary axis with wrap = 360 is reported in [0, 360); moves keep the whole position.
TEST(AxisMap, ARotaryAxisWithAWrapIsReportedModuloIt) {
  AxisSettings a;
  a.wrap = 360;
  EXPECT_DOUBLE_EQ(reported_position(a, 370), 10);
  EXPECT_DOUBLE_EQ(reported_position(a, -90), 270);
  EXPECT_DOUBLE_EQ(reported_position(a, 720), 0);
  a.wrap = 0;
  EXPECT_DOUBLE_EQ(reported_position(a, 370), 370);
}

// Squaring: Y on channels 2 and 5, the first motor's switch on input 3 (bit 8) at -0.5, the
// second's on input 5 (bit 10) at -0.3125 (the gantry 0.1875 in out of square). G28 Y (C3's
// built-in homing): each motor stops on its own switch, the other resting, then both back off
// together; each motor ends back_off from its own switch.
struct SquaringMachine {
  explicit SquaringMachine(double square_offset = 0, SimWorld w = world())
      : settings(profile(square_offset)), card(settings, false, std::move(w)) {}
  static Settings profile(double square_offset) {
    Settings s = default_settings();
    s.gcode_dialect = GcodeDialect::WinCNC;
    s.drivers.channel_axis = {0, 1, 2, 3, 1, 5};
    s.inputs.home_bit[4] = 10;       // channel 5's motor's switch
    s.inputs.switch_bits[4] = 10;    // is input 5
    s.homing.square_input[1] = 5;
    s.homing.square_offset[1] = square_offset;
    s.homing.order = "y";
    return s;
  }
  static SimWorld world() {
    SimWorld w;
    w.home_switch[1] = -0.5;     // the first motor's (channel 2)
    w.home_switch[4] = -0.3125;  // the second motor's (channel 5)
    return w;
  }
  Settings settings;
  SimCard card;
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  std::int64_t first_step_below(double units) const {
    return static_cast<std::int64_t>(std::floor(units * settings.axes[1].steps_per_unit));
  }
};

TEST(SlavedAxis, HomingSquaresTheGantryEachMotorOnItsOwnSwitch) {
  SquaringMachine m;
  ASSERT_TRUE(settings_problems(m.settings).empty()) << settings_problems(m.settings)[0];
  const Outcome o = m.c.run(Script::from_text("G28 Y\n", "part.nc"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : " " + o.errors[0].message);
  m.c.wait();
  const ControllerStatus st = m.c.status();
  ASSERT_EQ(st.state, MachineState::Idle) << st.message;
  const double spu = m.settings.axes[1].steps_per_unit;
  const auto back = std::llround(m.settings.homing.back_off * spu);
  // Each motor stood on its own switch (the first step at or below it), then backed off.
  EXPECT_EQ(m.card.steps()[1], m.first_step_below(-0.5) + back);
  EXPECT_EQ(m.card.steps()[4], m.first_step_below(-0.3125) + back);
  // The table base is 0 at the switches: Y reads back_off, the switches are open again.
  const ModalState ms = m.c.modal();
  EXPECT_NEAR(ms.position[1] + ms.zero[1], m.settings.homing.back_off, 1e-12);
  EXPECT_FALSE(st.inputs[2]);
  EXPECT_FALSE(st.inputs[4]);
  EXPECT_EQ(m.card.timing_violations(), 0u);
}

// The second motor's switch first: the same square, whichever closes first.
TEST(SlavedAxis, HomingSquaresWhicheverSwitchIsReachedFirst) {
  SimWorld w = SquaringMachine::world();
  std::swap(w.home_switch[1], w.home_switch[4]);
  SquaringMachine m(0, w);
  const Outcome o = m.c.run(Script::from_text("G28 Y\n", "part.nc"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : " " + o.errors[0].message);
  m.c.wait();
  ASSERT_EQ(m.c.status().state, MachineState::Idle) << m.c.status().message;
  const auto back = std::llround(m.settings.homing.back_off * m.settings.axes[1].steps_per_unit);
  EXPECT_EQ(m.card.steps()[1], m.first_step_below(-0.3125) + back);
  EXPECT_EQ(m.card.steps()[4], m.first_step_below(-0.5) + back);
}

// square_offset (WinCNC's g28altmove): the second motor moves on its own past its switch.
TEST(SlavedAxis, TheSquareOffsetMovesTheSecondMotorAlone) {
  SquaringMachine m(0.01);
  const Outcome o = m.c.run(Script::from_text("G28 Y\n", "part.nc"));
  ASSERT_TRUE(o) << o.reason;
  m.c.wait();
  ASSERT_EQ(m.c.status().state, MachineState::Idle) << m.c.status().message;
  const double spu = m.settings.axes[1].steps_per_unit;
  const auto back = std::llround(m.settings.homing.back_off * spu);
  EXPECT_EQ(m.card.steps()[1], m.first_step_below(-0.5) + back);
  EXPECT_EQ(m.card.steps()[4], m.first_step_below(-0.3125) - std::llround(0.01 * spu) + back);
}

}  // namespace
}  // namespace gantry
