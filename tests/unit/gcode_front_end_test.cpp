// The G-code front end (docs/gcode.md): golden canonical moves for the codes, located
// rejections, the offset model shared with OpenSBP's zero, G-code lines in OpenSBP files,
// and the WinCNC dialect.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/gcode.hpp"
namespace gantry {
namespace {

class CountingIO : public OperatorIO {
 public:
  void print(std::string_view text) override { printed += text; }
  bool confirm(std::string_view, const SourceLoc&) override {
    ++questions;
    return true;
  }
  std::optional<std::string> ask(std::string_view, std::string_view, std::string_view,
                                 const SourceLoc&) override {
    return std::nullopt;
  }
  std::string choose(std::string_view, const std::vector<std::string>& b, size_t d,
                     std::string_view, const SourceLoc&) override {
    return b.at(d);
  }
  void warn(const Diagnostic&) override {}
  std::string printed;
  int questions = 0;
};

class GcodeTest : public InterpreterFixture<CountingIO> {
 protected:
  // Runs `text` as the file `name`; the moves (lines and arcs unless `all`).
  std::vector<CanonMove> run(const std::string& text, const std::string& name = "t.nc",
                             bool all = false) {
    const std::vector<CanonMove>& moves = run_script(Script::from_text(text, name));
    return all ? moves : lines_and_arcs(moves);
  }
  // The first error a check finds (script errors included).
  Diagnostic error(const std::string& text, const std::string& name = "t.nc") {
    return first_error_of(check_script(Script::from_text(text, name)), text);
  }
};
void expect_at(const Vec6& got, const Vec6& want, const std::string& what) {
  for (int i = 0; i < kAxisCount; ++i) EXPECT_NEAR(got[i], want[i], 1e-12) << what << " axis " << i;
}

TEST_F(GcodeTest, LinesRapidsFeedsAndUnitsSwitchingMidFile) {
  const auto m =
      run("%\n(units switch mid-file)\nN10 g20 G90\nG0 X1 Y2\nG1 Z-0.5 F60\nG21\nG1 X50.8 ; mm\n"
          "G91 G1 Y-25.4 F254\nG20 x+.5\n%\n");
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[0].speed_class, SpeedClass::Jog);
  expect_at(m[0].to, v6(1, 2), "G0");
  EXPECT_EQ(m[1].speed_class, SpeedClass::Move);
  expect_at(m[1].to, v6(1, 2, -0.5), "G1");
  EXPECT_NEAR(m[1].speeds.xy, 1.0, 1e-12);  // F60 in/min = 1 in/s
  EXPECT_NEAR(m[1].speeds.z, 1.0, 1e-12);
  expect_at(m[2].to, v6(2, 2, -0.5), "G21 X50.8 mm");
  EXPECT_NEAR(m[2].speeds.xy, 1.0, 1e-12);  // F keeps its speed when the units change
  expect_at(m[3].to, v6(2, 1, -0.5), "G91 Y-25.4 mm");
  EXPECT_NEAR(m[3].speeds.xy, 254.0 / 25.4 / 60, 1e-12);  // F254 mm/min
  expect_at(m[4].to, v6(2.5, 1, -0.5), "G20 X+.5 incremental");
  EXPECT_EQ(m[4].loc.line, 9);
  EXPECT_EQ(m[4].loc.column, 1);
}

TEST_F(GcodeTest, ArcsInEveryPlaneAndDirection) {
  settings.machine.limit_checking = false;  // the arcs go round X 0, Y 0
  const auto m =
      run("G20 G90 G17 F60\nG0 X1 Y0 Z0\n"
          "G3 X0 Y1 I-1 J0\n"         // XY, counter-clockwise, a quarter about 0,0
          "G2 X1 Y0 I0 J-1\n"         // XY, clockwise back
          "G2 X0 Y-1 R1\n"            // R: the short way
          "G3 X1 Y0 R-1\n"            // R < 0: the long way round
          "G18 G2 X3 Z0 I1 K0\n"      // ZX: centre Z 0, X 2
          "G19 G3 Y2 Z0 J1 K0\n"      // YZ: centre Y 1, Z 0
          "G17 G3 X3 Y2 I1 J0 Z-1\n"  // a full helical turn
          "G2 X3 Y2 I1 P2\n");        // two turns clockwise
  ASSERT_EQ(m.size(), 9u);
  struct Want {
    ArcPlane plane;
    double cx, cy, sweep;
    Vec6 to;
  };
  const Want want[] = {
      {ArcPlane::XY, 0, 0, M_PI / 2, v6(0, 1)},     {ArcPlane::XY, 0, 0, -M_PI / 2, v6(1, 0)},
      {ArcPlane::XY, 0, 0, -M_PI / 2, v6(0, -1)},   {ArcPlane::XY, 1, -1, 3 * M_PI / 2, v6(1, 0)},
      {ArcPlane::ZX, 0, 2, -M_PI, v6(3, 0)},        {ArcPlane::YZ, 1, 0, M_PI, v6(3, 2)},
      {ArcPlane::XY, 4, 2, 2 * M_PI, v6(3, 2, -1)}, {ArcPlane::XY, 4, 2, -4 * M_PI, v6(3, 2, -1)}};
  for (size_t i = 0; i < 8; ++i) {
    const CanonMove& a = m[i + 1];
    const std::string what = "arc " + std::to_string(i);
    ASSERT_EQ(a.kind, MoveKind::Arc) << what;
    EXPECT_EQ(a.plane, want[i].plane) << what;
    EXPECT_NEAR(a.center_x, want[i].cx, 1e-12) << what;
    EXPECT_NEAR(a.center_y, want[i].cy, 1e-12) << what;
    EXPECT_NEAR(a.sweep, want[i].sweep, 1e-12) << what;
    for (int k = 0; k < kAxisCount; ++k) EXPECT_NEAR(a.to[k], want[i].to[k], 1e-12) << what;
    EXPECT_NEAR(a.speeds.xy, 1.0, 1e-12) << what;
  }
}

TEST_F(GcodeTest, CannedCyclesRetractToTheStartZWithG98AndToRWithG99) {
  const auto m =
      run("G20 G90 G17 F60\nG0 X0 Y0 Z1\n"
          "G98 G81 X1 Y1 Z-0.5 R0.1\nX2\nG99 X3\nG80\n"
          "G0 Z1\nG91 G83 X1 Y0 Z-0.6 R-0.9 Q0.25\nG90 G80\n");
  std::vector<std::pair<SpeedClass, Vec6>> want = {
      {SpeedClass::Jog, v6(0, 0, 1)},
      {SpeedClass::Jog, v6(1, 1, 1)},
      {SpeedClass::Jog, v6(1, 1, 0.1)},
      {SpeedClass::Move, v6(1, 1, -0.5)},
      {SpeedClass::Jog, v6(1, 1, 1)},
      {SpeedClass::Jog, v6(2, 1, 1)},
      {SpeedClass::Jog, v6(2, 1, 0.1)},
      {SpeedClass::Move, v6(2, 1, -0.5)},
      {SpeedClass::Jog, v6(2, 1, 1)},
      {SpeedClass::Jog, v6(3, 1, 1)},
      {SpeedClass::Jog, v6(3, 1, 0.1)},
      {SpeedClass::Move, v6(3, 1, -0.5)},
      {SpeedClass::Jog, v6(3, 1, 0.1)},
      {SpeedClass::Jog, v6(3, 1, 1)},
      // G83 in G91: R 0.9 below the start Z, the bottom 0.6 below R, pecks of 0.25, each
      // back to R and down again to 0.01 above the last depth.
      {SpeedClass::Jog, v6(4, 1, 1)},
      {SpeedClass::Jog, v6(4, 1, 0.1)},
      {SpeedClass::Move, v6(4, 1, -0.15)},
      {SpeedClass::Jog, v6(4, 1, 0.1)},
      {SpeedClass::Jog, v6(4, 1, -0.14)},
      {SpeedClass::Move, v6(4, 1, -0.4)},
      {SpeedClass::Jog, v6(4, 1, 0.1)},
      {SpeedClass::Jog, v6(4, 1, -0.39)},
      {SpeedClass::Move, v6(4, 1, -0.5)},
      {SpeedClass::Jog, v6(4, 1, 0.1)}};  // G99 is still in force
  ASSERT_EQ(m.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(m[i].speed_class, want[i].first) << "move " << i;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m[i].to[k], want[i].second[k], 1e-12) << "move " << i;
  }
}

