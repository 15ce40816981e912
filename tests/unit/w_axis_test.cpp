// The W axis (docs/hardware.md, "The W axis"): a second vertical head, the profile's A, B or C
// named W (display.w_axis). On the simulated card: G-code's W words move it on its channel,
// G28 W homes it upwards as a vertical head, its soft limits are named W, and the readout
// shows W; a profile without one refuses W where it stands.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/session/readout_lines.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/settings/values_file.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

// A router with a second head on A, named W: Z's drive, travel and speeds, its home switch on
// input 3 with X, Y and Z's.
Settings w_profile() {
  Settings s = default_settings();
  s.gcode_dialect = GcodeDialect::WinCNC;
  s.outputs.charge_pump_bit = -1;
  s.display.axes = 4;
  s.display.w_axis = 3;
  s.display.rotary_units[0] = AxisUnit::Inches;
  s.axes[3] = s.axes[2];
  s.speeds.move.a = s.speeds.move.z;
  s.speeds.jog.a = s.speeds.jog.z;
  s.ramps.move_ramp_speed.a = s.ramps.move_ramp_speed.z;
  s.ramps.jog_ramp_speed.a = s.ramps.jog_ramp_speed.z;
  s.inputs.home_bit[3] = s.inputs.home_bit[2];
  s.homing.direction[3] = 1;
  s.homing.at[3] = 0;
  s.homing.order = "a";
  return s;
}

struct Machine {
  explicit Machine(Settings s = w_profile(), SimWorld w = {})
      : settings(std::move(s)), card(settings, false, std::move(w)) {}
  Settings settings;
  SimCard card;
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};

  // Runs G-code; the error's message, or "" when it ran to its end.
  std::string run(const std::string& text) {
    const Outcome o = c.run(Script::from_text(text, "part.nc"));
    if (!o) return o.errors.empty() ? o.reason : o.errors[0].message;
    c.wait();
    const ControllerStatus st = c.status();
    return st.state == MachineState::Idle ? "" : st.message;
  }
  std::int64_t steps(int i, double units) const {
    return std::llround(units * settings.axes[static_cast<size_t>(i)].steps_per_unit);
  }
};

TEST(WAxis, TheProfileNamesItAndTheLoaderKeepsItToAVerticalHeadInUse) {
  ASSERT_TRUE(settings_problems(w_profile()).empty()) << settings_problems(w_profile())[0];
  // Written and read back by the schema: display.w_axis = "a".
  const std::string text = settings_text(w_profile());
  EXPECT_NE(text.find("w_axis = 'a'"), std::string::npos);
  const SettingsLoad back = parse_settings(text, "w.toml");
  ASSERT_TRUE(back.ok()) << back.errors[0].message;
  EXPECT_EQ(back.settings.display.w_axis, 3);
  EXPECT_EQ(axis_names(back.settings), "XYZWBC");
  EXPECT_EQ(axis_name(back.settings, 3), 'W');
  EXPECT_EQ(axis_name(default_settings(), 3), 'A');
  // B as W on a machine of 4 axes: not in use; A as W in degrees: not a vertical head.
  Settings s = w_profile();
  s.display.w_axis = 4;
  s.display.rotary_units[1] = AxisUnit::Inches;
  ASSERT_FALSE(settings_problems(s).empty());
  EXPECT_NE(settings_problems(s)[0].find("display.w_axis names B as W, an axis display.axes = 4 "
                                         "does not use"),
            std::string::npos);
  s = w_profile();
  s.display.rotary_units[0] = AxisUnit::Degrees;
  ASSERT_FALSE(settings_problems(s).empty());
  EXPECT_NE(settings_problems(s)[0].find("display.units_a is degrees"), std::string::npos);
  // The error is located at the key in the profile.
  std::string bad = text;
  bad.replace(bad.find("units_a = 'in'"), 14, "units_a = 'deg'");
  const SettingsLoad load = parse_settings(bad, "w.toml");
  ASSERT_FALSE(load.ok());
  EXPECT_GT(load.errors[0].loc.line, 0);
  EXPECT_NE(load.errors[0].message.find("display.w_axis"), std::string::npos);
}

