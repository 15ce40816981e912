#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "../support/where.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/settings/values_file.hpp"  // parse_settings with values

namespace gantry {
namespace {

const std::string kOrigin = "test.toml";

// A profile text with one line changed, and the 1-based number of that line.
struct Edited {
  std::string text;
  int line = 0;
};

// Finds the line `key = ...` inside `[section]` ("" for the top level) of `text`; returns the
// offset of its first character, or npos.
size_t find_key(const std::string& text, std::string_view section, std::string_view key) {
  size_t start = 0;
  if (!section.empty()) {
    const std::string header = "\n[" + std::string(section) + "]";
    start = text.find(header);
    if (start == std::string::npos) return std::string::npos;
    start += header.size();
  }
  size_t end = text.find("\n[", start);
  if (end == std::string::npos) end = text.size();
  const size_t at = text.find("\n" + std::string(key) + " =", start);
  if (at == std::string::npos || at >= end) return std::string::npos;
  return at + 1;
}

// Replaces the whole line `key = ...` in `[section]` by `new_line` (no newline in it).
Edited replace_line(const std::string& text, std::string_view section, std::string_view key,
                    std::string_view new_line) {
  const size_t at = find_key(text, section, key);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no key " << key << " in [" << section << "]";
    return {text, 0};
  }
  const size_t eol = text.find('\n', at);
  Edited out;
  out.text = text.substr(0, at) + std::string(new_line) + text.substr(eol);
  out.line = static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')) + 1;
  return out;
}

// Sets `key = value` in `[section]`; the value starts at column key.size() + 4.
Edited set_key(const std::string& text, std::string_view section, std::string_view key,
               std::string_view value) {
  return replace_line(text, section, key, std::string(key) + " = " + std::string(value));
}

Edited set_key(std::string_view section, std::string_view key, std::string_view value) {
  return set_key(default_profile_text(), section, key, value);
}

// The default profile without the line `key = ...` of `[section]`.
std::string remove_key(std::string_view section, std::string_view key) {
  const std::string& text = default_profile_text();
  const size_t at = find_key(text, section, key);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no key " << key << " in [" << section << "]";
    return text;
  }
  return text.substr(0, at) + text.substr(text.find('\n', at) + 1);
}

// The 1-based line of the first line of `text` that is exactly `line`.
int line_of(const std::string& text, std::string_view line) {
  const size_t at = text.find("\n" + std::string(line) + "\n");
  if (at == std::string::npos) {
    ADD_FAILURE() << "no line " << line;
    return 0;
  }
  return static_cast<int>(std::count(text.begin(), text.begin() + at + 1, '\n')) + 1;
}

SettingsLoad load(const std::string& text) {
  return parse_settings(text, kOrigin);
}

