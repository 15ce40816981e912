// `gantry import-wincnc` (docs/hardware.md, "Importing a WinCNC set-up"): the WinCNC
// manual's own examples (tests/data/wincnc/manual: its axis blocks, probe, enable, limits,
// homing, CNC.MAC and CNCSCRN.INI lines) read into a profile that is compared with a golden
// one, checked value by value against the manual's numbers, loaded, and run on the simulated
// card; every keyword it cannot map is listed with its file and line; bad input is located.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "gantry/core/text_file.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/session/key_bindings.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/settings/wincnc_import.hpp"
#include "import_wincnc.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;
const fs::path kData = fs::path(GANTRY_SOURCE_DIR) / "tests/data/wincnc/manual";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The manual's files, named as a user in their folder would name them.
WincncSources manual() {
  WincncSources in;
  in.ini = {"WINCNC.INI", slurp(kData / "WINCNC.INI")};
  in.screen = WincncFile{"CNCSCRN.INI", slurp(kData / "CNCSCRN.INI")};
  in.macros = WincncFile{"CNC.MAC", slurp(kData / "CNC.MAC")};
  in.name = "manual";
  return in;
}

WincncImport import_text(const std::string& ini) {
  WincncSources in;
  in.ini = {"WINCNC.INI", ini};
  return import_wincnc(in);
}

// A golden file: equal, or the output is left beside the temporary folder to compare.
void expect_golden(const std::string& got, const char* name) {
  const std::string want = slurp(kData / name);
  if (got == want) return;
  const fs::path out = fs::temp_directory_path() / (std::string("gantry_wincnc_") + name);
  std::ofstream(out, std::ios::binary) << got;
  ADD_FAILURE() << name << " differs from the golden file; this run's is " << out.string();
}

const WincncUnmapped* find(const WincncImport& r, std::string_view keyword) {
  for (const WincncUnmapped& u : r.unmapped)
    if (u.keyword == keyword) return &u;
  return nullptr;
}

TEST(WincncImport, TheManualsExamplesGiveTheGoldenProfileAndReport) {
  const WincncSources in = manual();
  const WincncImport r = import_wincnc(in);
  ASSERT_TRUE(r.ok()) << format(r.errors[0]);
  expect_golden(wincnc_profile_text(r, in), "profile.toml");
  expect_golden(wincnc_report(r), "report.txt");
}