// G0 W and G1 W move A's channel (step bit 3); Z's stays where Z's words put it.
TEST(WAxis, GcodeWWordsMoveTheAxisTheProfileNamesWOnItsChannel) {
  Machine m;
  ASSERT_EQ(m.run("G90\nG0 W-1\nG1 W-1.5 F10\nG0 Z0.5\n"), "");
  EXPECT_EQ(m.card.steps()[3], m.steps(3, -1.5));
  EXPECT_EQ(m.card.steps()[2], m.steps(2, 0.5));
  EXPECT_EQ(m.card.steps()[0], 0);
  EXPECT_NEAR(m.c.modal().position[3], -1.5, 1e-12);
  EXPECT_EQ(m.card.timing_violations(), 0u);
  // The readout and the run's messages name it W.
  const std::string readout =
      session::readout_text("ready", m.c.modal().position, Units::Inches, axis_names(m.settings));
  EXPECT_NE(readout.find("W -1.5000"), std::string::npos) << readout;
  EXPECT_EQ(readout.find(" A "), std::string::npos) << readout;
}

// W and the letter it replaces name one axis: both in one block is refused, nothing moves.
TEST(WAxis, WAndItsOwnLetterInOneBlockAreRefused) {
  Machine m;
  const std::string why = m.run("G90\nG0 W1 A1\n");
  EXPECT_NE(why.find("W and A both name the W axis"), std::string::npos) << why;
  EXPECT_EQ(m.card.steps()[3], 0);
}

// Beyond its soft limits (axes.a's): the message names W, and nothing moves.
TEST(WAxis, ItsSoftLimitsAreNamedW) {
  Machine m;
  const std::string why = m.run("G90\nG0 W9\n");
  EXPECT_NE(why.find("move to W=9.0000 is outside the soft limits"), std::string::npos) << why;
  EXPECT_EQ(m.card.steps()[3], 0);
}

// G28 W homes the head upwards (a vertical head, homing.a.direction "+") to its switch, which
// becomes homing.a.at, and backs off below it.
TEST(WAxis, G28WHomesTheHeadUpToItsSwitch) {
  SimWorld w;
  w.home_switch[3] = 2.0;
  w.home_above[3] = true;
  Machine m(w_profile(), w);
  ASSERT_EQ(m.run("G28 W\n"), "");
  const double spu = m.settings.axes[3].steps_per_unit;
  // The card's motor stood on its switch (2 in up), then backed off 0.25 in.
  EXPECT_NEAR(static_cast<double>(m.card.steps()[3]) / spu, 2.0 - m.settings.homing.back_off,
              2.0 / spu);
  const ModalState ms = m.c.modal();
  EXPECT_NEAR(ms.position[3] + ms.zero[3], -m.settings.homing.back_off, 1e-9);
  EXPECT_EQ(m.card.steps()[2], 0);  // Z did not move
}

// A profile without a W axis refuses W where it stands, and G28 W too.
TEST(WAxis, WithoutOneWIsRefusedWhereItStands) {
  Settings s = default_settings();
  s.gcode_dialect = GcodeDialect::WinCNC;
  s.outputs.charge_pump_bit = -1;
  Machine m(s);
  for (const char* text : {"G0 X1 W-0.5\n", "G28 W\n"}) {
    const std::string why = m.run(text);
    EXPECT_NE(why.find("W is the axis of a second vertical head"), std::string::npos) << why;
  }
  EXPECT_EQ(m.card.steps()[0], 0);
}

// OpenSBP has no W: its A commands move the W axis (docs/hardware.md, "The W axis").
TEST(WAxis, OpenSbpReachesItThroughItsOwnLettersCommands) {
  Machine m;
  const Outcome o = m.c.run(Script::from_text("MA, -0.75\n", "part.sbp"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : " " + o.errors[0].message);
  m.c.wait();
  EXPECT_EQ(m.card.steps()[3], m.steps(3, -0.75));
}

}  // namespace
}  // namespace gantry