std::string loc_at(int line, int column) {
  return kOrigin + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string messages(const SettingsLoad& l) {
  std::string out;
  for (const Diagnostic& d : l.errors) out += format(d) + "\n";
  return out;
}

// ---- the shipped default

TEST(DefaultProfile, LoadsWithoutErrors) {
  const SettingsLoad l = parse_settings(default_profile_text(), "settings/default.toml");
  EXPECT_TRUE(l.ok()) << messages(l);
  EXPECT_TRUE(l.errors.empty());
}

TEST(DefaultProfile, CompiledInTextIsTheShippedFile) {
  const SettingsLoad file =
      load_settings_file(std::string(GANTRY_SOURCE_DIR) + "/settings/default.toml");
  ASSERT_TRUE(file.ok()) << messages(file);
  EXPECT_EQ(file.settings.name, default_settings().name);
  EXPECT_DOUBLE_EQ(file.settings.axes[0].steps_per_unit, default_settings().axes[0].steps_per_unit);
}

TEST(DefaultProfile, NameAndUnits) {
  const Settings s = default_settings();
  EXPECT_EQ(s.name, "Desktop 24x18 (inches)");
  EXPECT_EQ(s.units, Units::Inches);
  EXPECT_STREQ(units_name(s.units), "in");
}

TEST(DefaultProfile, LinearAxes) {
  const Settings s = default_settings();
  const AxisSettings& x = s.axes[0];
  EXPECT_DOUBLE_EQ(x.steps_per_unit, 916.7324);
  EXPECT_DOUBLE_EQ(x.max_speed, 8.0);
  EXPECT_DOUBLE_EQ(x.max_accel, 20.0);
  EXPECT_DOUBLE_EQ(x.min, 0.0);
  EXPECT_DOUBLE_EQ(x.max, 24.0);
  const AxisSettings& y = s.axes[1];
  EXPECT_DOUBLE_EQ(y.steps_per_unit, 916.7324);
  EXPECT_DOUBLE_EQ(y.max, 18.0);
  const AxisSettings& z = s.axes[2];
  EXPECT_DOUBLE_EQ(z.steps_per_unit, 1018.5916);
  EXPECT_DOUBLE_EQ(z.max_speed, 4.0);
  EXPECT_DOUBLE_EQ(z.max_accel, 16.0);
  EXPECT_DOUBLE_EQ(z.min, -4.0);
  EXPECT_DOUBLE_EQ(z.max, 5.5);
}

TEST(DefaultProfile, RotaryAxes) {
  const Settings s = default_settings();
  for (int i = 3; i < kAxisCount; ++i) {
    SCOPED_TRACE(kAxisLetters[i]);
    EXPECT_DOUBLE_EQ(s.axes[i].steps_per_unit, 13.8889);
    EXPECT_DOUBLE_EQ(s.axes[i].max_speed, 90.0);
    EXPECT_DOUBLE_EQ(s.axes[i].max_accel, 360.0);
    EXPECT_DOUBLE_EQ(s.axes[i].min, -100000.0);
    EXPECT_DOUBLE_EQ(s.axes[i].max, 100000.0);
  }
}

TEST(DefaultProfile, Speeds) {
  const Settings s = default_settings();
  EXPECT_DOUBLE_EQ(s.speeds.move.xy, 2.0);
  EXPECT_DOUBLE_EQ(s.speeds.move.z, 0.5);
  EXPECT_DOUBLE_EQ(s.speeds.move.a, 10.0);
  EXPECT_DOUBLE_EQ(s.speeds.move.b, 10.0);
  EXPECT_DOUBLE_EQ(s.speeds.move.c, 10.0);
  EXPECT_DOUBLE_EQ(s.speeds.jog.xy, 6.0);
  EXPECT_DOUBLE_EQ(s.speeds.jog.z, 3.0);
  EXPECT_DOUBLE_EQ(s.speeds.jog.a, 45.0);
  EXPECT_DOUBLE_EQ(s.speeds.jog.b, 45.0);
  EXPECT_DOUBLE_EQ(s.speeds.jog.c, 45.0);
}

TEST(DefaultProfile, Ramps) {
  const RampSettings r = default_settings().ramps;
  EXPECT_DOUBLE_EQ(r.move_ramp_rate, 0.2);
  EXPECT_DOUBLE_EQ(r.jog_ramp_rate, 0.2);
  EXPECT_DOUBLE_EQ(r.threshold_3d, 100.0);
  EXPECT_DOUBLE_EQ(r.min_distance, 0.15);
  EXPECT_DOUBLE_EQ(r.slow_corner, 65.0);
  EXPECT_DOUBLE_EQ(r.keypad_ramp_rate, 0.2);
  EXPECT_DOUBLE_EQ(r.small_circle, 0.25);
  for (const GroupSpeeds& g : {r.move_ramp_speed, r.jog_ramp_speed}) {
    EXPECT_DOUBLE_EQ(g.xy, 0.4);
    EXPECT_DOUBLE_EQ(g.z, 0.4);
    EXPECT_DOUBLE_EQ(g.a, 0.4);
    EXPECT_DOUBLE_EQ(g.b, 0.4);
    EXPECT_DOUBLE_EQ(g.c, 0.4);
  }
}

TEST(DefaultProfile, Card) {
  const CardSettings c = default_settings().card;
  EXPECT_EQ(c.type, "sim");
  EXPECT_DOUBLE_EQ(c.clock_hz, 4'000'000.0);
  EXPECT_EQ(c.pacer_divisor, 20);
  EXPECT_DOUBLE_EQ(c.pacer_hz(), 200'000.0);
  EXPECT_DOUBLE_EQ(c.step_pulse_us, 5.0);
  EXPECT_DOUBLE_EQ(c.dir_setup_us, 5.0);
}

TEST(DefaultProfile, Pins) {
  const Settings s = default_settings();
  for (int i = 0; i < kAxisCount; ++i) {
    SCOPED_TRACE(kAxisLetters[i]);
    EXPECT_EQ(s.pins[i].step_bit, i);
    EXPECT_EQ(s.pins[i].dir_bit, 8 + i);
    EXPECT_FALSE(s.pins[i].invert_dir);
    EXPECT_FALSE(s.pins[i].step_active_low);
  }
}

// ---- values that load

TEST(DefaultProfile, MachineValues) {
  EXPECT_DOUBLE_EQ(default_settings().cutter.safe_z, 1.0);
}

TEST(DefaultProfile, Planner) {
  const PlannerSettings p = default_settings().planner;
  EXPECT_EQ(p.mode, PlannerMode::SB3);
  EXPECT_DOUBLE_EQ(p.corner_jump, 0.11);
  EXPECT_DOUBLE_EQ(p.junction_deviation, 0.002);
  EXPECT_DOUBLE_EQ(p.chord_tolerance, 0.0005);
  EXPECT_EQ(p.lookahead, 1024);
}

TEST(SettingsLoad, PlannerModesAndTheirErrors) {
  EXPECT_EQ(load(set_key("planner", "mode", "\"junction\"").text).settings.planner.mode,
            PlannerMode::Junction);
  EXPECT_EQ(load(set_key("planner", "mode", "\"stop\"").text).settings.planner.mode,
            PlannerMode::Stop);
  const Edited e = set_key("planner", "mode", "\"grbl\"");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "planner.mode = \"grbl\" is not allowed; use one of \"sb3\", \"junction\", \"stop\"");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 8));
  const SettingsLoad jump = load(set_key("planner", "corner_jump", "1.5").text);
  ASSERT_EQ(jump.errors.size(), 1u) << messages(jump);
  EXPECT_EQ(jump.errors[0].message,
            "planner.corner_jump = 1.5 is out of range; allowed: >= 0 and <= 1");
  EXPECT_EQ(load(set_key("planner", "chord_tolerance", "0.0").text).errors.size(), 1u);
  EXPECT_EQ(load(set_key("planner", "lookahead", "1").text).errors.size(), 1u);
}

