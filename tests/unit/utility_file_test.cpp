// The Utilities (UD UI UL UN UR US UU UV), FE, FS, FC, VV, VK and SC: what each prints,
// writes or changes, and their errors (located, nothing changed).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>    // llround
#include <cstdlib>  // unsetenv
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/temp_dir.hpp"
#include "gantry/commands/command_table.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/settings/values_file.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Each test gets its own folder; part.sbp runs from there.
class UtilityFileTest : public KeptInterpreterFixture {
 protected:
  UtilityFileTest() {
    options.profile = &profile;
    options.profile_path = "/profiles/desk.toml";
    options.values_path = "/config/values/desk.toml";
  }

  std::string path(const std::string& name) const { return (fs::path(dir_.path()) / name).string(); }
  std::string folder() const { return fs::path(dir_.path()).string(); }
  void write(const std::string& name, const std::string& text) const {
    fs::create_directories(fs::path(path(name)).parent_path());
    std::ofstream(path(name), std::ios::binary) << text;
  }
  void copy_data(const std::string& name) const {
    fs::copy_file(fs::path(GANTRY_SOURCE_DIR) / "tests/data/convert" / name, path(name));
  }

  // Runs `text` as part.sbp on a new interpreter; errors fail the test. The interpreter stays
  // for inspection.
  void run(const std::string& text) {
    fresh_interp();
    run_program(Script::from_text(text, path("part.sbp")));
  }

  // Runs `text` on a new interpreter expecting an error; returns it.
  Diagnostic run_error(const std::string& text) {
    auto script = Script::from_text(text, path("part.sbp"));
    fresh_interp();
    return program_error(script, text);
  }

 private:
  TempDir dir_{"utility_file_test"};
};

// ---- UL, VV, UU -----------------------------------------------------------------------------

TEST_F(UtilityFileTest, UlListsEveryVariableSortedWithTextQuoted) {
  run("UL\n&width = 12.5\n&Name = \"oak board\"\n&a = 2 + 1\nUL\n");
  EXPECT_EQ(printed,
            "No &variables are defined.\n"
            "&A = 3\n&NAME = \"oak board\"\n&WIDTH = 12.5\n");
  EXPECT_TRUE(sink.moves.empty());
}

TEST_F(UtilityFileTest, VvDefinesVariablesInPairs) {
  // The values are evaluated before any is set: &OLD * 2 is the old &OLD's.
  run("&OLD = 1\nVV, &DEPTH, 0.5, MATERIAL, Oak, &old, &OLD * 2, &T, \"a b\"\nUL\n");
  EXPECT_EQ(printed, "&DEPTH = 0.5\n&MATERIAL = \"Oak\"\n&OLD = 2\n&T = \"a b\"\n");
  ASSERT_NE(interp().variable("DEPTH"), nullptr);
  EXPECT_EQ(interp().variable("DEPTH")->num(), 0.5);
  // The values are the variables' like any others: commands read them.
  run("VV, &X, 2, &Y, 3\nJ2, &X, &Y\n");
  ASSERT_EQ(sink.moves.size(), 1u);
  EXPECT_EQ(sink.moves[0].to[0], 2);
  EXPECT_EQ(sink.moves[0].to[1], 3);
}

TEST_F(UtilityFileTest, VvErrorsAreLocatedAndSetNothing) {
  struct Case {
    std::string line;
    int column;
    std::string message;
  } cases[] = {
      {"VV, &A, 1, &B\n", 12, "VV: &B has no value (parameter 4)"},
      {"VV, &A, 1, &B, \"\"\n", 16, "VV: &B has no value (parameter 4)"},
      {"VV, &A, 1, , 2\n", 14, "VV: value 2 has no name; give the variable (&NAME) as parameter 3"},
      {"VV, &A, 1, &B C, 2\n", 12, "VV: &B C is not a variable name"},
      {"$P = 1\nVV, &A, 1, $P, 2\n", 12, "VV sets &variables; set $P with `$P = value`"},
      {"VV\n", 1, "VV needs a variable and its value, e.g. VV, &DEPTH, 0.5"},
  };
  for (const Case& c : cases) {
    const Diagnostic d = run_error(c.line);
    EXPECT_EQ(d.loc.line, c.line.starts_with("$") ? 2 : 1) << c.line;
    EXPECT_EQ(d.loc.column, c.column) << c.line;
    EXPECT_TRUE(contains(d.message, c.message)) << c.line << format(d);
    EXPECT_EQ(interp().variable("A"), nullptr) << c.line;  // the good pair was not set either
  }
}