// The numbers, worked out by hand from the manual's lines (units/min / 60 = units/s).
TEST(WincncImport, TheManualsNumbersLandInTheirKeys) {
  const WincncImport r = import_wincnc(manual());
  ASSERT_TRUE(r.ok()) << format(r.errors[0]);
  const Settings& s = r.settings;
  EXPECT_EQ(s.units, Units::Inches);
  EXPECT_EQ(s.card.type, "pci7200");
  EXPECT_EQ(s.gcode_dialect, GcodeDialect::WinCNC);
  EXPECT_EQ(s.display.axes, 4);  // X Y Z and W on A
  EXPECT_EQ(s.display.w_axis, 3);
  EXPECT_EQ(axis_names(s), "XYZWBC");
  // axisspec = p0 s0 d0 r818.5111 a400; axisvel = r450 f100 ...
  EXPECT_DOUBLE_EQ(s.axes[0].steps_per_unit, 818.5111);
  EXPECT_DOUBLE_EQ(s.axes[0].max_accel, 400.0 / 60);
  EXPECT_DOUBLE_EQ(s.axes[0].max_speed, 450.0 / 60);  // below maxstepv 50000 / 818.5
  EXPECT_DOUBLE_EQ(s.speeds.move.xy, 100.0 / 60);
  EXPECT_DOUBLE_EQ(s.speeds.jog.xy, 450.0 / 60);
  EXPECT_DOUBLE_EQ(s.axes[2].steps_per_unit, 400);
  EXPECT_DOUBLE_EQ(s.axes[2].max_speed, 250.0 / 60);
  EXPECT_DOUBLE_EQ(s.speeds.move.z, 50.0 / 60);
  // W: a150 f... the lower of A200 and F150; backlash .002; Home/End jog it (K4).
  EXPECT_DOUBLE_EQ(s.axes[3].max_accel, 150.0 / 60);
  EXPECT_DOUBLE_EQ(s.axes[3].backlash, 0.002);
  EXPECT_EQ(s.display.rotary_units[0], AxisUnit::Inches);
  // Step bits S and direction bits 8 + D; O1 (the default) and O0.
  EXPECT_EQ(s.pins[1].step_bit, 1);
  EXPECT_EQ(s.pins[1].dir_bit, 9);
  EXPECT_TRUE(s.pins[1].invert_dir);
  // altaxisspec = p0 s4 d4 o0: Y's second motor on the free channel 6 (C).
  EXPECT_EQ(s.drivers.channel_axis[5], 1);
  EXPECT_EQ(s.pins[5].step_bit, 4);
  EXPECT_EQ(s.pins[5].dir_bit, 12);
  EXPECT_FALSE(s.pins[5].invert_dir);
  // Limits: port P bit B is input bit 8 P + B (X p2 b6, b7; Z p3 b2, b3; W p2 b4).
  EXPECT_EQ(s.inputs.min_bit[0], 22);
  EXPECT_EQ(s.inputs.max_bit[0], 23);
  EXPECT_EQ(s.inputs.min_bit[2], 26);
  EXPECT_EQ(s.inputs.max_bit[2], 27);
  EXPECT_EQ(s.inputs.max_bit[3], 20);
  EXPECT_TRUE(s.inputs.limits_active_low);  // X's o1, the first limit line
  EXPECT_TRUE(s.limits.travel_only);        // lim_mode=1
  EXPECT_EQ(s.limits.debounce, 10);         // lim_cnt=10
  // The probe on pin 10: auxin=c1p3b7 (bit 31), scan C1; the enable on c2; c3 aborts.
  EXPECT_EQ(s.inputs.probe_bit, 31);
  EXPECT_EQ(s.inputs.switch_bits[0], 31);
  EXPECT_EQ(s.inputs.estop_bit, 30);
  EXPECT_TRUE(s.inputs.estop_active_low);
  EXPECT_EQ(s.switches.input_modes[2], 3);
  // Soft limits: lolim X-.4, hilim X96 Z.4 W.4; Z and W keep the default travel below.
  EXPECT_DOUBLE_EQ(s.axes[0].min, -0.4);
  EXPECT_DOUBLE_EQ(s.axes[0].max, 96);
  EXPECT_DOUBLE_EQ(s.axes[3].max, 0.4);
  EXPECT_LT(s.axes[3].min, s.axes[3].max);
  EXPECT_TRUE(s.machine.limit_checking);                // softlim t1
  EXPECT_EQ(s.limits.soft_clamp, SoftClamp::Vertical);  // softlim v1
  EXPECT_EQ(s.limits.cushion_steps, 100);               // lim_step=100
  EXPECT_EQ(s.limits.esc_steps, 200);                   // esc_step=200
  // G28: Z and W first (the first g28move line), up; X and Y down; zero .5 inside each switch.
  EXPECT_EQ(s.homing.order, "zaxy");
  EXPECT_EQ(s.homing.direction[3], 1);
  EXPECT_EQ(s.homing.direction[0], -1);
  EXPECT_DOUBLE_EQ(s.homing.at[0], -0.5);
  EXPECT_DOUBLE_EQ(s.homing.at[2], 0.5);
  EXPECT_DOUBLE_EQ(s.homing.fast_speed, 100.0 / 60);
  EXPECT_DOUBLE_EQ(s.homing.slow_speed, 10.0 / 60);
  EXPECT_DOUBLE_EQ(s.homing.back_off, 0.25);
  EXPECT_DOUBLE_EQ(s.homing.square_offset[1], 0.03);  // g28altmove=Y.03
  // g28move X.5 Y.5, Z.5 W.5: homing ends .5 off each switch, at zero.
  EXPECT_EQ(s.homing.offset[0], 0.5);
  EXPECT_EQ(s.homing.offset[3], 0.5);
  EXPECT_EQ(s.homing.debounce, 20);  // g28_lim_cnt=20
  // enab=c2 ... t1 a"XYZW": X, Y, Z and W (on A) to home again after the E-stop mid-motion.
  EXPECT_EQ(s.homing.require, 0b1111u);
  // G28 homes each axis on its limit switch of the homing side: Z and W up (axishi p3 b3, p2
  // b4 o0), Y down (axislo p3 b0 o0), each made an input switch after the auxin ones; X's
  // reads 0 when closed (o1), which an input switch cannot: listed.
  EXPECT_EQ(s.homing.axis_input[2], 4);
  EXPECT_EQ(s.inputs.switch_bits[3], 27);
  EXPECT_EQ(s.homing.axis_input[3], 5);
  EXPECT_EQ(s.inputs.switch_bits[4], 20);
  EXPECT_EQ(s.homing.axis_input[1], 6);
  EXPECT_EQ(s.inputs.switch_bits[5], 24);
  EXPECT_EQ(s.homing.axis_input[0], 0);
  EXPECT_NE(find(r, "g28move (x)"), nullptr);
  // override=E1 L10 H150
  EXPECT_EQ(s.feed_override.min, 10);
  EXPECT_EQ(s.feed_override.max, 150);
  // Outputs on port 7: c1 b7, c2 b6 -> bits 31, 30.
  ASSERT_EQ(s.outputs.aux_bits.size(), 2u);
  EXPECT_EQ(s.outputs.aux_bits[0], 31);
  EXPECT_EQ(s.outputs.aux_bits[1], 30);
  EXPECT_DOUBLE_EQ(s.spindle.max_rpm, 24000);
  // Keys: W on Home/End (K4), CTRL+F1/F2 on the pendant's macros; the XHC's key 1 and 2
  // (CNCSCRN.INI's UserBtns, ScanOn 1 and 2) are macros 1 and 2; CNC.MAC's M3 is C102.
  EXPECT_EQ(s.pendant.macros[0], "G28");
  EXPECT_EQ(s.pendant.macros[1], "C102");
  EXPECT_EQ(s.pendant.macros[2], "G28");
  EXPECT_EQ(s.pendant.macros[3], "C102");
  const std::vector<std::string> keys = {"Home = jog a+", "End = jog a-", "Ctrl+F1 = macro 3",
                                         "Ctrl+F2 = macro 4"};
  EXPECT_EQ(s.pendant.keys, keys);
  std::vector<session::KeyBindings::Problem> problems;
  session::KeyBindings::parse(s.pendant.keys, &problems);
  EXPECT_TRUE(problems.empty());
  // CNC.MAC: M1, M2, M3 as C100-C102; M5=[ (disabled) is listed.
  ASSERT_EQ(r.macros.size(), 3u);
  EXPECT_EQ(r.macros[2].name, "M3");
  EXPECT_EQ(r.macros[2].cut, 102);
  EXPECT_EQ(r.macros[2].file, "SPIN.MAC");
  EXPECT_EQ(
      wincnc_macro_cut(r.macros[0])
          .substr(
              wincnc_macro_cut(r.macros[0]).rfind('\n', wincnc_macro_cut(r.macros[0]).size() - 2) +
              1),
      "M11C2\n");
  ASSERT_NE(find(r, "M5=["), nullptr);
  EXPECT_EQ(find(r, "M5=[")->loc.line, 4);
}

