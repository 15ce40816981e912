// The tool table (docs/gcode.md, "Tool table"): LinuxCNC's file read and written back,
// malformed lines located, G43 H / M6 T / M61 Q / G10 L1 L10 L11 against LinuxCNC 2.9's
// rs274 (its numbers are the golden values below), the implicit table when none is
// configured, and VC following the tool in the spindle (M6, and OpenSBP's &Tool + C9).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "gantry/core/text_file.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/tool_table.hpp"
#include "gantry/preview/material.hpp"
#include "gantry/preview/toolpath.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

// Lines as LinuxCNC's users write them: a comment line, a comment after `;`, a sign, lower
// case, two spaces, a tool with no offsets, and every field as LinuxCNC itself writes them.
// rs274 -t reads every one of them (the runs below).
const std::string kTable =
    "; tools for the router\n"
    "T1 P1 D0.25 Z+1.5 ;t1\n"
    "T2  P2 D0.125 Z+1.0\n"
    "t3 p7 z-0.75 d+0.5 ; lowercase, signs\n"
    "T4 P4\n"
    "T10 P10 X0 Y0 Z+2.000000 A0 B0 C0 U0 V0 W0 D+0.062500 I0 J0 Q0 ;as LinuxCNC writes it\n";

using RecordingIO = AnsweringIO;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class GcodeToolTable : public InterpreterFixture<RecordingIO> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gantry_tools_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    settings.machine.limit_checking = false;  // the offsets below put Z under the table
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string table_file(const std::string& text, const std::string& name = "tool.tbl") {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    settings.tool_table_path = p.string();
    return p.string();
  }

  // Runs `text`; the lines and arcs it made. `after` receives the settings as it left them.
  std::vector<CanonMove> run(const std::string& text, Settings* after = nullptr) {
    return lines_and_arcs(run_script(Script::from_text(text, "t.ngc"), {}, after));
  }
  // What a check (a dry run) finds.
  std::vector<Diagnostic> check(const std::string& text) {
    return check_script(Script::from_text(text, "t.ngc"));
  }
  Diagnostic first_error(const std::string& text) { return first_error_of(check(text), text); }

  fs::path dir_;
};