TEST_F(UtilityFileTest, Fact182_UuPrintsTheValueOfItsExpression) {
  run("UU, 12+11/16\n&D = 2\nUU, &D * SQR(16) - 1\nUU, 7\n");
  EXPECT_EQ(printed, "12.6875\n7\n7\n");
  Diagnostic d = run_error("UU\n");
  EXPECT_EQ(d.message, "UU needs its parameter 1 (expression)");
  d = run_error("UU, &NOPE + 1\n");
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_TRUE(contains(d.message, "&NOPE")) << d.message;
  d = run_error("UU, \"text\"\n");
  EXPECT_TRUE(contains(d.message, "expression")) << d.message;
}

// ---- UN, FE ---------------------------------------------------------------------------------

// Only the machine profile names the editor (docs/security.md): a part file that could
// name it could run any program at the next FE, and UN's value would outlive the run.
TEST_F(UtilityFileTest, UnCannotChangeTheEditorFromAPartFile) {
  ::unsetenv("VISUAL");
  ::unsetenv("EDITOR");
  const Diagnostic d = run_error("UN, touch /tmp/gantry-pwned ;\n");
  EXPECT_EQ(format(d), path("part.sbp") +
                           ":1:5: error: UN cannot change the editor from a part file: set it in "
                           "the machine profile, [machine] editor = \"touch /tmp/gantry-pwned ;\" "
                           "(docs/security.md); FE uses vi (neither the machine profile, $VISUAL "
                           "nor $EDITOR names one)");
  EXPECT_EQ(interp().settings().machine.editor, "");
  // Sent as typed lines from a part file (SI), it is still the part file's.
  EXPECT_TRUE(contains(run_error("SI, \"UN, sh\"\n").message, "from a part file"));
}

TEST_F(UtilityFileTest, UnShowsTheProfilesEditorAndWhetherItCanBeFound) {
  profile.machine.editor = "no-such-editor-gantry --wait";
  run("UN\n");
  EXPECT_EQ(printed,
            "FE opens files in no-such-editor-gantry --wait (the machine profile's [machine] "
            "editor); no such program was found (PATH is searched for a bare name)\n");
}

// A values file (an older Gantry's UN saved one there) or UR may hold an editor: FE ignores it.
TEST_F(UtilityFileTest, FeStartsOnlyTheProfilesEditor) {
  ::unsetenv("VISUAL");
  ::unsetenv("EDITOR");
  options.dry_run = true;
  settings.machine.editor = "touch /tmp/gantry-pwned";
  run("FE, notes.txt\n");
  EXPECT_EQ(printed, "FE would open " + path("notes.txt") +
                         " in vi; a check or a preview starts no program\n");
}

TEST_F(UtilityFileTest, Fact93_FeBlankOpensTheLastFileLoadedWithFpOrFe) {
  write("sub.sbp", "MX, 1\n");
  ::unsetenv("VISUAL");  // FE's editor is then vi until UN names one
  ::unsetenv("EDITOR");
  options.dry_run = true;
  run("FE\nFP, sub.sbp\nFE\nFE, notes.txt\nFE\n");
  EXPECT_EQ(printed, "FE would open " + path("part.sbp") +
                         " in vi; a check or a preview starts no program\n"
                         "FE would open " +
                         path("sub.sbp") +
                         " in vi; a check or a preview starts no program\n"
                         "FE would open " +
                         path("notes.txt") +
                         " in vi; a check or a preview starts no program\n"
                         "FE would open " +
                         path("notes.txt") + " in vi; a check or a preview starts no program\n");
}

TEST_F(UtilityFileTest, Fact94_FeInAPartFileLetsTheFileContinue) {
  options.operator_present = false;  // nobody at a terminal: nothing is started
  profile.machine.editor = "false";
  run("FE, part.sbp\nMX, 1\n");
  EXPECT_EQ(printed, "FE would open " + path("part.sbp") +
                         " in false; nobody is at a terminal "
                         "to edit\n");
  ASSERT_EQ(sink.moves.size(), 1u);
  EXPECT_EQ(sink.moves[0].to[0], 1);
}

// ---- FS -------------------------------------------------------------------------------------