// Every keyword the manual documents that has no key is listed with its file and line, and
// why.
TEST(WincncImport, WhatItCannotMapIsListedWithFileAndLine) {
  const WincncImport r = import_wincnc(manual());
  ASSERT_TRUE(r.ok());
  struct Want {
    const char* keyword;
    const char* file;
    int line;
  };
  const Want wants[] = {
      {"axisvel S (X)", "WINCNC.INI", 12}, {"enab M", "WINCNC.INI", 48},
      {"spindle T1", "WINCNC.INI", 54},    {"atc1 O", "WINCNC.INI", 62},
      {"keypad", "WINCNC.INI", 61},        {"axishi O (W)", "WINCNC.INI", 29},
      {"\"Viewer\"", "CNCSCRN.INI", 4},    {"\"JobCmd\"", "CNCSCRN.INI", 14},
  };
  for (const Want& w : wants) {
    const WincncUnmapped* u = find(r, w.keyword);
    ASSERT_NE(u, nullptr) << w.keyword;
    if (w.line) {
      EXPECT_EQ(*u->loc.file, w.file) << w.keyword;
      EXPECT_EQ(u->loc.line, w.line) << w.keyword;
    }
    EXPECT_FALSE(u->why.empty()) << w.keyword;
  }
  // Y's and Z's limits are o0 where X's are o1: Gantry has one polarity, and says so.
  EXPECT_NE(find(r, "axislo O (Y)"), nullptr);
  const std::string report = wincnc_report(r);
  EXPECT_NE(report.find("WINCNC.INI:54: spindle T1"), std::string::npos);
  // Mapped since the cushioned stop, the clamp, the homing debounce and the override bounds
  // landed: not listed.
  for (const char* k : {"lim_step=100", "esc_step=200", "softlim V1", "g28_lim_cnt=20",
                        "g28_lim_cnt", "override", "lim_mode=1"})
    EXPECT_EQ(find(r, k), nullptr) << k;
}

