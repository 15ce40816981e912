// The V commands and the settings commands that change values: their fields, their scope
// (for good, or until the part file ends), their errors, and the values file.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "../support/interpreter_fixture.hpp"
#include "gantry/commands/values_sheets.hpp"
#include "gantry/core/text_file.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/system_variables.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/job.hpp"
#include "gantry/settings/settings_schema.hpp"
#include "gantry/settings/values_file.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

// A folder of part files for FP, removed at the end.
struct TempDir {
  fs::path path = fs::temp_directory_path() / ("gantry_values_" + std::to_string(getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

class ValuesTest : public KeptInterpreterFixture {
 protected:
  void run(const std::string& text) {
    const std::string file = dir.write("part.sbp", text);
    interp().run(Script::load(file));
  }
  Diagnostic run_error(const std::string& text) {
    try {
      run(text);
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    ADD_FAILURE() << "no error from:\n" << text;
    return {};
  }
  const Settings& values() { return interp().settings(); }
  ~ValuesTest() override { interp_.reset(); }  // the interpreter ends before its folder goes

  TempDir dir;
};

// ---- scope: permanent values, file-scoped values, SV

TEST_F(ValuesTest, VcValuesStayAfterTheFile) {
  run("VC, .5, , , 1.5, -, 20, 2\n");
  EXPECT_DOUBLE_EQ(values().cutter.diameter, .5);
  EXPECT_DOUBLE_EQ(values().cutter.safe_z, 1.5);
  EXPECT_DOUBLE_EQ(values().cutter.pocket_overlap, 20);
  EXPECT_DOUBLE_EQ(values().cutter.safe_a, 2);
  EXPECT_DOUBLE_EQ(interp().snapshot().cutter_diameter, .5);
}

TEST_F(ValuesTest, MhRisesToTheSafeZThatVcSet) {
  run("VC, , , , 2.5\nMZ, -0.5\nMX, 3\nMH\n");
  const std::vector<CanonMove>& m = sink.moves;
  ASSERT_GE(m.size(), 4u);
  EXPECT_DOUBLE_EQ(m[2].to[2], 2.5);  // up to safe Z first
  EXPECT_DOUBLE_EQ(m[3].to[0], 0);
}

// Handbook: VS, VU, VI, VL and SF made in a file revert when it ends, unless SV.
TEST_F(ValuesTest, VlAndSfRevertWhenTheFileEnds) {
  run("VL, -1, 30, , , , , , , 0\n");
  EXPECT_DOUBLE_EQ(values().axes[0].min, 0);
  EXPECT_DOUBLE_EQ(values().axes[0].max, 24);
  EXPECT_TRUE(values().machine.limit_checking);
  run("SF, 0\nMX, 30\n");  // inside the file the check is off: the move runs
  EXPECT_DOUBLE_EQ(sink.moves.back().to[0], 30);
  EXPECT_TRUE(values().machine.limit_checking);
}

TEST_F(ValuesTest, SvKeepsTheFilesValues) {
  run("VL, -1, 30\nVS, 3\nSV\nVU, 1000\n");
  EXPECT_DOUBLE_EQ(values().axes[0].min, -1);
  EXPECT_DOUBLE_EQ(values().axes[0].max, 30);
  EXPECT_DOUBLE_EQ(state().speeds.move.xy, 3);
  EXPECT_DOUBLE_EQ(values().axes[0].steps_per_unit, 916.7324);  // after SV: reverted
}

TEST_F(ValuesTest, ANestedFilesLimitsRevertWhenItEnds) {
  dir.write("inner.sbp", "VL, , 10\n");
  run("FP, inner.sbp\nMX, 20\n");  // the profile's 24 is back for the caller
  EXPECT_DOUBLE_EQ(sink.moves.back().to[0], 20);
  const Diagnostic d = run_error("VL, , 10\nMX, 15\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_NE(d.message.find("outside the soft limits 0.0000 to 10.0000"), std::string::npos)
      << d.message;
}

// ---- VU and VR reach the motion stream at rest

TEST_F(ValuesTest, VuSendsTheNewCalibrationDownAfterAStop) {
  run("MX, 1\nVU, 2000, , -1000\nMX, 2\n");
  ASSERT_EQ(sink.changes.size(), 2u);  // the change, then the revert at the file's end
  EXPECT_DOUBLE_EQ(sink.changes[0].axes[0].steps_per_unit, 2000);
  EXPECT_DOUBLE_EQ(sink.changes[0].axes[2].steps_per_unit, -1000);  // negative: reversed
  EXPECT_DOUBLE_EQ(sink.changes[1].axes[0].steps_per_unit, 916.7324);
  EXPECT_EQ(sink.moves[1].kind, MoveKind::Stop);  // at rest before the change
}

TEST_F(ValuesTest, VrSetsTheRampsForGood) {
  run("VR, .5, .6, .7, .8, .9, 1, 1.1, 1.2, .3, .4, 90, .2, 50, , , .25, .1\n");
  const RampSettings& r = values().ramps;
  EXPECT_DOUBLE_EQ(r.move_ramp_speed.xy, .5);
  EXPECT_DOUBLE_EQ(r.move_ramp_speed.b, .8);
  EXPECT_DOUBLE_EQ(r.jog_ramp_speed.xy, .9);
  EXPECT_DOUBLE_EQ(r.jog_ramp_speed.b, 1.2);
  EXPECT_DOUBLE_EQ(r.move_ramp_rate, .3);
  EXPECT_DOUBLE_EQ(r.jog_ramp_rate, .4);
  EXPECT_DOUBLE_EQ(r.threshold_3d, 90);
  EXPECT_DOUBLE_EQ(r.min_distance, .2);
  EXPECT_DOUBLE_EQ(r.slow_corner, 50);
  EXPECT_DOUBLE_EQ(r.keypad_ramp_rate, .25);
  EXPECT_DOUBLE_EQ(r.small_circle, .1);
  ASSERT_EQ(sink.changes.size(), 1u);
  EXPECT_DOUBLE_EQ(sink.changes[0].ramps.slow_corner, 50);
}

// ---- errors: located, and nothing changes

TEST_F(ValuesTest, AValueOutOfRangeIsLocatedAndChangesNothing) {
  const Diagnostic d = run_error("VR, .5, -1\n");
  EXPECT_EQ(d.loc.line, 1);
  EXPECT_EQ(d.loc.column, 9);
  EXPECT_EQ(d.message, "VR parameter 2 (Z move ramp speed) is -1; allowed: 1e-06 to 100000");
  EXPECT_DOUBLE_EQ(values().ramps.move_ramp_speed.xy, .4);  // the good first value too
}

// A V command's range is its schema row's (issue 24): VB allowed any spacing >= 0 and VU
// steps per unit to 1e7, values the profile (and so the values file) refuses.
TEST_F(ValuesTest, VCommandRangesAreTheProfiles) {
  EXPECT_EQ(run_error("VB, , 0\n").message,
            "VB parameter 2 (tab spacing) is 0; allowed: 1e-06 to 1000000");
  EXPECT_EQ(run_error("VU, 5000000\n").message,
            "VU parameter 1 (X steps per unit) is 5000000; allowed: -1000000 to 1000000");
  EXPECT_EQ(run_error("VB, 20000\n").message,
            "VB parameter 1 (tab height) is 20000; allowed: 0 to 10000");
}

TEST_F(ValuesTest, ARuleOfTheProfileIsCheckedAcrossFields) {
  const Diagnostic d = run_error("VL, 10, 5\n");
  EXPECT_EQ(d.message,
            "VL would break a rule of the machine profile: axes.x.min (10) must be below "
            "axes.x.max (5); nothing was changed");
  EXPECT_DOUBLE_EQ(values().axes[0].min, 0);
  const Diagnostic fast = run_error("VU, 50000\n");  // 8 in/s x 50000 steps: beyond the card
  EXPECT_NE(fast.message.find("exceeds the card's"), std::string::npos) << fast.message;
}

TEST_F(ValuesTest, WordsAndWholeNumbersAreChecked) {
  EXPECT_EQ(run_error("VC, , , , , x\n").message,
            "VC parameter 5 (plunge direction) is 'x'; allowed: -, +, 0, 1 or -1");
  EXPECT_EQ(run_error("VD, , 3.5\n").message,
            "VD parameter 2 (number of axes) must be a whole number, not 3.5");
  run("VC, , , , , , , , , , , , , 4\n");  // past the last: ignored, as SB3 does
  ASSERT_EQ(io.warnings().size(), 1u);
  EXPECT_EQ(io.warnings()[0].message,
            "VC takes 12 parameters; parameter 13 and those after it are ignored, as SB3 ignores "
            "them");
  EXPECT_NE(run_error("VC, , , , , , , , , , , , 4\n").message.find("cannot be output 4"),
            std::string::npos);
}

TEST_F(ValuesTest, VhModeOneSaysWhatIsMissing) {
  EXPECT_NE(run_error("VH, 1\n").message.find("needs an accessory enabled first"),
            std::string::npos);
  EXPECT_NE(run_error("VN, , , 2\nVH, 1\n").message.find("no torch-height, laser-PWM"),
            std::string::npos);
  run("VH, 0, .3, 10, 80\n");
  EXPECT_DOUBLE_EQ(values().accessories.pwm_high, 80);
}

// ---- VD: units

TEST_F(ValuesTest, VdToMillimetresConvertsValuesAndTheLocation) {
  run("MX, 2\nVD, , , 1\n");
  EXPECT_EQ(values().units, Units::Millimetres);
  EXPECT_NEAR(values().axes[0].steps_per_unit, 916.7324 / 25.4, 1e-9);  // 12 digits kept
  EXPECT_NEAR(values().axes[0].max, 24 * 25.4, 1e-9);
  EXPECT_NEAR(values().cutter.safe_z, 25.4, 1e-12);
  EXPECT_NEAR(state().position[0], 50.8, 1e-12);
  EXPECT_NEAR(state().speeds.move.xy, 50.8, 1e-12);
  EXPECT_NEAR(values().axes[3].steps_per_unit, 13.8889, 1e-12);  // A in degrees: unchanged
  ASSERT_FALSE(sink.changes.empty());
  EXPECT_EQ(sink.changes[0].units, Units::Millimetres);
  // The tool stays put: the next move starts where the last one ended, in steps.
  run("MX, 60\n");
  EXPECT_NEAR(sink.moves.back().from[0] * values().axes[0].steps_per_unit, 2 * 916.7324, 1e-6);
}

// The NIST corpus files open with this header (shared/corpus/nist_metatest.sbp).
TEST_F(ValuesTest, TheNistHeaderRuns) {
  run("VD , , 1\nVU, 157.480315, 157.480315, -157.480315\nMS, 10, 10\nJS, 20, 20\n"
      "VR,10.06, 10.06, , , 10.06, 10.06, , , 5.08, 5.08, 100, 3.81, 65, , , 5.08\n"
      "VC, 6.35, , , 10, 0, 10, 0, 0, 0, 0, Z, 8\nMX, 100\n");
  EXPECT_EQ(values().units, Units::Millimetres);
  EXPECT_DOUBLE_EQ(values().ramps.move_ramp_speed.xy, 10.06);
  EXPECT_DOUBLE_EQ(values().cutter.diameter, 6.35);
  EXPECT_TRUE(values().cutter.plunge_negative);
  EXPECT_EQ(values().cutter.trigger_output, 8);
  EXPECT_NEAR(values().axes[0].steps_per_unit, 916.7324 / 25.4, 1e-9);  // VU reverted
  const CanonMove& last = sink.moves[sink.moves.size() - 2];  // then the stop for VU's revert
  EXPECT_EQ(last.kind, MoveKind::Line);
  EXPECT_DOUBLE_EQ(last.to[0], 100);
  EXPECT_DOUBLE_EQ(last.speeds.xy, 10);
}

// FabMo's stock macros: SU sets units until the file ends; CN runs a macro.
TEST_F(ValuesTest, SuLastsUntilTheFileEnds) {
  dir.write("metric.sbp", "SU, \"mm\"\nMX, 25.4\n&inner = %(25)\n");
  run("FP, metric.sbp\n&outer = %(25)\nMX, 2\n");
  EXPECT_EQ(values().units, Units::Inches);
  EXPECT_EQ(interp().variable("INNER")->num(), 1);
  EXPECT_EQ(interp().variable("OUTER")->num(), 0);
  // Each move in the units of its time, which the motion stream heard of just before.
  std::vector<double> x;
  for (const CanonMove& m : sink.moves)
    if (m.kind == MoveKind::Line) x.push_back(m.to[0]);
  ASSERT_EQ(x.size(), 2u);
  EXPECT_DOUBLE_EQ(x[0], 25.4);
  EXPECT_DOUBLE_EQ(x[1], 2);
  ASSERT_EQ(sink.changes.size(), 2u);
  EXPECT_EQ(sink.changes[0].units, Units::Millimetres);
  EXPECT_EQ(sink.changes[1].units, Units::Inches);
}

TEST_F(ValuesTest, CnRunsTheNumberedMacro) {
  dir.write("macro_75.sbp", "MX, 3\n");
  run("CN, 75\nMY, 1\n");
  ASSERT_EQ(sink.moves.size(), 2u);
  EXPECT_DOUBLE_EQ(sink.moves[0].to[0], 3);
  EXPECT_NE(run_error("CN, 8\n").message.find("no C8.sbp or macro_8.sbp"), std::string::npos);
}

// ---- locations: VA, ZT, UZ, ST

TEST_F(ValuesTest, VaSetsWorkingAndTableBaseWithoutMoving) {
  run("MX, 5\nVA, 1, , , , , 10\n");
  EXPECT_DOUBLE_EQ(state().position[0], 1);
  EXPECT_DOUBLE_EQ(interp().snapshot().table_base[0], 10);
  const size_t before = sink.moves.size();
  run("MX, 2\n");  // one unit further in the machine: from 5 to 6
  ASSERT_EQ(sink.moves.size(), before + 1);
  EXPECT_DOUBLE_EQ(sink.moves.back().from[0], 5);
  EXPECT_DOUBLE_EQ(sink.moves.back().to[0], 6);
}

TEST_F(ValuesTest, ZtMovesTheTableBaseAndItsLimits) {
  run("MX, 5\nZT\n");
  EXPECT_DOUBLE_EQ(state().position[0], 5);  // working value kept
  EXPECT_DOUBLE_EQ(interp().snapshot().table_base[0], 0);
  // The limits are in table base coordinates: 24 more units to the right are allowed now.
  run("MX, 25\n");
  EXPECT_DOUBLE_EQ(sink.moves.back().to[0], 25);
  EXPECT_NE(run_error("MX, 30\n").message.find("table base X=25"), std::string::npos);
}

TEST_F(ValuesTest, UzZerosBothAndStRemovesOffsets) {
  run("MX, 5\nMY, 3\nUZ\n");
  EXPECT_DOUBLE_EQ(state().position[0], 0);
  EXPECT_DOUBLE_EQ(interp().snapshot().table_base[0], 0);
  run("MX, 2\nZX\nST\n");
  EXPECT_DOUBLE_EQ(state().position[0], 2);
  EXPECT_DOUBLE_EQ(state().zero[0], 0);
}

// FabMo's `VA, 0,,,,,, 0` (X, then table base X) read in SB3's layout would set table base Y:
// the default dialect refuses it, and FabMo's reads it as FabMo does (spec commands.md §4.1).
// SB3's own files set one table base value with parameter 6 blank, so under SB3's dialect
// such a line is read in SB3's layout, and says so: a FabMo file is told to set the dialect.
TEST_F(ValuesTest, VaInFabmosLayoutIsReadAsSb3sAndSaysSoUnderTheSb3Dialect) {
  run("MX, 5\nMY, 3\nVA,0,,,,,,0\n");
  ASSERT_EQ(io.warnings().size(), 1u);
  EXPECT_EQ(io.warnings()[0].loc.line, 3);
  EXPECT_EQ(io.warnings()[0].loc.column, 11);  // parameter 7
  EXPECT_EQ(io.warnings()[0].message,
            "VA parameter 7 is read as table base Y in SB3's 10-value layout (this profile's "
            "dialect); in FabMo's 12-value one, which this line's blank parameter 6 suggests, it "
            "is table base X: set dialect = \"fabmo\" if this is a FabMo file");
  EXPECT_DOUBLE_EQ(state().position[0], 0);
  EXPECT_DOUBLE_EQ(interp().snapshot().table_base[1], 0);
  Diagnostic d;
  d = run_error("VA,1,2,3,4,5,6,7,8,9,10,11,12\n");
  EXPECT_EQ(d.loc.column, 25);
  EXPECT_EQ(d.message,
            "VA takes 10 parameters; this is parameter 11: SB3's VA has 10 values (X to B, then "
            "table base X to B) and FabMo's 12 (X to C, then table base X to C); set dialect = "
            "\"fabmo\" in the profile for FabMo's layout");
  run("VA, 1, , , , , 10\n");  // SB3's own layout still works
  EXPECT_DOUBLE_EQ(interp().snapshot().table_base[0], 10);
}

TEST_F(ValuesTest, VaInFabmosLayoutUnderTheFabmoDialect) {
  settings.dialect = Dialect::FabMo;
  run("MX, 5\nMY, 3\nVA,0,,,,,,0\n");
  EXPECT_DOUBLE_EQ(state().position[0], 0);
  EXPECT_DOUBLE_EQ(interp().snapshot().table_base[0], 0);
  EXPECT_DOUBLE_EQ(interp().snapshot().table_base[1], 3);
}

// ---- VO and SP/SM

TEST_F(ValuesTest, VoOffsetsMovesUntilOffAndTheLocationShowsIt) {
  run("VO, 1, .5, .25\nMX, 2\n");
  EXPECT_DOUBLE_EQ(sink.moves.back().to[0], 2.5);
  EXPECT_DOUBLE_EQ(sink.moves.back().to[1], .25);
  // The run ended: the offset is off, the next move goes to the plain location.
  run("MX, 3\n");
  EXPECT_DOUBLE_EQ(sink.moves.back().to[0], 3);
  EXPECT_DOUBLE_EQ(sink.moves.back().to[1], 0);
  run("VO, 1\nMY, 1\nVO, 2\nMY, 2\n");  // ON again uses the last values
  EXPECT_DOUBLE_EQ(sink.moves[sink.moves.size() - 2].to[1], 1.25);
  EXPECT_DOUBLE_EQ(sink.moves.back().to[1], 2);
}

TEST_F(ValuesTest, PreviewMovesNothingAndSmReturnsToTheTool) {
  run("MX, 1\nSP\nMX, 5\nSO, 1, 1\nMY, 3\nSM\nMY, 1\n");
  std::vector<CanonMove> lines;
  for (const CanonMove& m : sink.moves)
    if (m.kind == MoveKind::Line || m.kind == MoveKind::Output) lines.push_back(m);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_DOUBLE_EQ(lines[1].from[0], 1);
  EXPECT_DOUBLE_EQ(lines[1].to[1], 1);
}

// ---- FabMo's parameter orders

TEST_F(ValuesTest, FabmoOrdersForVsVlAndVa) {
  settings.dialect = Dialect::FabMo;
  run("VS, 1, .5, 5, 6, 7, 3, 2, 20, 21, 22\nMC, 1\nJC, 2\nVL, , , , , , , , , , , -5, 5\n"
      "SV\nVA, , , , , , 4\n");
  EXPECT_DOUBLE_EQ(sink.moves[0].speeds.c, 7);
  EXPECT_DOUBLE_EQ(sink.moves[1].speeds.c, 22);
  EXPECT_DOUBLE_EQ(values().axes[5].min, -5);
  EXPECT_DOUBLE_EQ(state().position[5], 4);
}

// ---- the values file

TEST(ValuesFile, HoldsOnlyWhatDiffersAndReadsBack) {
  const Settings profile = default_settings();
  Settings changed = profile;
  changed.cutter.diameter = .5;
  changed.speeds.move.xy = 3;
  const std::string text = values_text(changed, profile);
  EXPECT_NE(text.find("[cutter]\ndiameter = 0.5"), std::string::npos) << text;
  EXPECT_EQ(text.find("safe_z"), std::string::npos) << text;  // unchanged keys stay out
  const SettingsLoad l =
      parse_settings(default_profile_text(), "default.toml", text, "values.toml");
  ASSERT_TRUE(l.ok()) << format(l.errors.front());
  EXPECT_DOUBLE_EQ(l.settings.cutter.diameter, .5);
  EXPECT_DOUBLE_EQ(l.settings.speeds.move.xy, 3);
  EXPECT_EQ(values_text(l.settings, profile), text);
}

TEST(ValuesFile, EveryKeyOfAProfileRoundTrips) {
  const Settings s = default_settings();
  const SettingsLoad l = parse_settings(settings_text(s), "written.toml");
  ASSERT_TRUE(l.ok()) << format(l.errors.front());
  EXPECT_EQ(settings_text(l.settings), settings_text(s));
  EXPECT_EQ(values_text(l.settings, s).find('='), std::string::npos);  // nothing differs
}

TEST(ValuesFile, AnErrorNamesTheValuesFileAndLine) {
  const SettingsLoad l = parse_settings(default_profile_text(), "default.toml",
                                        "[cutter]\ndiameter = -1\n", "values.toml");
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_EQ(format(l.errors[0]),
            "values.toml:2:12: error: cutter.diameter = -1 is out of range; allowed: >= 0 and "
            "<= 10000");
}

// A run saves what it changed; a check never writes.
TEST(ValuesFile, ARunSavesTheValuesItChanged) {
  TempDir dir;
  const std::string part = dir.write("part.sbp", "VC, .375\nVS, 3\nMS, 1.5\nMX, 1\n");
  const std::string values = (dir.path / "values.toml").string();
  const Settings profile = default_settings();
  JobOptions opt;
  opt.values_path = values;
  opt.profile = &profile;
  PersistentStore store;
  ScriptedIO io(true, {});
  check_program(Script::load(part), profile, store, opt);
  EXPECT_FALSE(fs::exists(values));
  SimCard card(profile);
  const JobResult r = run_job(Script::load(part), profile, card, io, store, opt);
  ASSERT_TRUE(r.ok()) << format(r.errors.front());
  const std::optional<std::string> text = read_text_file(values);
  ASSERT_TRUE(text);
  EXPECT_NE(text->find("diameter = 0.375"), std::string::npos) << *text;
  EXPECT_NE(text->find("xy = 1.5"), std::string::npos) << *text;  // MS stays, VS reverted
  EXPECT_EQ(text->find("xy = 3"), std::string::npos) << *text;
}

// ---- VN output modes: on at a file's start, off at its end (docs/values.md)

std::vector<std::pair<int, bool>> switched(const std::vector<CanonMove>& moves) {
  std::vector<std::pair<int, bool>> out;
  for (const CanonMove& m : moves)
    if (m.kind == MoveKind::Output) out.emplace_back(m.output, m.output_on);
  return out;
}

TEST_F(ValuesTest, VnOutputModesSwitchOnAtTheStartAndOffAtTheEndOfAFile) {
  // Outputs 1-6 in modes 0-5; the file turns 1 and 2 on itself.
  settings.switches.output_modes = {0, 1, 2, 3, 4, 5, 0, 0, 0, 0, 0, 0};
  run("SO, 1, 1\nSO, 2, 1\nMX, 1\n");
  const std::vector<std::pair<int, bool>> expected = {
      {4, true},  {5, true},  {6, true},  // modes 3, 4, 5: on as the file starts
      {1, true},  {2, true},              // the file's SO lines
      {1, false}, {4, false}, {6, false}  // at the end: all but modes 1 and 4
  };
  EXPECT_EQ(switched(sink.moves), expected);
  EXPECT_EQ(sink.moves[0].loc.line, 1);
  EXPECT_EQ(state().outputs, (1u << 1) | (1u << 4));  // 2 (mode 1) and 5 (mode 4) stay on
}

TEST_F(ValuesTest, VnOutputModesSetByTheFileApplyAtItsEndAndAnUnwiredOneIsNamed) {
  settings.outputs.aux_bits[7] = -1;                                    // output 8 not wired
  run("VN, , , , , , , , , , , , , , , 1, , , , , , , 3\nSO, 1, 1\n");  // 1: mode 1, 8: mode 3
  EXPECT_TRUE(switched(sink.moves) == (std::vector<std::pair<int, bool>>{{1, true}}));
  EXPECT_EQ(state().outputs, 1u);  // mode 1: stays on
  sink.moves.clear();
  run("MX, 1\n");  // output 8 in mode 3 cannot come on
  ASSERT_EQ(io.warnings().size(), 1u);
  EXPECT_EQ(io.warnings()[0].loc.line, 1);
  EXPECT_NE(io.warnings()[0].message.find("output switch 8 should come on as the file starts"),
            std::string::npos)
      << io.warnings()[0].message;
  EXPECT_TRUE(switched(sink.moves).empty());
}

}  // namespace
}  // namespace gantry

// ---- the values sheets: where each setting is shown --------------------------------------

namespace gantry {
namespace {

// Every row of the schema is shown in a sheet (a V command's parameter, or the profile's rows
// a bare V command lists after its parameters) or belongs to a table of the machine's wiring
// read from the profile only: a new row (a new table) cannot be left out unnoticed.
TEST(ValuesSheets, EveryRowIsInASheetOrAProfileOnlyTable) {
  const std::span<const std::string_view> only = profile_only_tables();
  for (const SettingRow& row : settings_schema()) {
    const bool profile_only = std::find(only.begin(), only.end(), row.section) != only.end();
    EXPECT_TRUE(!sheet_of(row).empty() || profile_only)
        << row.path()
        << ": shown in no values sheet; add its table to kSheetRows "
           "(src/commands/values_display.cpp) or to kProfileOnly, and to docs/values.md";
  }
  // Each line of kSheetRows names rows that exist.
  for (const SheetRows& r : sheet_profile_rows()) {
    bool any = false;
    for (const SettingRow& row : settings_schema()) any = any || row.path().starts_with(r.prefix);
    EXPECT_TRUE(any) << r.code << " lists " << r.prefix << ", which no row starts with";
  }
}

// Issue 28's settings (the machines people own) are in the sheet of their subject.
TEST(ValuesSheets, IssueTwentyEightsSettingsAreInTheirSheets) {
  const std::pair<std::string_view, std::string_view> want[] = {
      {"limits.travel_only", "VL"},
      {"limits.debounce", "VL"},
      {"limits.cushion_steps", "VL"},
      {"limits.esc_steps", "VL"},
      {"limits.soft_clamp", "VL"},
      {"homing.order", "VL"},
      {"homing.require", "VL"},
      {"homing.debounce", "VL"},
      {"homing.<x..c>.direction", "VL"},
      {"homing.<x..c>.fast_speed", "VL"},
      {"homing.<x..c>.slow_speed", "VL"},
      {"homing.<x..c>.back_off", "VL"},
      {"homing.<x..c>.offset", "VL"},
      {"homing.<x..c>.search", "VL"},
      {"homing.<x..c>.square_input", "VL"},
      {"homing.<x..c>.square_offset", "VL"},
      {"homing.<x..c>.input", "VL"},
      {"homing.<x..c>.park", "VL"},
      {"axes.<x..c>.backlash", "VU"},
      {"axes.<x..c>.wrap", "VU"},
      {"drivers.channels", "VI"},  // slaved axes: a parameter of VI
      {"display.w_axis", "VD"},
      {"feed_override.min", "VS"},
      {"feed_override.max", "VS"},
  };
  for (const auto& [path, code] : want) EXPECT_EQ(sheet_of(setting_row(path)), code) << path;
  bool parameter = false;
  EXPECT_EQ(sheet_of(setting_row("drivers.channels"), &parameter), "VI");
  EXPECT_TRUE(parameter);
  EXPECT_EQ(sheet_of(setting_row("limits.debounce"), &parameter), "VL");
  EXPECT_FALSE(parameter);
  // Every key of [spindle] and [toolchanger], whatever keys they gain: the cutter's sheet.
  int machine = 0;
  for (const SettingRow& row : settings_schema())
    if (row.section == "spindle" || row.section == "toolchanger") {
      EXPECT_EQ(sheet_of(row), "VC") << row.path();
      ++machine;
    }
  EXPECT_GT(machine, 10);
}

// A bare VL lists, after its parameters, the limit and homing keys in force; a family on one
// line, over the axes in use, a key left out as "-".
TEST(ValuesSheets, ABareSheetListsItsProfileRows) {
  Settings s = default_settings();
  s.limits.debounce = 7;
  s.homing.park[2] = 1.5;
  s.feed_override.max = 150;
  const std::string vl = sheet_profile_lines("VL", s);
  EXPECT_NE(vl.find("set in the profile"), std::string::npos) << vl;
  EXPECT_NE(vl.find("limits.debounce "), std::string::npos) << vl;
  EXPECT_NE(vl.find("  7\n"), std::string::npos) << vl;
  const std::size_t park = vl.find("homing.<x..c>.park");
  ASSERT_NE(park, std::string::npos) << vl;
  const std::string line = vl.substr(park, vl.find('\n', park) - park);
  EXPECT_NE(line.find("x -  y -  z 1.5"), std::string::npos) << line;
  EXPECT_EQ(line.find(" a "), std::string::npos) << line;  // display.axes = 3
  EXPECT_NE(sheet_profile_lines("VS", s).find("feed_override.max  150"), std::string::npos);
  EXPECT_EQ(sheet_profile_lines("VA", s), "");
}

}  // namespace
}  // namespace gantry