TEST_F(UtilityFileTest, Fact108_FsTakesRelativeFoldersAndDotDotInsidePartFiles) {
  write("sub/inner.sbp", "MX, 1\n");
  write("top.sbp", "MY, 2\n");
  run("FS, sub\nFP, inner.sbp\nFS, ..\nFP, top.sbp\n");
  ASSERT_EQ(sink.moves.size(), 2u);
  EXPECT_EQ(sink.moves[0].to[0], 1);
  EXPECT_EQ(sink.moves[1].to[1], 2);
  // Files a command writes go to the parts folder too.
  run("FS, sub\nUS, saved.toml\n");
  EXPECT_TRUE(fs::exists(path("sub/saved.toml")));
}

TEST_F(UtilityFileTest, Fact107_FsBlankRestoresTheTopLevelFolderAndTheMaskDefaultsToSbq) {
  write("sub/inner.sbp", "MX, 1\n");
  run("FS, sub, *.txt\nUV\nFS\nUV\n");
  EXPECT_TRUE(contains(printed, "Parts folder (FS): " + path("sub") + "\nFile mask (FS): *.txt\n"))
      << printed;
  const std::string after = printed.substr(printed.rfind("Values and settings"));
  EXPECT_TRUE(contains(after, "Parts folder (FS): " + folder() + "\nFile mask (FS): *.sb?\n"))
      << after;
}

TEST_F(UtilityFileTest, FsRefusesAFolderThatIsNotThere) {
  write("top.sbp", "MY, 2\n");
  const Diagnostic d = run_error("FS, nowhere\n");
  EXPECT_EQ(format(d), path("part.sbp") + ":1:5: error: FS: there is no folder " + path("nowhere") +
                           "; the parts folder stays " + folder());
}

// ---- UV, UD ---------------------------------------------------------------------------------

TEST_F(UtilityFileTest, UvShowsWhatTheLocationReadoutDoesNot) {
  profile.machine.editor = "sh";
  run("MS, 1.5, 0.75\nVC, 0.375\nUV\n");
  for (const std::string& line : std::vector<std::string>{
           "Values and settings (UV):\n",
           "Editor (FE): sh (the machine profile's [machine] editor)\n",
           "Units: in; dialect: sb3; axes in use: 3\n", "Coordinate system (SC): 1, user\n",
           "Move speeds (in/s): XY 1.5, Z 0.75,", "Cutter (VC): diameter 0.375,",
           "Steps per unit (VU): X " + fmt::format("{}", profile.axes[0].steps_per_unit),
           "Machine profile: \"" + profile.name + "\" (/profiles/desk.toml)\n",
           "Values file: /config/values/desk.toml\n",
           "Last file loaded (FE's blank): " + path("part.sbp") + "\n"})
    EXPECT_TRUE(contains(printed, line)) << line << "\nin:\n" << printed;
  for (const CanonMove& m : sink.moves) EXPECT_NE(m.kind, MoveKind::Line);
}

TEST_F(UtilityFileTest, UdReportsTheCardAndThePositionInSteps) {
  run("M2, 1, 2\nUD\n");
  const double sx = profile.axes[0].steps_per_unit, sy = profile.axes[1].steps_per_unit;
  EXPECT_TRUE(contains(printed, fmt::format("Position in steps (the moves issued so far): X {}, Y "
                                            "{}, Z 0\n",
                                            std::llround(sx), std::llround(2 * sy))))
      << printed;
  for (const std::string& line :
       {std::string("Diagnostics (UD), Gantry ") + GANTRY_VERSION + ":\n",
        "Machine profile: \"" + profile.name + "\" (/profiles/desk.toml)\n",
        std::string("Values file: /config/values/desk.toml\n"), std::string("Card: sim (pacer "),
        std::string("Location: X 1, Y 2, Z 0\n"), std::string("moves issued: 1\n"),
        std::string("Settings problems: none\n")})
    EXPECT_TRUE(contains(printed, line)) << line << "\nin:\n" << printed;
}

TEST_F(UtilityFileTest, Fact179_UdAndUvSaveTheirReportsToAFile) {
  run("UD, PROBLEM.LOG\nUV, values.log\n");
  const std::string log = slurp(path("PROBLEM.LOG"));
  EXPECT_TRUE(log.starts_with("Diagnostics (UD)")) << log;
  EXPECT_TRUE(contains(log, "Values and settings (UV):\n")) << log;  // both, as SB3's log
  EXPECT_TRUE(slurp(path("values.log")).starts_with("Values and settings (UV):\n"));
  EXPECT_TRUE(contains(printed, "UD saved this report and UV's to " + path("PROBLEM.LOG")));
  // A check writes nothing on the disk.
  fs::remove(path("PROBLEM.LOG"));
  options.dry_run = true;
  run("UD, PROBLEM.LOG\n");
  EXPECT_FALSE(fs::exists(path("PROBLEM.LOG")));
}