// The limit and homing keys issue 28 added, each from its WINCNC.INI line: lim_mode 2 and 3
// (0 and 1 with a shorter release debounce, which has nothing to act on here), a later
// g28move line's speeds and search length for its own axes, g28coord's park positions (an
// all-zero line is not used), g28_lim_cnt at most 30, override's bounds; g28move A, override
// E0 and its inputs listed.
TEST(WincncImport, LimitHomingAndOverrideKeysMap) {
  const std::string head =
      "unit=IN\naxischar=XYZ\naxisspec=p0 s0 d0 r1000 a400\naxisspec=p0 s1 d1 r1000 a400\n"
      "axisspec=p0 s2 d2 r1000 a200 t3\nlolim=X0 Y0\nhilim=X48 Y24 Z0\n";
  for (const auto& [mode, travel] : {std::pair{2, false}, std::pair{3, true}}) {
    const WincncImport r = import_text(head + fmt::format("lim_mode={}\n", mode));
    ASSERT_TRUE(r.ok()) << format(r.errors[0]);
    EXPECT_EQ(r.settings.limits.travel_only, travel) << mode;
    EXPECT_EQ(find(r, fmt::format("lim_mode={}", mode)), nullptr);
  }
  const WincncImport r = import_text(
      head +
      "g28move=Z.25 F60 T6 R.2\ng28move=X.5 Y1 F120 T12 R.3 L50 A1\ng28coord=X10 Y5 Z0\n"
      "g28_lim_cnt=45\noverride=E0 L25 H120 D3 U4\n");
  ASSERT_TRUE(r.ok()) << format(r.errors[0]);
  const Settings& s = r.settings;
  EXPECT_DOUBLE_EQ(s.homing.fast_speed, 1.0);  // the first line's: [homing]
  EXPECT_DOUBLE_EQ(*s.homing.fast[0], 2.0);    // the second line's: X's and Y's own
  EXPECT_DOUBLE_EQ(*s.homing.slow[1], 0.2);
  EXPECT_DOUBLE_EQ(*s.homing.retract[0], 0.3);
  EXPECT_DOUBLE_EQ(*s.homing.search[1], 50);
  EXPECT_FALSE(s.homing.fast[2]);
  EXPECT_FALSE(s.homing.search[2]);
  EXPECT_DOUBLE_EQ(*s.homing.offset[1], 1.0);
  EXPECT_DOUBLE_EQ(*s.homing.park[0], 10);
  EXPECT_DOUBLE_EQ(*s.homing.park[1], 5);
  EXPECT_DOUBLE_EQ(*s.homing.park[2], 0);
  EXPECT_EQ(s.homing.debounce, 30);  // at most 30, as lim_cnt
  EXPECT_EQ(s.feed_override.min, 25);
  EXPECT_EQ(s.feed_override.max, 120);
  for (const char* k : {"g28move A", "override E0", "override D", "override U"}) {
    const WincncUnmapped* u = find(r, k);
    ASSERT_NE(u, nullptr) << k;
  }
  EXPECT_NE(find(r, "g28move A")->why.find("homing.<axis>.input"), std::string::npos);
  // "not used if all positions are zero"
  const WincncImport zero = import_text(head + "g28coord=X0 Y0 Z0\n");
  ASSERT_TRUE(zero.ok());
  for (int i = 0; i < kAxisCount; ++i) EXPECT_FALSE(zero.settings.homing.park[i]);
  // A park outside the soft limits: the profile's rule, located at the key.
  const WincncImport out = import_text(head + "g28coord=X60\n");
  ASSERT_FALSE(out.ok());
  EXPECT_NE(format(out.errors[0]).find("homing.x.park"), std::string::npos)
      << format(out.errors[0]);
}