TEST_F(GcodeTest, WorkOffsetsG92ToolLengthAndStoredPositions) {
  auto m =
      run("G20 F60\nG10 L2 P2 X1 Y1\nG55 G0 X0 Y0\nG54 G0 X0 Y0\n"  // G55's 0 is at 1, 1
          "G0 X2\nG92 X0\nG0 X1\nG92.1\nG0 X1\n"                    // G92: X 2 reads 0
          "G10 L1 P1 Z0.5\nG43 H1\nG0 Z0\nG49\nG0 Z0\n"             // tool 1 is 0.5 long
          "G0 X1 Y1\nG28.1\nG0 X5\nG28\n"                           // G28 returns to 1, 1
          "G10 L2 P1 X2\nG0 X0\nG53 G0 X1\n");                      // G53: the table's own X
  const std::vector<Vec6> want = {v6(1, 1), v6(0, 0),      v6(2, 0),    v6(3, 0),
                                  v6(1, 0), v6(1, 0, 0.5), v6(1, 0, 0), v6(1, 1),
                                  v6(5, 1), v6(1, 1),      v6(2, 1),    v6(1, 1)};
  ASSERT_EQ(m.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) expect_at(m[i].to, want[i], "move " + std::to_string(i));
  EXPECT_EQ(state.gcode.system, 0);
  EXPECT_NEAR(state.zero[0], 2, 1e-12);  // G54's origin is SB3's zero
}