TEST(SettingsLoad, GpioLinePairsAreReadAndCheckedWithTheirForm) {
  const Settings d = default_settings();
  ASSERT_EQ(d.card.gpiod_outputs.size(), 6u);
  EXPECT_EQ(d.card.gpiod_outputs[1].bit, 8);  // "8:27": bit 8 on line 27
  EXPECT_EQ(d.card.gpiod_outputs[1].line, 27u);
  ASSERT_EQ(d.card.gpiod_inputs.size(), 3u);
  EXPECT_EQ(d.card.gpiod_inputs[0].line, 5u);  // "5:0": line 5 sets bit 0
  EXPECT_EQ(d.card.gpiod_inputs[0].bit, 0);
  const Edited e = set_key("card", "gpiod_outputs", "\"0:17, 40:3\"");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "card.gpiod_outputs: \"40:3\" is not BIT:LINE (bits 0-31, line offsets from 0)");
  EXPECT_EQ(load(set_key("card", "gpiod_inputs", "\"5-0\"").text).errors.size(), 1u);
  EXPECT_EQ(load(set_key("card", "gpiod_inputs", "7").text).errors[0].message,
            "card.gpiod_inputs must be a string such as \"0:17, 8:27\"");
}

TEST(SettingsLoad, AuxOutputBitsAreAListAndMayNotCollide) {
  EXPECT_EQ(default_settings().outputs.aux_bits,
            (std::vector<int>{18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29}));
  const SettingsLoad clash = load(set_key("outputs", "aux_bits", "\"18, 0\"").text);
  ASSERT_EQ(clash.errors.size(), 1u) << messages(clash);
  EXPECT_EQ(clash.errors[0].message,
            "outputs.aux_bits (output 2): output bit 0 is already used by another pin");
  const SettingsLoad bad = load(set_key("outputs", "aux_bits", "\"18, x\"").text);
  ASSERT_EQ(bad.errors.size(), 1u) << messages(bad);
  EXPECT_EQ(bad.errors[0].message, "outputs.aux_bits: \"x\" is not a whole number from -1 to 31");
}