// The tool changer's and the spindle's lines (atc1, g37, spindle, da, pwm at the manual's
// file's end): what Gantry has lands in its keys, the rest is listed with its line.
TEST(WincncImport, TheToolChangerAndSpindleLinesLandInTheirKeys) {
  const WincncImport r = import_wincnc(manual());
  ASSERT_TRUE(r.ok());
  const Settings& s = r.settings;
  EXPECT_DOUBLE_EQ(s.toolchanger.slot_z, 2);     // atc1=H2
  EXPECT_TRUE(s.toolchanger.slots.empty());      // the Tool Positions are not in the INI
  EXPECT_DOUBLE_EQ(s.toolchanger.sensor_x, 10);  // g37=X10 Y40 ... F30
  EXPECT_DOUBLE_EQ(s.toolchanger.sensor_y, 40);
  EXPECT_DOUBLE_EQ(s.toolchanger.sensor_speed, 0.5);
  EXPECT_EQ(s.toolchanger.sensor_input, 0);
  EXPECT_DOUBLE_EQ(s.spindle.pwm_hz, 75);      // pwm=F75 M100
  EXPECT_DOUBLE_EQ(s.spindle.initial_rpm, 0);  // spindle I0 wins over da I5
  struct Want {
    const char* keyword;
    int line;
  };
  for (const Want& w : {Want{"spindle T1", 54}, Want{"atc1 O", 62}, Want{"atc1 Z", 62},
                        Want{"g37 D", 68}, Want{"g37 I", 68}, Want{"g37 J", 68}, Want{"da I", 69},
                        Want{"da T", 69}, Want{"da R", 69}, Want{"atc2", 71}}) {
    const WincncUnmapped* u = find(r, w.keyword);
    ASSERT_NE(u, nullptr) << w.keyword;
    EXPECT_EQ(u->loc.line, w.line) << w.keyword;
  }
  EXPECT_EQ(find(r, "pwm M"), nullptr);  // M100: Gantry's own top duty
  // da's start voltage as a share of its top one, without spindle I; T3, the frequency output.
  const WincncImport d =
      import_text("axischar=XYZ\nspindle=T3 R20000\nda=V10 I2.5\npwm=F100 M80\n");
  ASSERT_TRUE(d.ok());
  EXPECT_DOUBLE_EQ(d.settings.spindle.initial_rpm, 5000);
  EXPECT_EQ(d.settings.spindle.speed_mode, SpindleSettings::SpeedMode::Frequency);
  ASSERT_NE(find(d, "pwm M"), nullptr);
  const WincncImport bad = import_text("axischar=XYZ\nda=V5 I7\n");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(format(bad.errors[0]), "WINCNC.INI:2:7: error: da I7 is above its top voltage V5");
}