void expect_z(const std::vector<CanonMove>& m, const std::vector<double>& z) {
  ASSERT_EQ(m.size(), z.size());
  for (size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(m[i].to[2], z[i], 1e-9) << "move " << i;
}

// ---- the file ---------------------------------------------------------------------------

TEST(ToolTableFile, ReadsLinuxCncLinesAndWritesUnchangedOnesBackByteForByte) {
  ToolTable t = ToolTable::parse(kTable, "tool.tbl");
  ASSERT_EQ(t.tools().size(), 5u);
  const ToolEntry* t3 = t.find(3);
  ASSERT_NE(t3, nullptr);
  EXPECT_EQ(t3->pocket, 7);
  EXPECT_EQ(t3->length(), -0.75);
  EXPECT_EQ(t3->diameter, 0.5);
  EXPECT_EQ(t3->comment, " lowercase, signs");
  EXPECT_EQ(t.find(4)->length(), 0);  // missing fields are 0
  EXPECT_EQ(t.find(4)->diameter, 0);
  EXPECT_EQ(t.find(10)->length(), 2);
  EXPECT_EQ(t.find(10)->diameter, 0.0625);
  EXPECT_EQ(t.find(5), nullptr);  // a file's table has only its tools
  EXPECT_EQ(t.text(), kTable);

  t.change(3)->offset[2] = 1;
  EXPECT_EQ(t.text(),
            "; tools for the router\n"
            "T1 P1 D0.25 Z+1.5 ;t1\n"
            "T2  P2 D0.125 Z+1.0\n"
            "T3 P7 D+0.5 Z+1 ; lowercase, signs\n"
            "T4 P4\n"
            "T10 P10 X0 Y0 Z+2.000000 A0 B0 C0 U0 V0 W0 D+0.062500 I0 J0 Q0 ;as LinuxCNC writes "
            "it\n");
  // What it wrote reads back as the same tool.
  const ToolTable again = ToolTable::parse(t.text(), "tool.tbl");
  EXPECT_EQ(again.find(3)->length(), 1);
  EXPECT_EQ(again.find(3)->diameter, 0.5);
  EXPECT_EQ(again.find(3)->comment, " lowercase, signs");
  EXPECT_EQ(format_tool_line(*again.find(10)), "T10 P10 D+0.0625 Z+2 ;as LinuxCNC writes it");
}

TEST(ToolTableFile, TheImplicitTableHasEveryToolAtLengthZero) {
  ToolTable t;
  EXPECT_TRUE(t.implicit());
  ASSERT_NE(t.find(7), nullptr);
  EXPECT_EQ(t.find(7)->length(), 0);
  t.change(7)->offset[2] = 0.5;
  EXPECT_EQ(t.find(7)->length(), 0.5);
  EXPECT_EQ(t.find(8)->length(), 0);
}

TEST(ToolTableFile, MalformedLinesAreLocatedErrorsSayingWhatToWrite) {
  struct Case {
    std::string line;
    int column;
    std::string says;
  };
  const std::vector<Case> cases = {
      {"T1 P1 Z", 7, "Z needs its number right after it"},
      {"T1 P1 Zabc", 7, "\"abc\" is not a number"},
      {"T1 P1 Z1.5.2", 7, "is not a number"},
      {"T1.5 P1", 1, "T takes a whole number"},
      {"T1 P1 K2", 7, "\"K2\" is not a tool table field"},
      {"T1 P1 Z1 Z2", 10, "Z is given twice"},
      {"  P1 Z1", 3, "no tool number"},
      {"T1 Z1", 1, "tool 1 has no pocket"},
      {"T0 P1", 1, "T0 is the empty spindle"},
      {"T1 P1001", 4, "pocket numbers are 0 to 1000"},
      {"T1 P1 Q12", 7, "orientation is 0 to 9"},
      {"T1 P1 Z+-1", 7, "is not a number"},
      {"T1 P1 Zinf", 7, "is not a number"},
      {"T2 P5 Z1", 1, "tool 2 is already in the table"},
  };
  for (const Case& c : cases) {
    try {
      ToolTable::parse("; header\nT2 P2 Z1\n" + c.line + " ;comment\n", "tools.tbl");
      ADD_FAILURE() << "accepted: " << c.line;
    } catch (const GantryError& e) {
      const Diagnostic& d = e.diagnostic();
      ASSERT_TRUE(d.loc.file) << c.line;
      EXPECT_EQ(*d.loc.file, "tools.tbl");
      EXPECT_EQ(d.loc.line, 3) << c.line;
      EXPECT_EQ(d.loc.column, c.column) << c.line;
      EXPECT_NE(d.message.find(c.says), std::string::npos) << c.line << ": " << d.message;
    }
  }
}

TEST(ToolTableFile, AMissingFileIsAnErrorNamingThePath) {
  const std::string absent = (fs::temp_directory_path() / "gantry_no_such_table.tbl").string();
  for (const std::string& path : {absent, std::string("/no/such/folder/tool.tbl")}) {
    try {
      load_tool_table(path);
      FAIL() << path;
    } catch (const GantryError& e) {
      const std::string& m = e.diagnostic().message;
      EXPECT_NE(m.find("the tool table " + path), std::string::npos) << m;
      EXPECT_NE(m.find(path == absent ? "does not exist" : "there is no folder /no/such/folder"),
                std::string::npos)
          << m;
    }
  }
}

// ---- the profile key --------------------------------------------------------------------

TEST(ToolTableSetting, TheProfileKeyIsRelativeToTheProfilesFolder) {
  std::string text = default_profile_text();
  const std::string key = "gcode_dialect = \"standard\"";
  const size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.insert(at, "tool_table = \"tools/router.tbl\"\n");
  const SettingsLoad load = parse_settings(text, "/etc/gantry/shop.toml");
  ASSERT_TRUE(load.ok()) << format(load.errors.front());
  EXPECT_EQ(load.settings.tool_table, "tools/router.tbl");
  EXPECT_EQ(load.settings.tool_table_path, "/etc/gantry/tools/router.tbl");
  const SettingsLoad absolute =
      parse_settings(text.replace(text.find("tools/router.tbl"), 16, "/srv/t.tbl"), "/etc/p.toml");
  ASSERT_TRUE(absolute.ok());
  EXPECT_EQ(absolute.settings.tool_table_path, "/srv/t.tbl");
  EXPECT_TRUE(default_settings().tool_table_path.empty());  // none: the implicit table
}

// ---- G43 H, M6 T, M61 Q and the parameters, against rs274 -------------------------------

// rs274 -t tool.tbl (kTable) -g on this program prints (canon Z, then the offset it uses):
//   USE_TOOL_LENGTH_OFFSET(0 0 -0.7500) STRAIGHT_TRAVERSE(1, 1, 0.5)
//   USE_TOOL_LENGTH_OFFSET(0 0 1.5000)  STRAIGHT_TRAVERSE(1, 1, 0)
//   USE_TOOL_LENGTH_OFFSET(0 0 -0.7500) STRAIGHT_TRAVERSE(1, 1, 0.25)   G43 alone: tool 3
//   USE_TOOL_LENGTH_OFFSET(0 0 0)       STRAIGHT_TRAVERSE(1, 1, 0)
//   USE_TOOL_LENGTH_OFFSET(0 0 2.0000)  STRAIGHT_TRAVERSE(1, 1, 0)      G43 H0: the spindle's
//   USE_TOOL_LENGTH_OFFSET(0 0 0)       STRAIGHT_TRAVERSE(1, 1, 1)      T4: no Z
//   USE_TOOL_LENGTH_OFFSET(0 0 1.0000)  STRAIGHT_FEED(1, 1, -0.1)
//   USE_TOOL_LENGTH_OFFSET(0 0 38.1000) STRAIGHT_TRAVERSE(25.4, 25.4, 10)  G21: mm
// and (DEBUG, #5400 #5403 #5410) after T3 M6: " 3.000000 -0.750000 0.500000", after T10 M6:
// " 10.000000 2.000000 0.062500". The machine's Z is canon Z plus the offset.
TEST_F(GcodeToolTable, G43HPositionsAndToolParametersMatchRs274) {
  table_file(kTable);
  const auto m =
      run("G20 G90\nT3 M6\nG43 H3\nG0 X1 Y1 Z0.5\nG10 L2 P2 X[#5400] Y[#5403] Z[#5410]\n"
          "G43 H1\nG0 Z0\nG43\nG0 Z0.25\nG49\nG0 Z0\n"
          "T10 M6\nG43 H0\nG0 Z0\nG10 L2 P3 X[#5400] Y[#5403] Z[#5410]\n"
          "T4 M6\nG43\nG0 Z1\nT2 M6\nG43 H2\nG1 Z-0.1 F30\nG21\nG43 H1\nG0 Z10\nM2\n");
  expect_z(m,
           {0.5 - 0.75, 0 + 1.5, 0.25 - 0.75, 0, 0 + 2.0, 1 + 0, -0.1 + 1.0, (10 + 38.1) / 25.4});
  EXPECT_NEAR(m.back().to[0], 25.4 / 25.4, 1e-12);
  const GcodeOffsets& o = state.gcode;
  EXPECT_NEAR(o.origin[1][0], 3, 1e-12);      // #5400 after T3 M6
  EXPECT_NEAR(o.origin[1][1], -0.75, 1e-12);  // #5403
  EXPECT_NEAR(o.origin[1][2], 0.5, 1e-12);    // #5410
  EXPECT_NEAR(o.origin[2][0], 10, 1e-12);
  EXPECT_NEAR(o.origin[2][1], 2, 1e-12);
  EXPECT_NEAR(o.origin[2][2], 0.0625, 1e-12);
  EXPECT_EQ(o.tool, 2);
  // The operator was asked at each change; a change to the tool in the spindle asks nothing.
  EXPECT_EQ(io.questions.size(), 4u);
  for (const Diagnostic& d : io.warnings)  // a table is configured: no note about lengths of 0
    EXPECT_EQ(d.message.find("no tool table"), std::string::npos) << d.message;
}

TEST_F(GcodeToolTable, M61SetsTheToolInTheSpindleWithoutAChange) {
  table_file(kTable);
  const auto m = run("G20\nM61 Q1\nG43\nG0 X1 Z0\nM61 Q0\nG43\nG0 Z0\n");
  expect_z(m, {1.5, 0});
  EXPECT_TRUE(io.questions.empty());  // nobody is asked: the tool is already there
  EXPECT_EQ(state.gcode.tool, 0);
}

// ---- G10 L1, L10, L11 written back ------------------------------------------------------

// rs274 -t tool.tbl (kTable) -g on this program prints SET_TOOL_TABLE_ENTRY for tool 2 with
// Z 0.2500 (L10), tool 4 with Z -3.0000 (L11, G59.3 at 0), tool 3 with Z 1.0000 (L11 after
// G10 L2 P9 Z-4), tool 10 with Z 0.1250 (L1); then USE_TOOL_LENGTH_OFFSET 1.0000 and 0.1250
// for the last two G43s. The moves, in machine Z (canon + G54 -3 + G92 1 + offset):
// -1 + 1 + 1.5 - 3, -1 + 1 + 0.25 - 3, 0 + 1 + 1 - 3, 0 + 1 + 0.125 - 3.
const std::string kTouchOff =
    "G20 G90\nT1 M6\nG43 H1\nG10 L2 P1 Z-3\nG92 Z0.5\nG0 X1 Y2 Z-1\nG10 L10 P2 Z0.25\n"
    "G43 H2\nG0 Z-1\nG10 L11 P4 Z0.25\nG10 L2 P9 Z-4\nG10 L11 P3 Z0.25\n"
    "G10 L1 P10 Z0.125 R0.1\nG43 H3\nG0 Z0\nG43 H10\nG0 Z0\nM2\n";

TEST_F(GcodeToolTable, G10L1L10L11SetTheOffsetsRs274ComputesAndWriteTheFileBack) {
  const std::string path = table_file(kTable);
  const auto m = run(kTouchOff);
  expect_z(m, {-1.5, -2.75, -1, -1.875});
  // Every changed line in the standard form, the others as they were; R is the radius
  // (LinuxCNC's G10 L1), the table keeps the diameter.
  EXPECT_EQ(slurp(path),
            "; tools for the router\n"
            "T1 P1 D0.25 Z+1.5 ;t1\n"
            "T2 P2 D+0.125 Z+0.25\n"
            "T3 P7 D+0.5 Z+1 ; lowercase, signs\n"
            "T4 P4 Z-3\n"
            "T10 P10 D+0.2 Z+0.125 ;as LinuxCNC writes it\n");
  // Another interpreter reads the file this one wrote: tool 4 is -3 long.
  expect_z(run("G20\nG43 H4\nG0 Z0\n"), {-3});
}

TEST_F(GcodeToolTable, ACheckWritesNothingButSeesItsOwnChanges) {
  const std::string path = table_file(kTable);
  const std::vector<Diagnostic> found = check("G20\nG10 L1 P2 Z5\nG43 H2\nG0 Z0\n");
  for (const Diagnostic& d : found) ADD_FAILURE() << format(d);
  EXPECT_EQ(slurp(path), kTable);
  ASSERT_EQ(sink.moves.size(), 1u);  // the check's dry run used tool 2's new length
  EXPECT_NEAR(sink.moves[0].to[2], 5, 1e-12);
  // A run after the check reads the file, unchanged: tool 2 is 1 long.
  expect_z(run("G20\nG43 H2\nG0 Z0\n"), {1});
}

TEST_F(GcodeToolTable, AFailedWriteKeepsTheOldFileAndTheOldOffsets) {
  // Its temporary file's name is past the system's limit: the save fails even for root.
  const std::string path = table_file(kTable, std::string(230, 't') + ".tbl");
  try {
    run("G20\nG10 L1 P2 Z5\n");
    FAIL() << "the write did not fail";
  } catch (const GantryError& e) {
    EXPECT_EQ(e.diagnostic().loc.line, 2);
    EXPECT_NE(e.diagnostic().message.find("could not write the tool table"), std::string::npos)
        << e.diagnostic().message;
    EXPECT_NE(e.diagnostic().message.find("the previous file and tool 2's offsets are kept"),
              std::string::npos);
  }
  EXPECT_EQ(slurp(path), kTable);
  expect_z(run("G20\nG43 H2\nG0 Z0\n"), {1});
}

// ---- no table, and tools missing from one -----------------------------------------------

// What Fusion 360's, VCarve's and FreeCAD's posts write at a program's start.
const std::string kCamStart =
    "%\n(T1 D=0.25 CR=0 - ZMIN=-0.25 - flat end mill)\nG90 G94 G17\nG20\n"
    "T1 M6\nS18000 M3\nG54\nG0 X1 Y1\nG43 Z0.6 H1\nG0 Z0.2\nG1 Z-0.1 F20\nG0 Z0.6\nM5\nM30\n";

TEST_F(GcodeToolTable, WithNoTableConfiguredCamProgramsRunWithLengthsOfZero) {
  settings.tool_table_path.clear();
  settings.cutter.diameter = 0.5;
  Settings after;
  const auto m = run(kCamStart, &after);
  expect_z(m, {0, 0.6, 0.2, -0.1, 0.6});
  EXPECT_EQ(state.gcode.tool, 1);
  EXPECT_EQ(after.cutter.diameter, 0.5);  // no table, no diameter: VC's cutter stays
  std::vector<Diagnostic> notes;          // one, at the first tool change
  for (const Diagnostic& d : io.warnings)
    if (d.message.find("no tool table is configured") != std::string::npos) notes.push_back(d);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0].loc.line, 5);
  EXPECT_NE(notes[0].message.find("length 0"), std::string::npos);
}