TEST(SettingsLoad, MillimetreUnits) {
  const SettingsLoad l = load(set_key("", "units", "\"mm\"").text);
  ASSERT_TRUE(l.ok()) << messages(l);
  EXPECT_EQ(l.settings.units, Units::Millimetres);
  EXPECT_STREQ(units_name(l.settings.units), "mm");
}

TEST(SettingsLoad, IntegerIsAcceptedForANumber) {
  const SettingsLoad l = load(set_key("axes.x", "max_speed", "7").text);
  ASSERT_TRUE(l.ok()) << messages(l);
  EXPECT_DOUBLE_EQ(l.settings.axes[0].max_speed, 7.0);
}

TEST(SettingsLoad, ChangedValuesAreRead) {
  Edited e = set_key("pins.y", "invert_dir", "true");
  e = set_key(e.text, "card", "pacer_divisor", "10");
  e = set_key(e.text, "ramps", "slow_corner", "100");
  const SettingsLoad l = load(e.text);
  ASSERT_TRUE(l.ok()) << messages(l);
  EXPECT_TRUE(l.settings.pins[1].invert_dir);
  EXPECT_FALSE(l.settings.pins[0].invert_dir);
  EXPECT_EQ(l.settings.card.pacer_divisor, 10);
  EXPECT_DOUBLE_EQ(l.settings.card.pacer_hz(), 400'000.0);
  EXPECT_DOUBLE_EQ(l.settings.ramps.slow_corner, 100.0);
}

// ---- errors at a key

TEST(SettingsLoad, MisspelledKeyIsUnknownAndTheRealKeyMissing) {
  const Edited e =
      replace_line(default_profile_text(), "axes.x", "steps_per_unit", "steps_per_uint = 916.7324");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 2u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "missing key axes.x.steps_per_unit");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line - 1, 1));  // the [axes.x] header
  EXPECT_EQ(l.errors[1].message,
            "unknown key axes.x.steps_per_uint; check its spelling against docs/settings.md");
  EXPECT_EQ(where(l.errors[1].loc), loc_at(e.line, 1));  // at the misspelled key
}

TEST(SettingsLoad, ExtraTopLevelKeyIsUnknown) {
  const std::string text = "colour = \"red\"\n" + default_profile_text();
  const SettingsLoad l = load(text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "unknown key colour; check its spelling against docs/settings.md");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(1, 1));
}

TEST(SettingsLoad, StringForANumber) {
  const Edited e = set_key("axes.x", "max_speed", "\"fast\"");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "axes.x.max_speed must be a number");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 13));
}

TEST(SettingsLoad, BoolForANumber) {
  const Edited e = set_key("axes.z", "max_accel", "true");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "axes.z.max_accel must be a number");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 13));
}

TEST(SettingsLoad, FloatForAnInteger) {
  const Edited e = set_key("card", "pacer_divisor", "20.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "card.pacer_divisor must be a whole number");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 17));
}

TEST(SettingsLoad, NumberForABool) {
  const Edited e = set_key("pins.b", "invert_dir", "1");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "pins.b.invert_dir must be true or false");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 14));
}

TEST(SettingsLoad, NumberForAChoice) {
  const Edited e = set_key("card", "type", "1");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "card.type must be a string, one of \"sim\", \"pci7200\", \"gpiod\"");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 8));
}

TEST(SettingsLoad, NumberForTheName) {
  const Edited e = set_key("", "name", "5");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "name must be a string");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 8));
}

TEST(SettingsLoad, ValueNotInTheChoices) {
  const Edited e = set_key("", "units", "\"cm\"");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "units = \"cm\" is not allowed; use one of \"in\", \"mm\"");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 9));
}

// SB3's convention (VU): a negative steps-per-unit value reverses the axis; zero is an error.
TEST(SettingsLoad, NegativeStepsPerUnitReversesAndZeroIsAnError) {
  const SettingsLoad reversed = load(set_key("axes.x", "steps_per_unit", "-916.7324").text);
  ASSERT_TRUE(reversed.ok()) << messages(reversed);
  EXPECT_DOUBLE_EQ(reversed.settings.axes[0].steps_per_unit, -916.7324);
  const SettingsLoad zero = load(set_key("axes.x", "steps_per_unit", "0.0").text);
  ASSERT_EQ(zero.errors.size(), 1u) << messages(zero);
  EXPECT_EQ(zero.errors[0].message, "axes.x.steps_per_unit must not be 0");
}

