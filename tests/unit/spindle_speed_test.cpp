// TR, the spindle's speed (docs/settings.md, "The spindle"): recorded and readable as %(161)
// while output 1 runs the spindle; sent between the moves to the profile's PWM speed output
// where there is one, else one warning a run; the [spindle] keys validated.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "gantry/core/diagnostic.hpp"
namespace gantry {
namespace {

class SpindleSpeedTest : public KeptInterpreterFixture {
 protected:
  // Runs `text`; the error it stops at ("" when none).
  std::string run(const std::string& text) {
    try {
      interp().run(Script::from_text(text, "part.sbp"));
    } catch (const GantryError& e) {
      return format(e.diagnostic());
    }
    return "";
  }
  std::string text_of(const char* name) {
    const Value* v = interp().variable(name);
    return v ? v->to_string() : "(unset)";
  }
  std::vector<double> speeds_sent() const {
    std::vector<double> rpm;
    for (const CanonMove& m : sink.moves)
      if (m.kind == MoveKind::SpindleSpeed) rpm.push_back(m.spindle_rpm);
    return rpm;
  }
};

TEST_F(SpindleSpeedTest, WithoutASpeedOutputTrWarnsOnceARun) {
  ASSERT_EQ(settings.spindle.pwm_bit, -1);  // the shipped profile wires none
  EXPECT_EQ(run("TR, 18000\nMX, 1\nTR, 12000\nTR, &s\n"),
            "part.sbp:4:5: error: undefined variable &S; set it before this line");
  EXPECT_EQ(run("TR, 18000\nMX, 1\nTR, 12000\nTR, 16000\n"), "");
  ASSERT_EQ(io.warnings().size(), 2u);  // one each run, at its first TR
  EXPECT_EQ(format(io.warnings()[1]),
            "part.sbp:1:1: warning: TR: this machine's profile has no spindle speed output "
            "([spindle] pwm_bit), so the spindle runs at the speed set on it; the RPM is only "
            "recorded (%(161)). Said once a run");
  EXPECT_EQ(interp().state().spindle_rpm, 16000);
  EXPECT_TRUE(speeds_sent().empty());
}

// The handbook: %(161) is the spindle's RPM, 0 when it is stopped; output 1 runs it.
TEST_F(SpindleSpeedTest, Percent161ReadsTheSpeedWhileOutputOneIsOn) {
  EXPECT_EQ(run("TR, 18000.4\n&off = %(161)\nSO, 1, 1\n&on = %(161)\nSO, 1, 0\n"
                "&after = %(161)\n"),
            "");
  EXPECT_EQ(text_of("OFF"), "0");
  EXPECT_EQ(text_of("ON"), "18000");
  EXPECT_EQ(text_of("AFTER"), "0");
}

TEST_F(SpindleSpeedTest, WithASpeedOutputTrIsSentBetweenTheMovesAndEndsAtZero) {
  settings.spindle.pwm_bit = 30;
  EXPECT_EQ(run("MX, 1\nTR, 18000\nMX, 2\n"), "");
  ASSERT_GE(sink.moves.size(), 4u);
  EXPECT_EQ(sink.moves[0].kind, MoveKind::Line);
  EXPECT_EQ(sink.moves[1].kind, MoveKind::SpindleSpeed);
  EXPECT_EQ(sink.moves[1].spindle_rpm, 18000);
  EXPECT_EQ(sink.moves[1].loc.line, 2);
  EXPECT_EQ(sink.moves[2].kind, MoveKind::Line);
  EXPECT_EQ(speeds_sent(), (std::vector<double>{18000, 0}));  // the run's end: 0
  EXPECT_TRUE(io.warnings().empty());
  EXPECT_EQ(interp().state().spindle_rpm, 18000);  // kept for the next C6, as a VFD keeps it
}

TEST_F(SpindleSpeedTest, AboveMaxRpmIsRefusedAtItsColumnAndNothingIsSent) {
  settings.spindle.pwm_bit = 30;
  settings.spindle.max_rpm = 24000;
  EXPECT_EQ(run("TR,  30000\n"),
            "part.sbp:1:6: error: TR 30000 RPM is faster than this spindle runs (24000 RPM, "
            "spindle.max_rpm); nothing was changed");
  EXPECT_TRUE(speeds_sent().empty());
  EXPECT_EQ(run("TR, -1\n").find("part.sbp:1:5: error: TR parameter 1 (speed) is -1"), 0u);
}

TEST_F(SpindleSpeedTest, FabMosSpindleNumberIsOne) {
  EXPECT_EQ(run("TR, 12000, 1\n"), "");
  EXPECT_EQ(run("TR, 12000, 2\n").find("part.sbp:1:12: error: TR parameter 2 (spindle) is 2"), 0u);
}

// ---- [spindle] in the profile

std::string profile_with(const std::string& from, const std::string& to) {
  std::string text = default_profile_text();
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

std::string messages(const SettingsLoad& l) {
  std::string out;
  for (const Diagnostic& d : l.errors) out += d.message + "\n";
  return out;
}

TEST(SpindleSettings, APwmBitLoads) {
  const SettingsLoad l = parse_settings(profile_with("pwm_bit = -1", "pwm_bit = 30"), "p.toml");
  ASSERT_TRUE(l.ok()) << messages(l);
  EXPECT_EQ(l.settings.spindle.pwm_bit, 30);
  EXPECT_EQ(l.settings.spindle.pwm_hz, 1000);
  EXPECT_EQ(l.settings.spindle.max_rpm, 24000);
}

TEST(SpindleSettings, APwmBitAlreadyUsedIsRefused) {
  const SettingsLoad l = parse_settings(profile_with("pwm_bit = -1", "pwm_bit = 18"), "p.toml");
  EXPECT_EQ(messages(l), "spindle.pwm_bit: output bit 18 is already used by another pin\n");
}

TEST(SpindleSettings, APwmTooFastForThePacerIsRefused) {
  const SettingsLoad l = parse_settings(
      profile_with("pwm_bit = -1\npwm_hz = 1000.0", "pwm_bit = 30\npwm_hz = 4000.0"), "p.toml");
  EXPECT_EQ(messages(l),
            "spindle.pwm_hz 4000 leaves 50 ticks a period at the card's 200000 Hz pacer; at "
            "most 2000 Hz keeps TR's duty within 1 %\n");
}

// Profiles written before TR have no [spindle]: they load, with no speed output.
TEST(SpindleSettings, AProfileWithoutASpindleTableHasNoSpeedOutput) {
  std::string text = default_profile_text();
  const size_t from = text.find("\n[spindle]\n");
  ASSERT_NE(from, std::string::npos);
  text.erase(from, text.find("\n[", from + 1) - from);
  const SettingsLoad l = parse_settings(text, "p.toml");
  EXPECT_EQ(messages(l), "");
  EXPECT_EQ(l.settings.spindle.pwm_bit, -1);
}

}  // namespace
}  // namespace gantry