// The profile written loads as --profile reads it and runs on the simulated card: W moves
// the A channel, X steps at 818.5111 a unit.
TEST(WincncImport, TheProfileItWritesLoadsAndRuns) {
  const WincncSources in = manual();
  const WincncImport r = import_wincnc(in);
  ASSERT_TRUE(r.ok());
  SettingsLoad load = parse_settings(wincnc_profile_text(r, in), "manual.toml");
  ASSERT_TRUE(load.ok()) << format(load.errors[0]);
  Settings s = load.settings;
  s.card.type = "sim";
  s.outputs.charge_pump_bit = -1;
  SimCard card(s, false, {});
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{s, card, io, store};
  const Outcome o = c.run(Script::from_text("G90\nG0 X1 W-0.5\n", "part.tap"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : " " + o.errors[0].message);
  c.wait();
  EXPECT_EQ(c.status().state, MachineState::Idle) << c.status().message;
  EXPECT_EQ(card.steps()[0], std::llround(818.5111));
  EXPECT_EQ(card.steps()[3], std::llround(-0.5 * 400));
  EXPECT_EQ(card.steps()[5], std::llround(0.0));  // Y's second motor: Y did not move
  EXPECT_EQ(card.timing_violations(), 0u);
}

// unit=CM: the profile is in millimetres, every length and speed times 10.
TEST(WincncImport, CentimetresBecomeMillimetres) {
  const WincncImport r = import_text(
      "unit=CM\naxischar=XYZ\naxisspec=p0 s0 d0 r400 a600\naxisvel=r300 f120\n"
      "axisspec=p0 s1 d1 r400 a600\naxisvel=r300 f120\naxisspec=p0 s2 d2 r800 a300 t3\n"
      "hilim=X240 Y120\n");
  ASSERT_TRUE(r.ok()) << format(r.errors[0]);
  EXPECT_EQ(r.settings.units, Units::Millimetres);
  EXPECT_DOUBLE_EQ(r.settings.axes[0].steps_per_unit, 40);  // 400 a cm
  EXPECT_DOUBLE_EQ(r.settings.axes[0].max_speed, 50);       // 300 cm/min
  EXPECT_DOUBLE_EQ(r.settings.axes[0].max_accel, 100);      // 600 cm/min/s
  EXPECT_DOUBLE_EQ(r.settings.speeds.move.xy, 20);
  EXPECT_DOUBLE_EQ(r.settings.axes[0].max, 2400);
  EXPECT_EQ(r.settings.display.w_axis, -1);
}

// Bad input: each problem at its file, line and column, all of them at once.
TEST(WincncImport, BadInputIsLocated) {
  struct Case {
    const char* ini;
    int line, column;
    const char* says;
  };
  const Case cases[] = {
      {"axischar=XYZ\nthis line has no equals\n", 2, 1, "expected keyword=value"},
      {"axischar=XYZ\nlimstep=100\n", 2, 1, "unknown keyword limstep="},
      {"axischar=XYZ\naxisspec = p0 s7 d0 r818\n", 2, 15, "axisspec S7 is out of range"},
      {"axischar=XYZ\naxisspec = p0 s0 d0 r818 q4\n", 2, 26, "axisspec has no parameter Q"},
      {"axischar=XYZ\naxisspec = p0 s0 d0 rx\n", 2, 21, "R needs a number"},
      {"axischar=XYZ\nlim_mode=7\n", 2, 10, "lim_mode=7 is out of range"},
      {"axischar=XYZ\nunit=MM\n", 2, 1, "unit= must be the first line"},
      {"axischar=ZXY\n", 1, 10, "must name X first and Y second"},
      {"axisvel=r100\n", 1, 1, "comes before the first axisspec"},
      {"axischar=XY\naxisspec=p0 s0 d0 r1\naxisspec=p0 s0 d1 r1\n", 3, 13,
       "step bit 0 is already another motor's"},
      {"axischar=XYZ\nenab=c4 t1\n", 2, 6, "no auxin= line defines input channel 4"},
  };
  for (const Case& c : cases) {
    const WincncImport r = import_text(c.ini);
    ASSERT_FALSE(r.ok()) << c.ini;
    const Diagnostic& d = r.errors[0];
    EXPECT_EQ(*d.loc.file, "WINCNC.INI") << c.ini;
    EXPECT_EQ(d.loc.line, c.line) << c.ini << ": " << d.message;
    EXPECT_EQ(d.loc.column, c.column) << c.ini << ": " << d.message;
    EXPECT_NE(d.message.find(c.says), std::string::npos) << c.ini << ": " << d.message;
  }
  // CNCSCRN.INI and CNC.MAC too.
  WincncSources in;
  in.ini = {"WINCNC.INI", "axischar=XYZ\n"};
  in.screen = WincncFile{"CNCSCRN.INI", "\"Button\", 1, 2\nUserBtn, 1\n"};
  in.macros = WincncFile{"CNC.MAC", "M1 = M11C2\nSPINDLE ON\n"};
  const WincncImport r = import_wincnc(in);
  ASSERT_EQ(r.errors.size(), 3u);
  EXPECT_EQ(format(r.errors[0]).substr(0, 16), "CNCSCRN.INI:1:1:");
  EXPECT_NE(r.errors[0].message.find("unknown record \"Button\""), std::string::npos);
  EXPECT_EQ(r.errors[1].loc.line, 2);
  EXPECT_EQ(format(r.errors[2]).substr(0, 12), "CNC.MAC:2:1:");
}

// The command: a missing file is an error that names it and writes nothing; the manual's
// set-up writes the profile, the custom cuts and the subprogram they call.
TEST(WincncImport, TheCommandWritesTheProfileAndTheCustomCuts) {
  const fs::path dir = fs::temp_directory_path() / ("gantry_import_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  ImportWincncArgs a;
  a.ini = (dir / "missing.ini").string();
  a.output = (dir / "p.toml").string();
  EXPECT_EQ(run_import_wincnc(a), 1);
  EXPECT_FALSE(fs::exists(a.output));
  // A bad line: nothing written either.
  std::ofstream(dir / "bad.ini") << "axischar=XYZ\nlim_mode=9\n";
  a.ini = (dir / "bad.ini").string();
  EXPECT_EQ(run_import_wincnc(a), 1);
  EXPECT_FALSE(fs::exists(a.output));
  for (const char* f : {"WINCNC.INI", "CNCSCRN.INI", "CNC.MAC", "SPIN.MAC"})
    fs::copy_file(kData / f, dir / f);
  a.ini = (dir / "WINCNC.INI").string();
  a.screen = (dir / "CNCSCRN.INI").string();
  ASSERT_EQ(run_import_wincnc(a), 0);
  const SettingsLoad load = load_settings_file(a.output);
  ASSERT_TRUE(load.ok()) << format(load.errors[0]);
  EXPECT_EQ(load.settings.name, "p");
  EXPECT_EQ(load.settings.display.w_axis, 3);
  for (const char* f : {"C100.sbp", "C101.sbp", "C102.sbp", "SPIN.MAC"})
    EXPECT_TRUE(fs::exists(dir / "macros" / f)) << f;
  const std::optional<std::string> cut = read_text_file((dir / "macros/C102.sbp").string());
  ASSERT_TRUE(cut);
  EXPECT_NE(cut->find("\nM98 SPIN.MAC\n"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gantry