TEST(SettingsLoad, ZeroIsOutsideAnOpenRange) {
  const Edited e = set_key("axes.y", "max_speed", "0.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "axes.y.max_speed = 0 is out of range; allowed: > 0 and <= 100000");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 13));
}

TEST(SettingsLoad, AboveAClosedRange) {
  const Edited e = set_key("ramps", "slow_corner", "100.5");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "ramps.slow_corner = 100.5 is out of range; allowed: >= 0 and <= 100");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 15));
}

TEST(SettingsLoad, IntegerOutOfRange) {
  const Edited e = set_key("pins.c", "step_bit", "32");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "pins.c.step_bit = 32 is out of range; allowed: 0 to 31");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 12));
}

TEST(SettingsLoad, MissingKeyIsReportedAtItsTable) {
  const std::string text = remove_key("axes.y", "max_accel");
  const SettingsLoad l = load(text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "missing key axes.y.max_accel");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(line_of(text, "[axes.y]"), 1));
}

TEST(SettingsLoad, MissingTopLevelKey) {
  const SettingsLoad l = load(remove_key("", "units"));
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "missing key units");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(1, 1));  // the top-level table
}

TEST(SettingsLoad, MissingTableIsReportedAtTheTopLevel) {
  const std::string& text = default_profile_text();
  const size_t from = text.find("[card]");
  const size_t to = text.find("[pins.x]");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  const SettingsLoad l = load(text.substr(0, from) + text.substr(to));
  ASSERT_FALSE(l.errors.empty());
  EXPECT_EQ(l.errors[0].message, "missing key card");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(1, 1));
  for (const Diagnostic& d : l.errors)
    EXPECT_EQ(d.message.rfind("missing key card", 0), 0u) << d.message;
}

TEST(SettingsLoad, ExtraTableIsAnUnknownKeyAtItsHeader) {
  const std::string text = default_profile_text() + "\n[axes.q]\nmin = 1.0\n";
  const SettingsLoad l = load(text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "unknown key axes.q; check its spelling against docs/settings.md");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(line_of(text, "[axes.q]"), 7));  // the q
}

TEST(SettingsLoad, NanIsOutOfRange) {
  const Edited e = set_key("axes.x", "max_speed", "nan");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "axes.x.max_speed = nan is out of range; allowed: > 0 and <= 100000");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 13));
}

TEST(SettingsLoad, InfiniteSoftLimitIsOutOfRange) {
  const Edited e = set_key("axes.a", "max", "inf");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "axes.a.max = inf is out of range; allowed: >= -1000000000 and <= 1000000000");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 7));
}

TEST(SettingsLoad, InvalidTomlIsOneLocatedError) {
  const Edited e = set_key("axes.x", "max_accel", "20.0.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message.rfind("not valid TOML: ", 0), 0u) << l.errors[0].message;
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 17));
}

TEST(SettingsLoad, UnclosedTableHeaderIsInvalidToml) {
  const std::string text = "name = \"x\"\n[axes.x\n";
  const SettingsLoad l = load(text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message.rfind("not valid TOML: ", 0), 0u) << l.errors[0].message;
  EXPECT_EQ(l.errors[0].loc.line, 2);
}

// ---- errors across keys

// A rule across keys is located at the first key it names (it was at the file's top).
TEST(SettingsLoad, MinEqualToMaxIsAnErrorAtTheMinKey) {
  const Edited e = set_key("axes.x", "min", "24.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "axes.x.min (24) must be below axes.x.max (24)");
  EXPECT_EQ(format(l.errors[0]),
            loc_at(e.line, 7) + ": error: axes.x.min (24) must be below axes.x.max (24)");
}

// The same rule broken by a values file's key is that file's, at its line (it was blamed on
// the profile, settings/default.toml, with no line).
TEST(SettingsLoad, ARuleBrokenByAValuesFileKeyIsLocatedInTheValuesFile) {
  const SettingsLoad l = parse_settings(default_profile_text(), "settings/default.toml",
                                        std::string("# V commands\n[axes.x]\nmin = 30.0\n"),
                                        "values.toml");
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(format(l.errors[0]),
            "values.toml:3:7: error: axes.x.min (30) must be below axes.x.max (24)");
}

TEST(SettingsLoad, MinAboveMaxIsAnError) {
  const SettingsLoad l = load(set_key("axes.z", "min", "6.5").text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "axes.z.min (6.5) must be below axes.z.max (5.5)");
}

TEST(SettingsLoad, StepRateAboveTheCardLimitIsAnError) {
  const Edited e = set_key("axes.x", "max_speed", "200.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "axes.x.max_speed 200 x steps_per_unit 916.7324 = 183346 steps/s exceeds the card's "
            "100000 steps/s (pacer 200000 Hz, 1-tick pulse plus one idle tick); lower max_speed "
            "or raise the pacer");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 13));
}

