// The WinCNC G-code dialect (gcode_dialect = "wincnc"; docs/gcode.md, "The WinCNC dialect").
// Golden values come from the WinCNC Users Guide (shared seed 003): each test names the section
// whose example or statement it checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "../support/interpreter_fixture.hpp"
namespace gantry {
namespace {

using CountingIO = AnsweringIO;

class WinCncTest : public InterpreterFixture<CountingIO> {
 protected:
  WinCncTest() {
    settings.gcode_dialect = GcodeDialect::WinCNC;
    settings.axes[0].max = 96;  // a 4 x 8 ft table: the manual's examples work at X20 Y20
    settings.axes[1].max = 48;
  }
  // Runs `text`; the moves (lines and arcs unless `all`).
  std::vector<CanonMove> run(const std::string& text, bool all = false) {
    io = CountingIO();
    const std::vector<CanonMove>& moves = run_script(Script::from_text(text, "t.tap"));
    return all ? moves : lines_and_arcs(moves);
  }
  // The first error a check finds (script errors included).
  Diagnostic error(const std::string& text) {
    return first_error_of(check_script(Script::from_text(text, "t.tap")), text);
  }
};
void expect_at(const CanonMove& m, const Vec6& want, const std::string& what) {
  for (int i = 0; i < kAxisCount; ++i) EXPECT_NEAR(m.to[i], want[i], 1e-9) << what << " axis " << i;
}

// ---- local zero: G92, G92.1, G92.2, G92.3, L92 ---------------------------------------------

// Manual, "Coordinate System": "G92.1 X20Y20Z1 — Move LZ 20" in XY and 1" above the table";
// "Using G92.1 it is not necessary to move to the workpiece first".
TEST_F(WinCncTest, G92_1ShiftsLocalZeroWithoutMoving) {
  const auto m = run("G90\nG92.1 X20Y20Z1\nG0 X0 Y0 Z0\n");
  ASSERT_EQ(m.size(), 1u);  // the G92.1 line itself moves nothing
  expect_at(m[0], v6(20, 20, 1), "X0 Y0 Z0 is the workpiece corner, 1 above the table");
}

// Manual, G92.1: "G92.1 X0 leaves YZW local coordinates but sets X back to absolute".
TEST_F(WinCncTest, G92_1X0RestoresOnlyX) {
  const auto m = run("G92.1 X20Y20Z1\nG92.1 X0\nG0 X1 Y1 Z0\n");
  ASSERT_EQ(m.size(), 1u);
  expect_at(m[0], v6(1, 21, 1), "X absolute, Y and Z still local");
}

// Manual, G92.2: "needs to [be] set to cut .010" deeper, G92.2 Z-.01 will accomplish this".
TEST_F(WinCncTest, G92_2ZMinusPoint01CutsDeeper) {
  const auto m = run("G92.1 Z1\nG0 Z0\nG92.2 Z-.01\nG0 Z0\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[0], v6(0, 0, 1), "Z0 before");
  expect_at(m[1], v6(0, 0, 0.99), "Z0 is .010 deeper after G92.2 Z-.01");
}

// Manual, "Coordinate System": "G1 X10 Y10 ... Next type G92X0Y0 ... X & Y will now show as X0,
// Y0"; G92: "Use G92 alone to restore the Machine Coordinates".
TEST_F(WinCncTest, G92SetsAndAloneRestoresMachineCoordinates) {
  const auto m = run("G1 X10 Y10 F60\nG92X0Y0\nG0 X1\nG92\nG0 X1\n");
  ASSERT_EQ(m.size(), 3u);
  expect_at(m[1], v6(11, 10), "X1 from the local zero at X10 Y10");
  expect_at(m[2], v6(1, 10), "X1 in machine coordinates");
}

// Manual, G92.3: "If G92 positions are set on any axis then they will be stored and cleared.
// The next G92.3 call will restore the previous G92 values even if they have been cleared by
// using G92."
TEST_F(WinCncTest, G92_3StoresClearsAndRestores) {
  const auto m = run("G92.1 X5\nG92.3\nG0 X1\nG92\nG92.3\nG0 X1\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[0], v6(1, 0), "stored and cleared");
  expect_at(m[1], v6(6, 0), "restored after G92");
  EXPECT_EQ(error("G92.3 X1\n").message.find("G92.3 takes no axes"), 0u);
}

// Manual, G92: "If running a .tap ... file, and there is a G92 in the file, and the user wishes
// to maintain that G92 after the file is done and closed, then a L92 must be added"; L92:
// "the original G92 system is restored" otherwise.
TEST_F(WinCncTest, AFilesG92IsRestoredAtItsEndUnlessL92) {
  run("G92.1 X5 Y2\nG0 X0\n");
  EXPECT_EQ(state.gcode.axis_offset[0], 0);
  EXPECT_EQ(state.gcode.axis_offset[1], 0);
  run("G92.1 X5 Y2\nG0 X0\nL92\n");
  EXPECT_EQ(state.gcode.axis_offset[0], 5);
  EXPECT_EQ(state.gcode.axis_offset[1], 2);
}

// ---- G53, G0.1, L53: the head lift; G28 of named axes ---------------------------------------

// Manual, G53: "G53 alone will lift all vertical or type 3 axes". Fusion 360's WinCNC post
// retracts with a bare G53 before the next rapid: the rapid must not go sideways at depth.
TEST_F(WinCncTest, BareG53LiftsZBeforeTheNextRapid) {
  const double top = settings.axes[2].max;  // the top of Z's travel (docs/gcode.md)
  const auto m = run("G0 X1 Y1 Z0.5\nG1 Z-0.2 F30\nG53\nG0 X5 Y5\n");
  ASSERT_EQ(m.size(), 4u);
  expect_at(m[2], v6(1, 1, top), "G53 lifts Z straight up");
  EXPECT_EQ(m[2].speed_class, SpeedClass::Jog);
  EXPECT_EQ(m[2].loc.line, 3);
  expect_at(m[3], v6(5, 5, top), "the rapid runs at the top");
  // A local zero or tool measure does not change where the top is.
  const auto n = run("G92.1 Z1\nG53\n");
  ASSERT_EQ(n.size(), 1u);
  expect_at(n[0], v6(0, 0, top), "the top in machine coordinates");
  EXPECT_TRUE(run("G53 Z5.5\nG53\n").size() == 1u);  // already at the top: no move
}

// Manual, G53: "Moves to the position specified at rapid velocity, ignoring tool measures and
// local coordinates".
TEST_F(WinCncTest, G53WithAxesRapidsInMachineCoordinates) {
  const auto m = run("G92.1 X5 Y5\nG1 X1 F60\nG53 X2 Y3\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[1], v6(2, 3), "machine X2 Y3");
  EXPECT_EQ(m[1].speed_class, SpeedClass::Jog);  // a rapid in G1 mode
}

// Manual, G0.1: "First lifts all vertical heads then moves the position specified at Rapid
// velocity then drops the vertical heads back to their previous positions."
TEST_F(WinCncTest, G0_1LiftsMovesAndDropsBack) {
  const double top = settings.axes[2].max;
  const auto m = run("G0 X1 Y1 Z0.25\nG0.1 X3 Y2\n");
  ASSERT_EQ(m.size(), 4u);
  expect_at(m[1], v6(1, 1, top), "lift");
  expect_at(m[2], v6(3, 2, top), "rapid at the top");
  expect_at(m[3], v6(3, 2, 0.25), "back down");
  // L53 raises the (one) head as high as possible.
  const auto l = run("G0 Z1\nL53\n");
  ASSERT_EQ(l.size(), 2u);
  expect_at(l[1], v6(0, 0, top), "L53");
}

// Manual, "Homing": "G28 can also be used to home only specified axes. (I.e. G28Z homes only
// the Z axis)"; G28: "All axes are moved if none are specified".
TEST_F(WinCncTest, G28HomesOnlyTheNamedAxes) {
  const auto z = run("G0 X2 Y3\nG28 Z\n", true);
  ASSERT_GT(z.size(), 1u);
  for (size_t i = 1; i < z.size(); ++i) {
    EXPECT_NEAR(z[i].to[0], 2, 1e-9) << i;  // X and Y stay
    EXPECT_NEAR(z[i].to[1], 3, 1e-9) << i;
  }
  bool z_moved = false;
  for (size_t i = 1; i < z.size(); ++i) z_moved |= z[i].to[2] != 0;
  EXPECT_TRUE(z_moved);
  const auto all = run("G0 X2 Y3\nG28\n", true);
  bool x_moved = false, y_moved = false;
  for (size_t i = 1; i < all.size(); ++i) {
    x_moved |= all[i].to[0] != 2;
    y_moved |= all[i].to[1] != 3;
  }
  EXPECT_TRUE(x_moved && y_moved) << "G28 alone homes every axis";
  const Diagnostic d = error("G28 A\n");
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_NE(d.message.find("G28 A: A is not in the profile's homing order"), std::string::npos)
      << d.message;
}

// ---- M codes -----------------------------------------------------------------------------

// Manual, M11-M14: "Channel specified by # is turned on / off".
TEST_F(WinCncTest, M11ToM14SwitchOutputs) {
  const auto m = run("M11 C2\nM13C3\nM14 C3\nM12C2\n", true);
  std::vector<std::pair<int, bool>> switched;
  for (const CanonMove& c : m)
    if (c.kind == MoveKind::Output && c.loc.line <= 4) switched.emplace_back(c.output, c.output_on);
  EXPECT_EQ(switched,
            (std::vector<std::pair<int, bool>>{{2, true}, {3, true}, {3, false}, {2, false}}));
  Diagnostic d = error("M11\n");
  EXPECT_NE(d.message.find("M11 needs C"), std::string::npos) << d.message;
  d = error("M11 D7\n");  // manual, M11: "M11D7 would turn on the first 3 channels" of a bank
  EXPECT_NE(d.message.find("drill bank"), std::string::npos) << d.message;
  d = error("M12 C13\n");
  EXPECT_NE(d.message.find("from 1 to 12"), std::string::npos) << d.message;
  // A move on an M code's line would be dropped: refused.
  d = error("G1 F10\nX1 M11 C2\n");
  EXPECT_EQ(d.loc.column, 1);
  EXPECT_NE(d.message.find("M11 does not take X"), std::string::npos) << d.message;
}

// Manual, M17.4: "1 will run the next line, 0 will skip the next line"; M18.4 the reverse.
TEST_F(WinCncTest, RunNextAndSkipNext) {
  auto m = run("M17.4 C0\nG0 X1\nG0 Y1\n");
  ASSERT_EQ(m.size(), 1u);
  expect_at(m[0], v6(0, 1), "X skipped");
  m = run("M18.4 C0\n(a comment line is not the next line)\nG0 X1\nG0 Y1\n");
  ASSERT_EQ(m.size(), 2u);
  // M17.3/M18.3 read the virtual inputs L61/L60 set.
  m = run("L61 C5\nM17.3 C5\nG0 X1\nM18.3 C5\nG0 Y1\nL60 C5\nM18.3 C5\nG0 Z1\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[0], v6(1, 0), "input 5 on: X runs");
  expect_at(m[1], v6(1, 0, 1), "Y skipped, Z runs once it is off");
  // M17.2/M18.2 read the outputs; M17.1 in a run without a machine takes D (simulate logic).
  m = run("M11 C2\nM17.2 C2\nG0 X1\nM18.2 C2\nG0 Y1\nM17.1 D1 C3\nG0 Z1\nM17.1 C3\nG0 Z2\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[1], v6(1, 0, 1), "D1: input 3 taken as on");
  // L110 / L111 / L112 (manual: "Run next line if tool number is equal to T#"; "Skip next").
  m = run("L110 T3\nL111 T3\nG0 X1\nL112 T3\nG0 Y1\nL111 T4\nG0 Z1\n");
  ASSERT_EQ(m.size(), 1u);
  expect_at(m[0], v6(1, 0), "tool 3");
}

// Manual, M17: "Wait for channel specified by # to come on"; M18: "to go off".
TEST_F(WinCncTest, M17WaitsForTheInput) {
  run("M17 C3\nM18 C4\n");
  ASSERT_EQ(io.questions.size(), 2u);  // no machine: the operator is asked
  EXPECT_NE(io.questions[0].find("M17: waiting for input 3 to close"), std::string::npos);
  EXPECT_NE(io.questions[1].find("M18: waiting for input 4 to open"), std::string::npos);
}

// Manual, "Tool Length Offset": "Move the Z head tool tip to the table. Command M37 Z0. M37
// turns on G43 ... disabled using G49 and re-enabled with G43 without re-measuring."
TEST_F(WinCncTest, M37MeasuresAndG43G49SwitchIt) {
  const auto m = run("G0 Z-1\nM37 Z0\nG0 Z0.5\nG49\nG0 Z0.5\nG43\nG0 Z0\n");
  ASSERT_EQ(m.size(), 4u);
  expect_at(m[1], v6(0, 0, -0.5), "Z0.5 above the measured tip");
  expect_at(m[2], v6(0, 0, 0.5), "G49: no offset");
  expect_at(m[3], v6(0, 0, -1), "G43: the measure again");
  EXPECT_TRUE(io.questions.empty());
  // A tool number with no tool changer: the operator loads it; L110 brings its measure back.
  const auto t = run("G0 Z-1\nM37 Z0 T5\nG0 Z1\nM37 Z0 T6\nL110 T5\nG0 Z0\n");
  ASSERT_EQ(io.questions.size(), 2u);
  EXPECT_NE(io.questions[0].find("load tool 5"), std::string::npos) << io.questions[0];
  expect_at(t.back(), v6(0, 0, -1), "tool 5's measure");
  const Diagnostic d = error("M37\n");
  EXPECT_NE(d.message.find("M37 needs Z"), std::string::npos) << d.message;
  EXPECT_NE(error("G43 H1\n").message.find("takes no H"), std::string::npos);
}

TEST_F(WinCncTest, M99_1Aborts) {
  const Diagnostic d = error("G0 X1\nM99.1\nG0 X2\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_NE(d.message.find("M99.1"), std::string::npos);
}

// ---- L codes -------------------------------------------------------------------------------

// Manual, L90/L91: "specify G90 [G91] coordinates on one line without changing program mode".
TEST_F(WinCncTest, L90AndL91AreForOneLine) {
  const auto m = run("G90\nG0 X1\nL91 G0 X1\nG0 X1\nG91\nL90 G0 X5\nG0 X1\n");
  ASSERT_EQ(m.size(), 5u);
  expect_at(m[1], v6(2, 0), "L91: relative once");
  expect_at(m[2], v6(1, 0), "G90 again");
  expect_at(m[3], v6(5, 0), "L90: absolute once");
  expect_at(m[4], v6(6, 0), "G91 again");
}

// Manual, L3: "Stores current position of each axis specified. Values specified are ignored";
// L4: "Moves each axis specified to the last L3 position stored".
TEST_F(WinCncTest, L3StoresAndL4Returns) {
  const auto m = run("G0 X1 Y2\nL3 XY\nG0 X5 Y5\nL4 X\n");
  ASSERT_EQ(m.size(), 3u);
  expect_at(m[2], v6(1, 5), "X back to 1, Y stays");
  EXPECT_NE(error("L4 Z\n").message.find("no position of Z was stored"), std::string::npos);
}

// Manual, L28: "does not move the machine, but sets the current position to the values".
TEST_F(WinCncTest, L28SetsMachineCoordinatesWithoutMoving) {
  const auto m = run("G0 X1\nL28 X10\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR(state.position[0] + state.zero[0], 10, 1e-12);  // the table base
}

// Manual, "Braces": "G0Z{TH1+2} moves Z to tool height 1, plus 2 units"; "ANY use of braces
// requires a value or axis spec and a number".
TEST_F(WinCncTest, BracesSubstituteValues) {
  auto m = run("G0 Z-1\nM37 Z0\nG49\nG0 Z{TH1+2}\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[1], v6(0, 0, 1), "TH1 (-1) + 2");
  m = run("L110 T2\nG92.1 X4\nG0 X{TP1*3} Y{LZ0-1.5}\nG0 X{X+1} Y{ Y / 2 }\n");
  ASSERT_EQ(m.size(), 2u);
  expect_at(m[0], v6(10, 2.5), "X6 and Y2.5 from local zero X4");
  expect_at(m[1], v6(11, 1.25), "X+1, Y/2");
  Diagnostic d = error("G0 X{TH1}\n");
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_NE(d.message.find("need a value and a number"), std::string::npos) << d.message;
  d = error("G0 X{2+TH1}\n");
  EXPECT_NE(d.message.find("numbers only"), std::string::npos) << d.message;
  d = error("G0 X{TH2+1}\n");
  EXPECT_NE(d.message.find("second tool changer"), std::string::npos) << d.message;
  d = error("G0 X{THZ+1}\n");
  EXPECT_NE(d.message.find("torch height"), std::string::npos) << d.message;
  d = error("G0 X{TP1+1\n");
  EXPECT_NE(d.message.find("never closed"), std::string::npos) << d.message;
  settings.gcode_dialect = GcodeDialect::Standard;
  d = error("G0 X{TP1+1}\n");
  EXPECT_NE(d.message.find("WinCNC's substitution"), std::string::npos) << d.message;
}

// ---- G4, canned cycles ---------------------------------------------------------------------

// Manual, G4: "If no time is specified, then the machine will be stopped until the operator
// pushes ENTER. Place a comment after the dwell to prompt the operator. Example: G4 [Ready To
// Start Section 2]".
TEST_F(WinCncTest, G4WaitsForTheOperatorOrDwellsXSeconds) {
  const auto m = run("G4 [Ready To Start Section 2]\nG4 X1.5\nG4\n", true);
  ASSERT_EQ(io.questions.size(), 2u);
  EXPECT_EQ(io.questions[0], "Ready To Start Section 2");
  EXPECT_EQ(io.questions[1], "G4: press Enter to continue");
  bool dwelled = false;
  for (const CanonMove& c : m) dwelled |= c.kind == MoveKind::Dwell && c.dwell_s == 1.5;
  EXPECT_TRUE(dwelled);
}

std::vector<double> zs(const std::vector<CanonMove>& m) {
  std::vector<double> out;
  for (const CanonMove& c : m) out.push_back(std::round(c.to[2] * 1e9) / 1e9);
  return out;
}

// Manual, G81: "Moves to Z specified at Feed velocity. Moves back to R at Rapid velocity"
// (to R even from higher up); G83: "moves at Rapid velocity to within 0.05" of previous peck
// depth"; G73: "lifts 0.05" at Rapid velocity to break the chip".
TEST_F(WinCncTest, CyclesRetractToRWithA0_05PeckClearance) {
  auto m = run("G0 Z1\nG81 X1 Y1 Z-0.5 R0.1 F30\n");
  EXPECT_EQ(zs(m), (std::vector<double>{1, 1, 0.1, -0.5, 0.1}));
  m = run("G0 Z1\nG83 X0 Y0 Z-0.3 R0.1 Q0.1 F30\n");
  EXPECT_EQ(zs(m), (std::vector<double>{1, 0.1, 0, 0.1, 0.05, -0.1, 0.1, -0.05, -0.2, 0.1, -0.15,
                                        -0.3, 0.1}));
  m = run("G0 Z1\nG73 X0 Y0 Z-0.2 R0.1 Q0.1 F30\n");
  EXPECT_EQ(zs(m), (std::vector<double>{1, 0.1, 0, 0.05, -0.1, -0.05, -0.2, 0.1}));
}

// ---- every code of the manual: it works or it is refused by name ------------------------------

// True when `message` names `code` (not as the start of a longer code: L10 is not L101).
bool names(const std::string& message, const std::string& code) {
  for (size_t at = message.find(code); at != std::string::npos; at = message.find(code, at + 1)) {
    const size_t end = at + code.size();
    if (end == message.size() || !(std::isdigit(static_cast<unsigned char>(message[end])) ||
                                   (message[end] == '.' && end + 1 < message.size() &&
                                    std::isdigit(static_cast<unsigned char>(message[end + 1])))))
      return true;
  }
  return false;
}

// Every G, M and L code in the manual's "G Codes", "L Codes" and "M Codes" chapters (and G58,
// G59, which its workspace section names): each either runs or is refused with a located
// error naming it, and a refused one moves nothing.
TEST_F(WinCncTest, EveryCodeOfTheManualWorksOrIsRefusedByName) {
  const std::vector<std::pair<std::string, std::string>> codes = {
      {"G0", "G0 X1"},
      {"G0.1", "G0.1 X1"},
      {"G1", "G1 X1 F10"},
      {"G2", "G2 X2 Y0 I1 J0 F10"},
      {"G3", "G0 Y2\nG3 X2 Y2 I1 J0 F10"},
      {"G4", "G4 X0.1"},
      {"G5", "G5 T0"},
      {"G9", "G9 S2"},
      {"G20", "G20"},
      {"G21", "G21"},
      {"G22", "G22"},
      {"G23", "G23"},
      {"G28", "G28 Z"},
      {"G31", "G31"},
      {"G40", "G40"},
      {"G41", "G41"},
      {"G42", "G42"},
      {"G43", "G43"},
      {"G49", "G49"},
      {"G50", "G50"},
      {"G51", "G51 X2"},
      {"G52", "G52 I1 J1 A10"},
      {"G52.1", "G52.1 A1 B2"},
      {"G53", "G53"},
      {"G54", "G54"},
      {"G55", "G55"},
      {"G56", "G56"},
      {"G57", "G57"},
      {"G58", "G58"},
      {"G59", "G59"},
      {"G73", "G73 X0 Y0 Z-0.2 R0.1 Q0.1 F10"},
      {"G80", "G80"},
      {"G81", "G81 X0 Y0 Z-0.2 R0.1 F10"},
      {"G82", "G82 X0 Y0 Z-0.2 R0.1 P100 F10"},
      {"G83", "G83 X0 Y0 Z-0.2 R0.1 Q0.1 F10"},
      {"G90", "G90"},
      {"G91", "G91"},
      {"G92", "G92 X0"},
      {"G92.1", "G92.1 X1"},
      {"G92.2", "G92.2 X1"},
      {"G92.3", "G92.3"},
      {"G92.4", "G92.4 A1 B2 C3 D4"},
      {"G93", "G93"},
      {"G94", "G94"},
      {"G95", "G95 F10"},
      {"M11", "M11 C1"},
      {"M12", "M12 C1"},
      {"M13", "M13 C1"},
      {"M14", "M14 C1"},
      {"M17", "M17 C1"},
      {"M17.1", "M17.1 C1"},
      {"M17.2", "M17.2 C1"},
      {"M17.3", "M17.3 C1"},
      {"M17.4", "M17.4 C1"},
      {"M18", "M18 C1"},
      {"M18.1", "M18.1 C1"},
      {"M18.2", "M18.2 C1"},
      {"M18.3", "M18.3 C1"},
      {"M18.4", "M18.4 C1"},
      {"M28", "M28"},
      {"M29", "M29"},
      {"M37", "M37 Z0"},
      {"M37.1", "M37.1 Z0"},
      {"M37.2", "M37.2 Z0"},
      {"M37.3", "M37.3 S1"},
      {"M98", "M98"},
      {"M98.1", "M98.1"},
      {"M99", "M99"},
      {"M99.1", "M99.1"}};
  std::vector<std::pair<std::string, std::string>> all = codes;
  // L codes: the working ones with their words, the others bare.
  const std::vector<std::pair<std::string, std::string>> l_working = {
      {"L3", "L3 X"},      {"L4", "L3 X\nL4 X"}, {"L28", "L28 X0"},    {"L60", "L60 C1"},
      {"L61", "L61 C1"},   {"L90", "L90 G0 X1"}, {"L91", "L91 G0 X1"}, {"L110", "L110 T1"},
      {"L111", "L111 T1"}, {"L112", "L112 T1"}};
  all.insert(all.end(), l_working.begin(), l_working.end());
  for (const char* l :
       {"L1",     "L1.1", "L1.2",   "L5",   "L6",     "L7",    "L8",     "L9",    "L10",    "L11",
        "L12",    "L13",  "L20",    "L21",  "L22",    "L22.1", "L23",    "L23.1", "L28.1",  "L29",
        "L29.1",  "L30",  "L30.1",  "L31",  "L32",    "L33",   "L34",    "L35",   "L36",    "L36.1",
        "L36.2",  "L37",  "L37.1",  "L38",  "L39",    "L40",   "L41",    "L48",   "L51",    "L53",
        "L55",    "L56",  "L57",    "L58",  "L59",    "L70",   "L82",    "L82.1", "L82.2",  "L82.3",
        "L83",    "L92",  "L101",   "L102", "L111.1", "L113",  "L120",   "L201",  "L202",   "L204",
        "L205",   "L210", "L210.1", "L211", "L211.1", "L212",  "L213",   "L214",  "L215",   "L249",
        "L250",   "L251", "L251.1", "L252", "L252.1", "L253",  "L253.1", "L254",  "L254.1", "L255",
        "L255.1", "L256", "L300",   "L301", "L400",   "L401",  "L402",   "L500",  "L500.2", "L501",
        "L502",   "L600", "L601",   "L602", "L603",   "L604",  "L605",   "L606",  "L800",   "L801",
        "L802",   "L803", "L810",   "L820", "L821",   "L901",  "L910",   "L911"})
    all.emplace_back(l, l);
  int works = 0, refused = 0;
  for (const auto& [code, text] : all) {
    sink = RecordingSink();
    io = CountingIO();
    Interpreter interp(settings, sink, io, store);
    try {
      interp.run(Script::from_text(text + "\n", "t.tap"));
      ++works;
    } catch (const GantryError& e) {
      ++refused;
      const Diagnostic& d = e.diagnostic();
      EXPECT_TRUE(names(d.message, code)) << code << ": " << d.message;
      EXPECT_EQ(d.loc.line, std::count(text.begin(), text.end(), '\n') + 1) << code;
      EXPECT_GE(d.loc.column, 1) << code;
      EXPECT_TRUE(sink.moves.empty()) << code << " moved before it was refused";
    }
  }
  EXPECT_EQ(works + refused, static_cast<int>(all.size()));
  std::printf("WinCNC codes of the manual: %zu, running %d, refused by name %d\n", all.size(),
              works, refused);
}

// The letters and forms WinCNC writes that have no place here are refused where they stand,
// naming what they are in WinCNC and what to write instead (docs/gcode.md, the WinCNC table).
TEST_F(WinCncTest, WinCncLettersAreRefusedByWhatTheyAre) {
  struct Case {
    const char* line;
    int column;
    const char* names;
  };
  const Case cases[] = {
      {"G1 X1 W-0.5 F20", 7, "a second vertical head"},
      {"G0 U2", 4, "a third vertical head"},
      {"G0 V2", 4, "a fourth vertical head"},
      {"L10 R5 C5 X4 Y4 E1", 17, "L10's (a cut array)"},
      {"L1 N3 V2", 4, "WinCNC's L1 N# V# stores an H register"},
      {"G41 O0.125", 5, "compensation amount of G41/G42"},
      {"G42 O0.125", 5, "compensation amount of G41/G42"},
      {"G5 T1 M\"Continue?\"", 8, "WinCNC's G5 message box"},
  };
  for (const Case& c : cases) {
    const Diagnostic d = error(std::string(c.line) + "\n");
    EXPECT_EQ(d.loc.line, 1) << c.line;
    EXPECT_EQ(d.loc.column, c.column) << c.line << ": " << d.message;
    EXPECT_NE(d.message.find(c.names), std::string::npos) << c.line << ": " << d.message;
    EXPECT_TRUE(sink.moves.empty()) << c.line;
  }
  // M37's O, the measure's offset, is read (the measure is the O given).
  settings.gcode_dialect = GcodeDialect::WinCNC;
  const std::vector<CanonMove> plain = run("G90\nG0 Z1\n");
  const std::vector<CanonMove> measured = run("G90\nM37 O0.25\nG43\nG0 Z1\n");
  ASSERT_FALSE(plain.empty());
  ASSERT_FALSE(measured.empty());
  EXPECT_NEAR(measured.back().to[2] - plain.back().to[2], 0.25, 1e-9);  // machine = file + O
  // An O-word line of standard G-code still reads as one.
  EXPECT_NE(error("G1 X1 o100 call\n").message.find("an O-word comes first"), std::string::npos);
}

}  // namespace
}  // namespace gantry