// ---- US, UR ---------------------------------------------------------------------------------

TEST_F(UtilityFileTest, Fact181_UsSavesTheSettingsAndUrLoadsThemBack) {
  run("VC, 0.5\nMS, 1.5\nUS, saved.toml\nVC, 0.75\nMS, 2.5\nVU, 2000\nUR, saved.toml\nUV\n");
  EXPECT_EQ(interp().settings().cutter.diameter, 0.5);
  EXPECT_EQ(interp().settings().axes[0].steps_per_unit, profile.axes[0].steps_per_unit);
  EXPECT_EQ(interp().state().speeds.move.xy, 1.5);
  EXPECT_TRUE(contains(printed, "US saved the current settings to " + path("saved.toml")));
  EXPECT_TRUE(contains(printed, "UR loaded " + path("saved.toml") + " as the current values"));
  // The file is a complete profile.
  const SettingsLoad load = parse_settings(slurp(path("saved.toml")), "saved.toml");
  ASSERT_TRUE(load.ok()) << format(load.errors.front());
  EXPECT_EQ(load.settings.cutter.diameter, 0.5);
  EXPECT_EQ(load.settings.speeds.move.xy, 1.5);
  // The new values reach the planner and the step generator.
  ASSERT_FALSE(sink.changes.empty());
  EXPECT_EQ(sink.changes.back().axes[0].steps_per_unit, profile.axes[0].steps_per_unit);
}

TEST_F(UtilityFileTest, Fact181_UrBlankReturnsToTheProfilesValues) {
  settings.cutter.diameter = 0.125;  // as a values file left it
  settings.speeds.move.xy = 0.5;
  run("VD, , , 1\nUR\n");  // millimetres first: UR's profile is in inches
  EXPECT_EQ(interp().settings().cutter.diameter, profile.cutter.diameter);
  EXPECT_EQ(interp().settings().units, Units::Inches);
  EXPECT_EQ(interp().state().speeds.move.xy, profile.speeds.move.xy);
  // Nothing differs from the profile: the values file empties.
  EXPECT_FALSE(contains(values_text(interp().settings(), profile), "diameter"));
}

TEST_F(UtilityFileTest, UrValuesOutlastTheFileThatLoadedThem) {
  write("sub.sbp", "VS, 0.25\nUR\n");
  settings.speeds.move.xy = 0.5;
  run("FP, sub.sbp\n");
  EXPECT_EQ(interp().state().speeds.move.xy, profile.speeds.move.xy);  // not undone to 0.5
}