TEST(SettingsLoad, StepRateExactlyAtTheCardLimitIsAllowed) {
  Edited e = set_key("axes.c", "steps_per_unit", "1000.0");
  e = set_key(e.text, "axes.c", "max_speed", "100.0");
  const SettingsLoad l = load(e.text);
  EXPECT_TRUE(l.ok()) << messages(l);
}

TEST(SettingsLoad, StepRateJustAboveTheCardLimitIsAnError) {
  Edited e = set_key("axes.c", "steps_per_unit", "1000.0");
  e = set_key(e.text, "axes.c", "max_speed", "100.001");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message.rfind("axes.c.max_speed 100.001 x steps_per_unit 1000 = 100001 "
                                      "steps/s exceeds the card's 100000 steps/s",
                                      0),
            0u)
      << l.errors[0].message;
}

TEST(SettingsLoad, WiderStepPulseLowersTheCardLimit) {
  // 12 us at a 5 us tick is a 3-tick pulse: 200 kHz / 4 = 50 000 steps/s.
  Edited e = set_key("card", "step_pulse_us", "12.0");
  e = set_key(e.text, "axes.x", "max_speed", "60.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "axes.x.max_speed 60 x steps_per_unit 916.7324 = 55004 steps/s exceeds the card's "
            "50000 steps/s (pacer 200000 Hz, 3-tick pulse plus one idle tick); lower max_speed "
            "or raise the pacer");
}

TEST(SettingsLoad, SlowerPacerLowersTheCardLimit) {
  // 4 MHz / 80 = 50 kHz, a 20 us tick: a 5 us pulse takes one tick, so 25 000 steps/s.
  Edited e = set_key("card", "pacer_divisor", "80");
  e = set_key(e.text, "axes.y", "max_speed", "30.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message,
            "axes.y.max_speed 30 x steps_per_unit 916.7324 = 27502 steps/s exceeds the card's "
            "25000 steps/s (pacer 50000 Hz, 1-tick pulse plus one idle tick); lower max_speed "
            "or raise the pacer");
}