TEST_F(GcodeTest, G54IsTheZeroOfOpenSbpSoBothFrontEndsAgree) {
  const auto m =
      run("MX, 2\nZX\nG0 X1\nG10 L20 P1 X0\nMX, 1\nG10 L2 P2 X5\nG55\nMX, 1\n", "mixed.sbp");
  ASSERT_EQ(m.size(), 4u);
  EXPECT_NEAR(m[0].to[0], 2, 1e-12);  // MX, 2
  EXPECT_NEAR(m[1].to[0], 3, 1e-12);  // ZX made X 2 working 0: G0 X1 is table X 3
  EXPECT_NEAR(m[2].to[0], 4, 1e-12);  // G10 L20 made table X 3 working 0 for both
  EXPECT_NEAR(m[3].to[0], 6, 1e-12);  // G55's 0 is at table X 5
  EXPECT_EQ(state.gcode.system, 1);
  EXPECT_NEAR(state.zero[0], 5, 1e-12);
  EXPECT_NEAR(state.gcode.origin[0][0], 3, 1e-12);  // G54 kept for when it is selected again
}

TEST_F(GcodeTest, ParametersExpressionsAndFunctions) {
  const auto m =
      run("#1=2\n#<depth> = [#1 * 2]\nG0 X#1 Y#<depth> Z[SIN[30]*2]\n"
          "#2 = [ATAN[1]/[1] + 3 MOD 2 + 2 ** 3]\nG0 X[#2 / 10] (MSG, done)\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[0].to, v6(2, 4, 1.0000000000000000), "params");
  EXPECT_NEAR(m[0].to[2], 1, 1e-12);
  EXPECT_NEAR(m[1].to[0], (45 + 1 + 8) / 10.0, 1e-12);
  EXPECT_EQ(io.printed, "done\n");
}

TEST_F(GcodeTest, SpindleCoolantOutputsDwellsAndStops) {
  const auto m = run("M3 S12000\nM8\nM7\nG4 P0.5\nG4 P0\nM9\nM5\nM64 P4\n", "t.nc", true);
  ASSERT_EQ(m.size(), 10u);
  auto output = [&](size_t i, int n, bool on) {
    EXPECT_EQ(m[i].kind, MoveKind::Output) << i;
    EXPECT_EQ(m[i].output, n) << i;
    EXPECT_EQ(m[i].output_on, on) << i;
  };
  output(0, 1, true);
  output(1, 2, true);
  output(2, 3, true);
  EXPECT_EQ(m[3].kind, MoveKind::Dwell);
  EXPECT_EQ(m[3].dwell_s, 0.5);
  EXPECT_EQ(m[4].kind, MoveKind::Stop);
  output(5, 3, false);
  output(6, 2, false);
  output(7, 1, false);
  output(8, 4, true);
  output(9, 4, false);  // the job's end turns every switch off
}

TEST_F(GcodeTest, M2EndsTheFileAndGcodeLinesRunInOpenSbpFiles) {
  EXPECT_EQ(run("G0 X1\nM2\nG0 X5\n").size(), 1u);
  const auto m = run("MX, 1\nG1 Y2 F60\nM3, 3, 2, 0\nM30\nMX, 9\n", "part.sbp");
  ASSERT_EQ(m.size(), 3u);
  expect_at(m[1].to, v6(1, 2), "G1 in OpenSBP");
  expect_at(m[2].to, v6(3, 2), "M3 stays OpenSBP's move");
}

TEST_F(GcodeTest, ProbeWithoutAMachineReachesItsTargetAtTheFeed) {
  const auto m = run("G20 F6\nG38.2 Z-1\n");
  ASSERT_EQ(m.size(), 1u);
  expect_at(m[0].to, v6(0, 0, -1), "G38.2");
  EXPECT_NEAR(m[0].speeds.z, 0.1, 1e-12);
}

TEST_F(GcodeTest, WinCncDialect) {
  settings.gcode_dialect = GcodeDialect::WinCNC;
  const auto m = run("G21 G0 X2.54\nG22 G0 Y25.4\nG4 [Ready To Start Section 2]\nG0 X Y\n");
  ASSERT_EQ(m.size(), 3u);
  expect_at(m[0].to, v6(1, 0), "G21: centimetres");
  expect_at(m[1].to, v6(1, 1), "G22: millimetres");
  EXPECT_EQ(io.questions, 1);  // G4 without X waits for the operator
  expect_at(m[2].to, v6(0, 0), "bare letters are 0");
}

TEST_F(GcodeTest, RejectionsAreLocatedErrors) {
  struct Case {
    const char* text;
    int line, column;
    const char* says;
  };
  const Case cases[] = {
      {"G0 G1 X1\n", 1, 4, "same modal group"},
      {"G20\nG1 X1\n", 2, 1, "G1 needs a feed rate"},
      {"G20 F10\nG0 X1\nG2 X2 Y1 I0.5 J0\n", 3, 1, "radii differ"},
      {"F10\nG2 X1 Y1\n", 2, 1, "needs its centre"},
      {"G2 X1 Y1 I1 R1 F10\n", 1, 13, "not both"},
      {"G5 X1\n", 1, 1, "G5 is refused: splines"},
      {"M98\n", 1, 1, "M98 needs P"},
      {"G81 X1 R0.1 F10\n", 1, 1, "needs Z"},
      {"G81 X1 Z-1 F10\n", 1, 1, "needs R"},
      {"G0 X1 X2\n", 1, 7, "appears twice"},
      {"G0 X[1 +\n", 1, 5, "never closed"},
      {"G0 X\n", 1, 4, "needs a value"},
      {"G0 E1\n", 1, 4, "not a G-code word letter"},
      {"G0 X1 (note\n", 1, 7, "not closed"},
      {"X1\n", 1, 1, "without a motion mode"},
      {"G1 X1 I1 F10\n", 1, 7, "centre offset"},
      // Issue 22: a value out of range says so, where it is (F-10 said "needs a feed rate").
      {"G1 X1 F-10\n", 1, 7, "F-10 is out of range: a feed rate cannot be negative"},
      {"F-10\nG1 X1\n", 1, 1, "F-10 is out of range"},
      {"G4 P100000000000000\n", 1, 1, "a wait of 100000000000000 s is out of range"},
      {"G4 P100000000000000000000\n", 1, 1, "a wait of 1e+20 s is out of range"},
      {"G20 F10\nG2 X0 Y0 I1 J0 P1000000000000\n", 2, 16,
       "turns: an arc may have at most 1000000 chords"},
  };
  for (const Case& c : cases) {
    const Diagnostic d = error(c.text);
    EXPECT_EQ(d.loc.line, c.line) << c.text;
    EXPECT_EQ(d.loc.column, c.column) << c.text << d.message;
    EXPECT_NE(d.message.find(c.says), std::string::npos) << c.text << d.message;
  }
  // Nothing moves: the bad block is found before the first move.
  sink = RecordingSink();
  EXPECT_EQ(sink.moves.size(), 0u);
}

TEST_F(GcodeTest, WhichLinesAndFilesAreGcode) {
  EXPECT_TRUE(is_gcode_line("G1 X1"));
  EXPECT_TRUE(is_gcode_line("  n10 g0 x1"));
  EXPECT_TRUE(is_gcode_line("M3 S12000"));
  EXPECT_TRUE(is_gcode_line("M30"));
  EXPECT_FALSE(is_gcode_line("M3, 1, 2, 3"));
  EXPECT_FALSE(is_gcode_line("M5"));
  EXPECT_FALSE(is_gcode_line("MX, 1"));
  EXPECT_FALSE(is_gcode_line("GOTO END"));
  EXPECT_TRUE(is_gcode_file("job.NC", ""));
  EXPECT_TRUE(is_gcode_file("job.tap", "'x"));
  EXPECT_FALSE(is_gcode_file("job.sbp", "G0 X1"));
  EXPECT_TRUE(is_gcode_file("job.txt", "\n%\nG0 X1"));
  EXPECT_FALSE(is_gcode_file("job.txt", "'comment\nMX, 1"));
}

}  // namespace
}  // namespace gantry