TEST_F(UtilityFileTest, UrRefusesAnotherMachineAndBadFilesChangingNothing) {
  write("other.toml", "[card]\nstep_pulse_us = 7.0\n");
  write("bad.toml", "[cutter]\ndiameter = -1\n");
  Diagnostic d = run_error("VC, 0.5\nUR, other.toml\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_TRUE(contains(d.message, "other.toml describes another machine (card differs"))
      << d.message;
  EXPECT_EQ(interp().settings().cutter.diameter, 0.5);
  d = run_error("VC, 0.5\nUR, bad.toml\n");
  EXPECT_TRUE(contains(d.message, "bad.toml:2:12: error: cutter.diameter = -1 is out of range"))
      << d.message;
  EXPECT_EQ(interp().settings().cutter.diameter, 0.5);
  d = run_error("UR, missing.toml\n");
  EXPECT_EQ(d.message, "UR: cannot read " + path("missing.toml") + "; nothing was changed");
  d = run_error("US\n");
  EXPECT_EQ(d.message, "US needs its parameter 1 (file name)");
}

// ---- UI, VK: refused by name ---------------------------------------------------------------

TEST_F(UtilityFileTest, UiAndVkSayWhyTheyCannotRun) {
  Diagnostic d = run_error("MX, 1\nUI\nMX, 2\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_TRUE(
      d.message.starts_with("UI (install control box firmware) cannot run on this "
                            "machine: Gantry drives the step card directly"))
      << d.message;
  EXPECT_EQ(sink.moves.size(), 1u);  // the line before; nothing after
  d = run_error("VK\n");
  EXPECT_TRUE(d.message.starts_with("VK cannot run: SB3's reference names it only in UV's"))
      << d.message;
  for (const char* code : {"UI", "VK"})
    EXPECT_TRUE(CommandTable::standard().find(code)->coverage.starts_with("refused by name: "))
        << code;
}

// ---- SC -------------------------------------------------------------------------------------

TEST_F(UtilityFileTest, Fact178_ScSelectsTableBaseOrUserCoordinates) {
  // User offset X 2; SC 0 reads and moves in table base coordinates; SC 1 brings it back.
  run("JX, 2\nZX\nSC, 0\nJX, 1\nSC, 1\nJX, 1\n");
  ASSERT_EQ(sink.moves.size(), 3u);
  EXPECT_EQ(sink.moves[1].to[0], 1);  // table base X 1
  EXPECT_EQ(sink.moves[2].to[0], 3);  // user X 1 is table base 3
  EXPECT_EQ(interp().state().zero[0], 2);
  EXPECT_FALSE(interp().state().user_zero);
  run("JX, 2\nZX\nSC, 0\nUV\n");
  EXPECT_EQ(interp().state().position[0], 2);
  EXPECT_TRUE(contains(printed, "Coordinate system (SC): 0, table base")) << printed;
}

TEST_F(UtilityFileTest, ZeroingWhileTableBaseIsSelectedMakesANewUserSystem) {
  run("JX, 2\nZX\nSC, 0\nJX, 5\nZX\nSC, 1\nJX, 1\n");
  EXPECT_EQ(interp().state().zero[0], 5);  // the offsets set aside (2) are dropped
  EXPECT_EQ(sink.moves.back().to[0], 6);
  const Diagnostic d = run_error("SC, 2\n");
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_EQ(d.message, "SC parameter 1 (system) is 2; allowed: 0 to 1");
}

// ---- FC -------------------------------------------------------------------------------------

// The moves a file makes when run, as (jog?, X, Y, Z) of each end point.
struct End {
  bool jog;
  double x, y, z;
  bool operator==(const End&) const = default;
};
std::vector<End> ends(const std::vector<CanonMove>& moves) {
  std::vector<End> out;
  for (const CanonMove& m : moves)
    out.push_back({m.speed_class == SpeedClass::Jog, m.to[0], m.to[1], m.to[2]});
  return out;
}

TEST_F(UtilityFileTest, Fact92_FcConvertsHpglIntoAPartFileThatCutsThePlot) {
  copy_data("square.plt");
  run("FC, square.plt, , -0.25, 0.5\n");
  EXPECT_TRUE(sink.moves.empty());  // FC itself moves nothing
  EXPECT_EQ(printed, "FC converted square.plt (HP-GL) into 2 paths in " + path("square.sbp") +
                         "; run it with FP, square.sbp\n");
  EXPECT_TRUE(contains(warnings(),
                       "warning: FC: not converted from square.plt: 1 CI "
                       "instruction(s)"))
      << warnings();
  run("FP, square.sbp\n");
  const double c = -0.25, s = 0.5;
  EXPECT_EQ(ends(sink.moves), (std::vector<End>{{true, 0, 0, s},
                                                {false, 0, 0, c},
                                                {false, 1, 0, c},
                                                {false, 1, 1, c},
                                                {false, 0, 1, c},
                                                {false, 0, 0, c},
                                                {true, 0, 0, s},
                                                {true, 2, 0, s},
                                                {false, 2, 0, c},
                                                {false, 2.5, 0, c},
                                                {false, 2.5, 0.5, c},
                                                {true, 2.5, 0.5, s}}));
}

TEST_F(UtilityFileTest, Fact92_FcConvertsDxfLinesAndPolylinesInTheDrawingsUnits) {
  copy_data("lines.dxf");  // millimetres; the profile is in inches
  run("FC, lines.dxf, cut.sbp\nFP, cut.sbp\n");
  const double c = 0, s = profile.cutter.safe_z;
  EXPECT_EQ(ends(sink.moves), (std::vector<End>{{true, 0, 0, s},
                                                {false, 0, 0, c},
                                                {false, 1, 0, c},
                                                {false, 1, 1, c},
                                                {true, 1, 1, s},
                                                {true, 2, 0, s},
                                                {false, 2, 0, c},
                                                {false, 3, 0, c},
                                                {false, 3, 1, c},
                                                {false, 2, 0, c},
                                                {true, 2, 0, s}}));
}

TEST_F(UtilityFileTest, Fact92_FcConvertsDxfArcsCirclesAndBulgesIntoCg) {
  copy_data("shapes.dxf");
  run("FC, shapes.dxf\n");
  const std::string text = slurp(path("shapes.sbp"));
  for (const char* part : {"J2, 7, 1\nMZ, 0\nCG, , 6, 2, -1, 0, T, -1, , , , , , 1\n",
                           "J2, 9.5, 2\nMZ, 0\nCG, , 9.5, 2, -0.5, 0, T, -1, , , , , , 1\n",
                           "J2, 10, 0\nMZ, 0\nCG, , 12, 0, 1, 0, T, 1, , , , , , 1\n",
                           "J2, 14, 0\nMZ, 0\nM2, 15, 0\nCG, , 16, 1, 0, 1, T, -1, , , , , , 1\n"
                           "M2, 14, 0\nJZ, 1\n"})
    EXPECT_TRUE(contains(text, part)) << part << "\nin:\n" << text;
  EXPECT_TRUE(contains(warnings(), "FC: not converted from shapes.dxf: 1 TEXT entity(ies)"));
  // Run: every arc starts and ends where the drawing's does, about its centre, at cut Z.
  run("FP, shapes.sbp\n");
  std::vector<std::vector<double>> arcs;
  for (const CanonMove& m : sink.moves)
    if (m.kind == MoveKind::Arc)
      arcs.push_back({m.from[0], m.from[1], m.to[0], m.to[1], m.center_x, m.center_y, m.to[2]});
  const std::vector<std::vector<double>> expected = {{7, 1, 6, 2, 6, 1, 0},
                                                     {9.5, 2, 9.5, 2, 9, 2, 0},
                                                     {10, 0, 12, 0, 11, 0, 0},
                                                     {15, 0, 16, 1, 15, 1, 0}};
  ASSERT_EQ(arcs.size(), expected.size());
  for (size_t i = 0; i < arcs.size(); ++i)
    for (size_t k = 0; k < 7; ++k) EXPECT_NEAR(arcs[i][k], expected[i][k], 1e-9) << i << " " << k;
}

TEST_F(UtilityFileTest, FcSaysByNameWhatItDoesNotConvertAndDoesNothing) {
  write("job.nc", "G0 X1\n");
  write("photo.jpg", "");
  write("drawing.xyz", "");
  Diagnostic d = run_error("FC, job.nc\n");
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_TRUE(contains(d.message,
                       "FC: job.nc is a G-code file; there is nothing to convert: FP "
                       "runs G-code files directly"))
      << d.message;
  d = run_error("FC, photo.jpg\n");
  EXPECT_TRUE(contains(d.message,
                       "raster image; converting an image's grey levels into heights "
                       "is not offered"))
      << d.message;
  d = run_error("FC, drawing.xyz\n");
  EXPECT_TRUE(contains(d.message, "has no extension FC converts")) << d.message;
  d = run_error("FC, missing.dxf\n");
  EXPECT_EQ(d.message, "FC: cannot read " + path("missing.dxf"));
  for (const char* out : {"job.sbp", "photo.sbp", "drawing.sbp"})
    EXPECT_FALSE(fs::exists(path(out)));
}

TEST_F(UtilityFileTest, FcErrorsInTheDrawingNameItsLineAndTheFcLine) {
  write("bad.plt", "IN;\nPD1,2,3;\n");
  Diagnostic d = run_error("MX, 1\nFC, bad.plt\n");
  EXPECT_EQ(format(d), path("part.sbp") +
                           ":2 -> bad.plt:2:1: error: FC: PD has 3 numbers; its "
                           "points need an X and a Y each");
  EXPECT_FALSE(fs::exists(path("bad.sbp")));
  d = run_error("FC, bad.plt, , 0, -1\n");
  EXPECT_EQ(d.loc.column, 19);
  EXPECT_EQ(d.message,
            "FC: safe Z -1 is not above the cutting Z 0; the jogs between paths would "
            "go through the material");
  write("ok.plt", "PU0,0;PD10,0;");
  d = run_error("FC, ok.plt, ok.plt\n");
  EXPECT_TRUE(contains(d.message, "would overwrite the drawing")) << d.message;
  d = run_error("FC, ok.plt, , , , 0\n");
  EXPECT_TRUE(contains(d.message, "FC parameter 5 (scale) is 0")) << d.message;
}

TEST_F(UtilityFileTest, FcInACheckWritesNothing) {
  copy_data("square.plt");
  options.dry_run = true;
  run("FC, square.plt\nFP, square.sbp\n");  // the check sees its own writes
  EXPECT_FALSE(fs::exists(path("square.sbp")));
  EXPECT_FALSE(sink.moves.empty());
}

}  // namespace
}  // namespace gantry