TEST(SettingsLoad, DuplicateOutputBitAcrossAxesIsAnError) {
  const Edited e = set_key("pins.y", "step_bit", "0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "pins.y.step_bit: output bit 0 is already used by another pin");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 12));
}

TEST(SettingsLoad, StepAndDirectionOnTheSameBitIsAnError) {
  const SettingsLoad l = load(set_key("pins.z", "dir_bit", "2").text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "pins.z.dir_bit: output bit 2 is already used by another pin");
}

TEST(SettingsLoad, DirectionBitReusedAsALaterStepBitIsAnError) {
  const SettingsLoad l = load(set_key("pins.c", "step_bit", "8").text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "pins.c.step_bit: output bit 8 is already used by another pin");
}

TEST(SettingsLoad, MoveSpeedAboveMaxSpeedIsAnError) {
  const Edited e = set_key("speeds.move", "xy", "9.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "speeds.move.xy = 9 exceeds the axis max_speed 8");
  EXPECT_EQ(where(l.errors[0].loc), loc_at(e.line, 6));
}

TEST(SettingsLoad, XySpeedLimitIsTheSlowerOfXAndY) {
  Edited e = set_key("axes.y", "max_speed", "5.0");
  e = set_key(e.text, "speeds.jog", "xy", "5.5");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "speeds.jog.xy = 5.5 exceeds the axis max_speed 5");
}

TEST(SettingsLoad, JogSpeedAboveMaxSpeedIsAnError) {
  const SettingsLoad l = load(set_key("speeds.jog", "c", "91.0").text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "speeds.jog.c = 91 exceeds the axis max_speed 90");
}

TEST(SettingsLoad, SpeedEqualToMaxSpeedIsAllowed) {
  Edited e = set_key("speeds.move", "xy", "8.0");
  e = set_key(e.text, "speeds.jog", "z", "4.0");
  const SettingsLoad l = load(e.text);
  EXPECT_TRUE(l.ok()) << messages(l);
}

// ---- several errors

TEST(SettingsLoad, EveryKeyErrorInAFileIsReported) {
  Edited a = set_key("axes.x", "max_speed", "\"fast\"");
  Edited b = set_key(a.text, "ramps", "slow_corner", "-1.0");
  Edited c = set_key(b.text, "card", "pacer_divisor", "1.5");
  Edited d = set_key(c.text, "pins.c", "invert_dir", "\"no\"");
  const SettingsLoad l = load(d.text);
  ASSERT_EQ(l.errors.size(), 4u) << messages(l);
  EXPECT_EQ(where(l.errors[0].loc), loc_at(a.line, 13));
  EXPECT_EQ(l.errors[0].message, "axes.x.max_speed must be a number");
  EXPECT_EQ(where(l.errors[1].loc), loc_at(b.line, 15));
  EXPECT_EQ(l.errors[1].message,
            "ramps.slow_corner = -1 is out of range; allowed: >= 0 and <= 100");
  EXPECT_EQ(where(l.errors[2].loc), loc_at(c.line, 17));
  EXPECT_EQ(l.errors[2].message, "card.pacer_divisor must be a whole number");
  EXPECT_EQ(where(l.errors[3].loc), loc_at(d.line, 14));
  EXPECT_EQ(l.errors[3].message, "pins.c.invert_dir must be true or false");
}

TEST(SettingsLoad, EveryCrossKeyErrorIsReported) {
  Edited e = set_key("axes.y", "min", "18.0");
  e = set_key(e.text, "axes.z", "max_speed", "100.0");
  e = set_key(e.text, "pins.b", "dir_bit", "0");
  e = set_key(e.text, "speeds.move", "a", "95.0");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 4u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "axes.y.min (18) must be below axes.y.max (18)");
  EXPECT_EQ(l.errors[1].message.rfind("axes.z.max_speed 100 x steps_per_unit 1018.5916 = 101859 "
                                      "steps/s exceeds",
                                      0),
            0u)
      << l.errors[1].message;
  EXPECT_EQ(l.errors[2].message, "pins.b.dir_bit: output bit 0 is already used by another pin");
  EXPECT_EQ(l.errors[3].message, "speeds.move.a = 95 exceeds the axis max_speed 90");
}

TEST(SettingsLoad, CrossKeyRulesWaitUntilEveryKeyIsValid) {
  // The rules across keys are not checked on fallback values: only the key error shows.
  Edited e = set_key("axes.x", "min", "30.0");
  e = set_key(e.text, "axes.y", "max_accel", "\"slow\"");
  const SettingsLoad l = load(e.text);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(l.errors[0].message, "axes.y.max_accel must be a number");
}

// ---- files

TEST(LoadSettingsFile, MissingFileIsOneErrorNamingIt) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/tests/data/no_such_profile.toml";
  const SettingsLoad l = load_settings_file(path);
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_EQ(where(l.errors[0].loc), path + ":0:0");
  EXPECT_EQ(l.errors[0].message,
            "cannot open the settings file; check the path (--profile) and its permissions");
  EXPECT_FALSE(l.ok());
}

TEST(LoadSettingsFile, DirectoryIsAnUnreadableFile) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/tests/data";
  const SettingsLoad l = load_settings_file(path);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(where(l.errors[0].loc), path + ":0:0");
  EXPECT_EQ(l.errors[0].message,
            "cannot open the settings file; check the path (--profile) and its permissions");
}

TEST(LoadSettingsFile, ReportsErrorsWithThePath) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/tests/data/bad_value.toml";
  const SettingsLoad l = load_settings_file(path);
  ASSERT_EQ(l.errors.size(), 1u) << messages(l);
  EXPECT_EQ(where(l.errors[0].loc), path + ":13:13");
  EXPECT_EQ(l.errors[0].message,
            "axes.x.max_speed = -8 is out of range; allowed: > 0 and <= 100000");
}

}  // namespace
}  // namespace gantry