// rs274 -t with a table lacking tool 5 refuses `T5 M6`, `T5`, `G43 H5`, `M61 Q5` and
// `G10 L1 P5 Z1` and `G41 D5` alike: "Requested tool 5 not found in the tool table", nothing run.
TEST_F(GcodeToolTable, AToolMissingFromAConfiguredTableIsRefusedLocated) {
  table_file(kTable);
  struct Case {
    std::string program;
    int line, column;
  };
  const std::vector<Case> cases = {
      {"G20\nT5 M6\n", 2, 1},  {"G20\nG0 X1 T5\n", 2, 7},     {"G20\nG43 H5\n", 2, 5},
      {"G20\nM61 Q5\n", 2, 5}, {"G20\nG10 L1 P5 Z1\n", 2, 8}, {"G20\nG41 D5 G1 X1 F10\n", 2, 5}};
  for (const Case& c : cases) {
    const Diagnostic d = first_error(c.program);
    EXPECT_EQ(d.loc.line, c.line) << c.program;
    EXPECT_EQ(d.loc.column, c.column) << c.program;
    EXPECT_NE(d.message.find("tool 5 is not in the tool table"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("tool.tbl"), std::string::npos) << d.message;
  }
  EXPECT_TRUE(sink.moves.empty());
  // The CAM program's T1 is in this table: it runs, with tool 1's length.
  const auto m = run(kCamStart);
  expect_z(m, {0, 0.6 + 1.5, 0.2 + 1.5, -0.1 + 1.5, 0.6 + 1.5});
}

TEST_F(GcodeToolTable, ABrokenOrMissingTableIsALocatedError) {
  table_file("T1 P1 Z+1.5\nT2 P2 Z1..5\n");
  Diagnostic d = first_error("G20\nT1 M6\n");
  ASSERT_TRUE(d.loc.file);
  EXPECT_EQ(fs::path(*d.loc.file).filename(), "tool.tbl");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_EQ(d.loc.column, 7);
  settings.tool_table_path = (dir_ / "gone.tbl").string();
  d = first_error("G20\nG0 X1\nT1 M6\n");
  EXPECT_EQ(d.loc.line, 3);
  EXPECT_NE(d.message.find("gone.tbl does not exist"), std::string::npos) << d.message;
}

TEST_F(GcodeToolTable, G43RefusesAToolWithOffsetsOtherThanItsLength) {
  table_file("T1 P1 X0.1 Z1\n");
  const Diagnostic d = first_error("G20\nG43 H1\n");
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_NE(d.message.find("X offset"), std::string::npos) << d.message;
}

// ---- VC follows the tool in the spindle -------------------------------------------------

TEST_F(GcodeToolTable, VcsCutterDiameterIsTheDiameterOfTheToolInTheSpindle) {
  table_file(kTable);
  settings.cutter.diameter = 0.75;
  Settings after;
  run("T2 M6\n", &after);
  EXPECT_EQ(after.cutter.diameter, 0.125);  // tool 2's D
  settings = after;
  run("T3\nM6\n", &after);
  EXPECT_EQ(after.cutter.diameter, 0.5);
  settings = after;
  run("T4 M6\n", &after);  // tool 4 has no D: VC's cutter stays
  EXPECT_EQ(after.cutter.diameter, 0.5);
  settings = after;
  run("M61 Q10\n", &after);
  EXPECT_EQ(after.cutter.diameter, 0.0625);
  settings = after;
  run("G10 L1 P1 R0.2\nT1 M6\n", &after);  // a diameter G10 just set
  EXPECT_EQ(after.cutter.diameter, 0.4);
}

// And back: a VC that changes the cutter's diameter writes it as the spindle tool's D, the
// other lines byte for byte as they were; a check writes nothing; T0 or no table: nothing.
TEST_F(GcodeToolTable, VcWritesTheDiameterOfTheToolInTheSpindleToTheTable) {
  const std::string path = table_file(kTable);
  settings.cutter.diameter = 0.75;
  {
    Interpreter interp(settings, sink, io, store);
    interp.run(Script::from_text("T2 M6\n", "t.ngc"));
    EXPECT_EQ(interp.settings().cutter.diameter, 0.125);
    EXPECT_EQ(slurp(path), kTable);  // M6 reads the table, writes nothing
    interp.run(Script::from_text("VC, 0.3\n", "t.sbp"));
    EXPECT_EQ(interp.settings().cutter.diameter, 0.3);
    std::string expected = kTable;
    const std::string old_line = "T2  P2 D0.125 Z+1.0\n";
    expected.replace(expected.find(old_line), old_line.size(), "T2 P2 D+0.3 Z+1\n");
    EXPECT_EQ(slurp(path), expected);
    // G-code sees it: #5410 is tool 2's diameter now.
    io.printed.clear();
    interp.run(Script::from_text("(DEBUG, #5400 #5410)\n", "t.ngc"));
    EXPECT_EQ(io.printed, "2.000000 0.300000\n");
    settings = interp.settings();
  }
  // A check of another VC writes nothing.
  const std::string written = slurp(path);
  {
    InterpreterOptions o;
    o.dry_run = true;
    Interpreter interp(settings, sink, io, store, o);
    interp.run(Script::from_text("T2 M6\n", "t.ngc"));
    for (const Diagnostic& d : interp.check(Script::from_text("VC, 0.4\n", "t.sbp")))
      ADD_FAILURE() << format(d);
    EXPECT_EQ(slurp(path), written);
  }
  // T0 in the spindle: VC is VC's own.
  {
    Interpreter interp(settings, sink, io, store);
    interp.run(Script::from_text("M61 Q0\n", "t.ngc"));
    interp.run(Script::from_text("VC, 0.6\n", "t.sbp"));
    EXPECT_EQ(interp.settings().cutter.diameter, 0.6);
    EXPECT_EQ(slurp(path), written);
  }
}

TEST_F(GcodeToolTable, VcWithoutATableWritesNoFile) {
  settings.tool_table_path.clear();
  Interpreter interp(settings, sink, io, store);
  interp.run(Script::from_text("T2 M6\n", "t.ngc"));
  interp.run(Script::from_text("VC, 0.3\n", "t.sbp"));
  EXPECT_EQ(interp.settings().cutter.diameter, 0.3);
  EXPECT_TRUE(fs::is_empty(dir_));
}

// The preview cuts with the tool in the spindle: a 0.5 in cutter along Y = 0, then, after
// T2 M6 (D0.125), along Y = 1. A point 0.2 in from each line's axis is cut by the first
// (radius 0.25) and not by the second (radius 0.0625).
TEST_F(GcodeToolTable, ThePreviewCutsWithTheDiameterOfTheToolInTheSpindle) {
  table_file(kTable);
  settings.cutter.diameter = 0.5;
  const fs::path program = dir_ / "two_tools.ngc";
  std::ofstream(program) << "G20 G90\nG0 X0 Y0 Z0.5\nG1 Z-0.1 F30\nG1 X4\nG0 Z0.5\n"
                            "T2 M6\nG0 X0 Y1\nG1 Z-0.1\nG1 X4\nG0 Z0.5\nM2\n";
  const Toolpath path = load_toolpath(program.string(), settings);
  ASSERT_FALSE(path.has_errors()) << format(path.violations.front());
  ASSERT_EQ(path.cutter_changes.size(), 1u);
  EXPECT_EQ(path.cutter_changes[0].diameter, 0.125);
  EXPECT_EQ(path.cutter_changes[0].first, 4u);  // the four segments before M6
  Cutter flat;
  flat.diameter = 0.5;
  const HeightMap map = carve(path, flat, 0, 400);
  EXPECT_LT(*map.height(2, 0.2), -0.09);   // within the first cutter
  EXPECT_GT(*map.height(2, 1.2), -0.001);  // outside the second
  EXPECT_LT(*map.height(2, 1.03), -0.09);  // within the second
}


// OpenSBP's tool change (&Tool = n, then C9) as M6: tool n is in the spindle, its D is VC's
// when the table gives one, and the drawing state tells a preview the tool and its cutter at
// the C9 line. This shop's C9 sets no VC (the shipped one does not either).
class SbpToolChange : public GcodeToolTable {
 protected:
  // A recorder of the drawing states the interpreter tells its sink.
  struct DrawingSink : RecordingSink {
    void drawing_changed(const DrawingState& d) override { drawn.push_back(d); }
    std::vector<DrawingState> drawn;
  };
  void SetUp() override {
    GcodeToolTable::SetUp();
    fs::create_directories(dir_ / "macros");
    std::ofstream(dir_ / "macros" / "C9.sbp") << "' a tool change without VC\nJZ, 1\n";
    options.macro_dir = (dir_ / "macros").string();
  }
  // Runs `text` (an .sbp) into `drawing`; the settings it left.
  Settings run_sbp(const std::string& text) {
    drawing = DrawingSink();
    Interpreter interp(settings, drawing, io, store, options);
    interp.run(Script::from_text(text, "t.sbp"));
    state = interp.state();
    return interp.settings();
  }
  InterpreterOptions options;
  DrawingSink drawing;
};

TEST_F(SbpToolChange, TheToolOfC9IsInTheSpindleAndItsTableDiameterIsVcs) {
  table_file(kTable);
  settings.cutter.diameter = 0.75;
  Settings after = run_sbp("JZ, 0.5\nMX, 1\n&Tool = 2\nC9\nMX, 2\n");
  EXPECT_EQ(state.gcode.tool, 2);
  EXPECT_EQ(after.cutter.diameter, 0.125);  // tool 2's D
  ASSERT_EQ(drawing.drawn.size(), 2u);
  EXPECT_EQ(drawing.drawn[0].tool, 0);
  EXPECT_EQ(drawing.drawn[0].cutter_diameter, 0.75);
  EXPECT_EQ(drawing.drawn[1].tool, 2);
  EXPECT_EQ(drawing.drawn[1].cutter_diameter, 0.125);
  EXPECT_EQ(drawing.drawn[1].line, 4);  // the C9 line
  // Tool 4 has no D: VC's stays; tool 7 is not in the table: VC's stays, with a warning.
  settings = after;
  after = run_sbp("&Tool = 4\nC9\n");
  EXPECT_EQ(state.gcode.tool, 4);
  EXPECT_EQ(after.cutter.diameter, 0.125);
  io.warnings.clear();
  after = run_sbp("&Tool = 7\nC9\n");
  EXPECT_EQ(state.gcode.tool, 7);
  EXPECT_EQ(after.cutter.diameter, 0.125);
  ASSERT_EQ(io.warnings.size(), 1u);
  EXPECT_NE(io.warnings[0].message.find("tool 7 is not in the tool table"), std::string::npos)
      << io.warnings[0].message;
  EXPECT_EQ(io.warnings[0].loc.line, 2);
  // CN, 9 is C9 too.
  settings = after;
  after = run_sbp("&Tool = 3\nCN, 9\n");
  EXPECT_EQ(after.cutter.diameter, 0.5);
}

TEST_F(SbpToolChange, WithoutATableTheToolNumberStillReachesThePreview) {
  settings.tool_table_path.clear();
  settings.cutter.diameter = 0.25;
  const Settings after = run_sbp("&Tool = 3\nC9\nMX, 1\n");
  EXPECT_EQ(after.cutter.diameter, 0.25);  // VC's: nothing tells another
  ASSERT_FALSE(drawing.drawn.empty());
  EXPECT_EQ(drawing.drawn.back().tool, 3);
  EXPECT_TRUE(io.warnings.empty());
}

// The preview: a cut with tool 1 (D0.25), then &Tool = 3 and C9 (D0.5): the cuts after it
// are tool 3's, with its cutter, from the C9 line; the same diameter is a change too.
TEST_F(SbpToolChange, ThePreviewFollowsAToolChangeByC9) {
  table_file(kTable);
  settings.cutter.diameter = 0.25;
  const fs::path program = dir_ / "two_tools.sbp";
  std::ofstream(program) << "&Tool = 1\nC9\nMZ, -0.1\nMX, 4\nJZ, 0.5\n"
                            "&Tool = 3\nC9\nJ2, 0, 1\nMZ, -0.1\nMX, 4\nJZ, 0.5\n"
                            "&Tool = 1\nC9\nMX, 0\n";
  ToolpathOptions topts;
  topts.job.interpreter.macro_dir = options.macro_dir;
  const Toolpath path = load_toolpath(program.string(), settings, topts);
  ASSERT_FALSE(path.has_errors()) << format(path.violations.front());
  EXPECT_EQ(path.tool, 1);  // named before the first cut
  EXPECT_EQ(path.cutter_diameter, 0.25);
  ASSERT_EQ(path.cutter_changes.size(), 2u);
  EXPECT_EQ(path.cutter_changes[0].tool, 3);
  EXPECT_EQ(path.cutter_changes[0].diameter, 0.5);
  EXPECT_EQ(path.cutter_changes[0].line, 7u);  // the C9 line
  EXPECT_EQ(path.cutter_changes[1].tool, 1);
  EXPECT_EQ(path.cutter_changes[1].diameter, 0.25);
  EXPECT_EQ(path.segments[path.cutter_changes[0].first].tool, 1);
  EXPECT_EQ(path.segments.back().tool, 2);
  Cutter flat;
  flat.diameter = 0.25;
  const HeightMap map = carve(path, flat, 0, 400);
  EXPECT_GT(*map.height(2, 0.2), -0.001);  // outside tool 1's cut along Y = 0
  EXPECT_LT(*map.height(2, 1.2), -0.09);   // within tool 3's along Y = 1
}

}  // namespace
}  // namespace gantry
