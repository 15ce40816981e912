#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/vec6_expect.hpp"
#include "../support/where.hpp"
#include "gantry/canon/canon_move.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

class InterpreterTest : public KeptInterpreterFixture {
 protected:
  std::vector<Diagnostic> check(std::string_view text) {
    return interp().check(Script::from_text(std::string(text), "part.sbp"));
  }
};

// ---- absolute and relative distances

TEST_F(InterpreterTest, StartsAtOriginInAbsoluteModeWithProfileSpeeds) {
  EXPECT_TRUE(state().absolute);
  expect_vec(state().position, Vec6::Zero());
  expect_speeds(state().speeds.move, 2.0, 0.5, 10, 10, 10);
  expect_speeds(state().speeds.jog, 6.0, 3.0, 45, 45, 45);
}

TEST_F(InterpreterTest, Sb3WorkedExampleAbsoluteThenRelative) {
  run("SA\nM3 1,1,.2\nSR\nMZ -.45\nJZ .45\nJX 1.5\n");
  ASSERT_EQ(moves().size(), 4u);
  expect_vec(moves()[0].from, at(0, 0, 0));
  expect_vec(moves()[0].to, at(1, 1, 0.2));
  expect_vec(moves()[1].from, at(1, 1, 0.2));
  expect_vec(moves()[1].to, at(1, 1, -0.25));
  expect_vec(moves()[2].to, at(1, 1, 0.2));
  expect_vec(moves()[3].to, at(2.5, 1, 0.2));
  EXPECT_EQ(moves()[0].speed_class, SpeedClass::Move);
  EXPECT_EQ(moves()[1].speed_class, SpeedClass::Move);
  EXPECT_EQ(moves()[2].speed_class, SpeedClass::Jog);
  EXPECT_EQ(moves()[3].speed_class, SpeedClass::Jog);
  expect_vec(state().position, at(2.5, 1, 0.2));
  EXPECT_FALSE(state().absolute);
}

TEST_F(InterpreterTest, AbsoluteMovesGoToTheLocation) {
  run("MX, 5\nMX, 3\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_vec(moves()[1].from, at(5));
  expect_vec(moves()[1].to, at(3));
}

TEST_F(InterpreterTest, RelativeMovesAddToThePosition) {
  run("SR\nMX, 5\nMX, 3\nMY, 2\nMY, -1.5\n");
  ASSERT_EQ(moves().size(), 4u);
  expect_vec(moves()[1].to, at(8));
  expect_vec(moves()[3].to, at(8, 0.5));
}

TEST_F(InterpreterTest, SaAfterSrRestoresAbsolute) {
  run("SR\nMX, 5\nSA\nMX, 2\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_vec(moves()[1].to, at(2));
  EXPECT_TRUE(state().absolute);
}

TEST_F(InterpreterTest, BlankParameterKeepsThatAxisInAbsoluteMode) {
  run("SA\nM3, 1, 2, 3\nM2, , 3\nM3, 4, , 1\n");
  ASSERT_EQ(moves().size(), 3u);
  expect_vec(moves()[1].to, at(1, 3, 3));
  expect_vec(moves()[2].to, at(4, 3, 1));
}

TEST_F(InterpreterTest, BlankParameterKeepsThatAxisInRelativeMode) {
  run("SR\nM2, 1, 2\nM2, , 3\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_vec(moves()[1].to, at(1, 5));
}

TEST_F(InterpreterTest, MultiAxisCommandsUseAxisOrderXYZAB) {
  run("M5, 1, 2, 3, 4, 5\nJ4, 6, 7, 1, 8\nM4, , , , 9\n");
  ASSERT_EQ(moves().size(), 3u);
  expect_vec(moves()[0].to, at(1, 2, 3, 4, 5));
  expect_vec(moves()[1].to, at(6, 7, 1, 8, 5));
  expect_vec(moves()[2].to, at(6, 7, 1, 9, 5));
}

struct SingleAxisCase {
  const char* code;
  int axis;
  SpeedClass cls;
};

TEST_F(InterpreterTest, EachSingleAxisCommandMovesItsAxisInItsClass) {
  const SingleAxisCase cases[] = {{"MX", 0, SpeedClass::Move}, {"MY", 1, SpeedClass::Move},
                                  {"MZ", 2, SpeedClass::Move}, {"MA", 3, SpeedClass::Move},
                                  {"MB", 4, SpeedClass::Move}, {"JX", 0, SpeedClass::Jog},
                                  {"JY", 1, SpeedClass::Jog},  {"JZ", 2, SpeedClass::Jog},
                                  {"JA", 3, SpeedClass::Jog},  {"JB", 4, SpeedClass::Jog}};
  std::string text;
  for (const auto& c : cases) text += std::string(c.code) + ", 1\n" + c.code + ", 0\n";
  run(text);
  ASSERT_EQ(moves().size(), 2 * std::size(cases));
  for (size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(cases[i].code);
    const CanonMove& m = moves()[2 * i];
    Vec6 expected = Vec6::Zero();
    expected[cases[i].axis] = 1;
    expect_vec(m.to, expected);
    EXPECT_EQ(m.speed_class, cases[i].cls);
    EXPECT_EQ(moves()[2 * i + 1].speed_class, cases[i].cls);
  }
}

TEST_F(InterpreterTest, MultiAxisJogsAreJogClassAndMovesAreMoveClass) {
  run("M2, 1, 1\nJ2, 2, 2\nM3, 3, 3, 1\nJ3, 0, 0, 0\nM5, 1, 1, 1, 1, 1\nJ5, 2, 2, 2, 2, 2\n");
  ASSERT_EQ(moves().size(), 6u);
  for (size_t i = 0; i < moves().size(); ++i)
    EXPECT_EQ(moves()[i].speed_class, i % 2 == 0 ? SpeedClass::Move : SpeedClass::Jog) << i;
}

TEST_F(InterpreterTest, MoveRecordsItsStatementLocation) {
  run("SA\n\n   MX, 1\n");
  ASSERT_EQ(moves().size(), 1u);
  EXPECT_EQ(where(moves()[0].loc), "part.sbp:3:4");
  EXPECT_EQ(moves()[0].kind, MoveKind::Line);
}

// ---- speeds

TEST_F(InterpreterTest, MovesCarryMoveSpeedsAndJogsCarryJogSpeeds) {
  run("MX, 1\nJX, 2\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_speeds(moves()[0].speeds, 2.0, 0.5, 10, 10, 10);
  expect_speeds(moves()[1].speeds, 6.0, 3.0, 45, 45, 45);
}

// ---- MH / JH

TEST_F(InterpreterTest, MhRaisesToSafeZOnlyWhenBelowItThenGoesToXY0) {
  run("M3, 5, 4, 0.25\nMH\n");
  ASSERT_EQ(moves().size(), 3u);
  expect_vec(moves()[1].to, at(5, 4, 1));  // Safe-Z 1.0 first
  expect_vec(moves()[2].to, at(0, 0, 1));
  EXPECT_EQ(moves()[2].speed_class, SpeedClass::Move);
  run("SR\nM3, 3, 2, 1\nJH\n");  // above Safe-Z: Z stays; SR does not apply
  ASSERT_EQ(moves().size(), 5u);
  expect_vec(moves()[4].to, at(0, 0, 2));
  EXPECT_EQ(moves()[4].speed_class, SpeedClass::Jog);
}

TEST_F(InterpreterTest, HomeIsWorkingZeroAfterZeroing) {
  run("M2, 5, 5\nZ2\nM2, 1, 1\nMH\n");
  expect_vec(moves().back().to, at(5, 5, 1));  // table base of working 0,0 at Safe-Z
  expect_vec(state().position, at(0, 0, 1));
}

// ---- MD: move distance

TEST_F(InterpreterTest, MdMovesItsLengthAlongTheHeadingFromTheToolAndTurnsFromTheLastMove) {
  run("M2, 5, 5\nMD, 2, 90\nMD, 1, 90R\nMD, 1, N, 0.5\nMD, 1, 3:00, 0.25D\nMD, 2, SSW, 1U\n");
  ASSERT_EQ(moves().size(), 6u);
  expect_vec(moves()[1].to, at(7, 5));                       // 90: +X
  expect_vec(moves()[2].to, at(7, 4));                       // 90 right of +X: -Y
  expect_vec(moves()[3].to, at(7, 5, 0.5));                  // N, Z to 0.5
  expect_vec(moves()[4].to, at(8, 5, 0.25));                 // 3:00, Z down 0.25
  EXPECT_NEAR(moves()[5].to[0], 8 - 2 * 0.382683432, 1e-9);  // SSW = 202.5 degrees
  EXPECT_NEAR(moves()[5].to[1], 5 - 2 * 0.923879533, 1e-9);
  EXPECT_NEAR(moves()[5].to[2], 1.25, 1e-12);
  EXPECT_EQ(moves()[5].speed_class, SpeedClass::Move);
}

TEST_F(InterpreterTest, MdSaysWhatIsWrongWithItsAngleOrZChange) {
  Diagnostic d = run_error("MD, 1, NS\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:8");
  EXPECT_EQ(d.message,
            "MD angle 'NS' is not degrees (90), degrees right or left of the last move (30R, "
            "45L), a clock time (3:00) or a compass point (N, NE, SSW)");
  d = run_error("MD, 1, 90, 2X\n");
  EXPECT_EQ(d.message,
            "MD Z change '2X' is not a Z location (0.5) or an amount up or down (0.25U, 0.1D)");
  EXPECT_EQ(run_error("MD, 1\n").message, "MD needs its parameter 2 (angle)");
  EXPECT_TRUE(moves().empty());
}

// ---- Zero commands

TEST_F(InterpreterTest, ZeroingMakesTheCurrentLocationWorkingZeroAndTheMachineMovesOn) {
  run("M3, 5, 4, 1\nZX\nMX, 1\n&x = %(1)\n&tx = %(6)\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_vec(moves()[1].from, at(5, 4, 1));  // the machine moves in table base coordinates
  expect_vec(moves()[1].to, at(6, 4, 1));
  expect_vec(state().position, at(1, 4, 1));
  expect_vec(state().zero, at(5));
}

TEST_F(InterpreterTest, EachZeroCommandZeroesItsAxes) {
  const std::pair<const char*, unsigned> cases[] = {
      {"Z2", 0b11}, {"Z3", 0b111}, {"Z4", 0b1111}, {"Z5", 0b11111}, {"Z6", 0b111111}, {"ZX", 0b1},
      {"ZY", 0b10}, {"ZZ", 0b100}, {"ZA", 0b1000}, {"ZB", 0b10000}, {"ZC", 0b100000}};
  for (const auto& [code, axes] : cases) {
    SCOPED_TRACE(code);
    run("M5, 1, 1, 0.5, 2, 3\n");  // C has no move command yet: it stays at 0
    const Vec6 before = state().position, table = state().position + state().zero;
    run(std::string(code) + "\n");
    for (int i = 0; i < kAxisCount; ++i)
      EXPECT_EQ(state().position[i], (axes >> i) & 1 ? 0 : before[i]) << kAxisLetters[i];
    expect_vec(state().position + state().zero, table);  // the machine did not move
  }
}

TEST_F(InterpreterTest, SoftLimitsStayTheTablesAfterZeroing) {
  const Diagnostic d = run_error("MX, 20\nZX\nMX, 5\n");
  EXPECT_EQ(d.message,
            "move to X=5.0000 (table base X=25.0000) is outside the soft limits 0.0000 to "
            "24.0000 in (axes.x.min/max in the profile); nothing was moved");
  EXPECT_EQ(moves().size(), 1u);
  run("MX, -19\n");  // working -19 is table 1: inside
  expect_vec(state().position + state().zero, at(1));
}

TEST_F(InterpreterTest, SystemVariablesReadWorkingAndTableBaseLocations) {
  run("M2, 3, 2\nZ2\nM2, 1, 1\n&wx = %(1)\n&wy = %(2)\n&bx = %(6)\n&by = %(7)\n");
  EXPECT_EQ(interp().variable("WX")->num(), 1);
  EXPECT_EQ(interp().variable("WY")->num(), 1);
  EXPECT_EQ(interp().variable("BX")->num(), 4);
  EXPECT_EQ(interp().variable("BY")->num(), 3);
}

// ---- SO: output switches

TEST_F(InterpreterTest, SoSwitchesAnOutputBetweenMovesAndTheJobsEndTurnsItOff) {
  run("SO, 1, 1\nMX, 1\nSO, 3, 1\nSO, 1\nMX, 2\n");
  ASSERT_EQ(moves().size(), 6u);
  auto is_output = [&](size_t k, int n, bool on) {
    EXPECT_EQ(moves()[k].kind, MoveKind::Output) << k;
    EXPECT_EQ(moves()[k].output, n) << k;
    EXPECT_EQ(moves()[k].output_on, on) << k;
  };
  is_output(0, 1, true);
  EXPECT_EQ(moves()[1].kind, MoveKind::Line);
  is_output(2, 3, true);
  is_output(3, 1, false);  // a blank state is off
  EXPECT_EQ(moves()[4].kind, MoveKind::Line);
  is_output(5, 3, false);  // still on at the end: switched off
  EXPECT_EQ(state().outputs, 0u);
  EXPECT_EQ(where(moves()[2].loc), "part.sbp:3:1");
}

// ---- SW and switch 4: the warning before a run's first motion (docs/controller.md)

// The motion stream as kinds: "4+" switch 4 on, "w2" the warning's 2 s wait, "L" a line.
std::string stream(const std::vector<CanonMove>& moves) {
  std::string out;
  for (const CanonMove& m : moves) {
    if (!out.empty()) out += ' ';
    if (m.kind == MoveKind::Output)
      out += std::to_string(m.output) + (m.output_on ? "+" : "-");
    else if (m.kind == MoveKind::Dwell)
      out += (m.warning ? "w" : "d") + std::to_string(static_cast<int>(m.dwell_s));
    else
      out += m.kind == MoveKind::Line ? "L" : kind_name(m.kind);
  }
  return out;
}

TEST_F(InterpreterTest, TheFirstMotionOfARunIsWarnedOfWithSwitchFourAndTheWait) {
  options.warn_before_motion = true;
  run("SO, 1, 1\nPAUSE 1\nMX, 1\nMY, 1\n");
  // Outputs and a dwell are no motion: the warning comes just before the first move, and
  // switch 4 goes off after the last, with the file's other switches.
  EXPECT_EQ(stream(moves()), "1+ d1 4+ w2 L L 1- 4-");
  EXPECT_EQ(where(moves()[3].loc), "part.sbp:3:1");
  EXPECT_EQ(state().outputs, 0u);
}

TEST_F(InterpreterTest, SwAndSoFourChooseTheWarning) {
  options.warn_before_motion = true;
  run("SW, 0\nMX, 1\n");
  EXPECT_EQ(stream(moves()), "4+ L 4-");  // no wait: switch 4 comes on as the motion starts
  EXPECT_EQ(interp().settings().machine.warning_s, 0);
  sink.moves.clear();
  run("SW, 3\nSO, 4, -4\nMX, 2\n");
  EXPECT_EQ(stream(moves()), "w3 L");  // -4: switch 4 is an ordinary switch
  sink.moves.clear();
  run("SO, 4, -2\nSO, 4, 1\nMX, 3\nSO, 4, 0\nMX, 4\n");
  EXPECT_EQ(stream(moves()), "4+ w3 L 4- L");  // on already: the file's own switching stands
  sink.moves.clear();
  run("SP\nMX, 5\nSM\n");              // a preview moves nothing: nothing to warn of
  EXPECT_EQ(stream(moves()), "stop");  // SP's: the machine at rest before the preview
}

TEST_F(InterpreterTest, EachTypedLineIsWarnedOfAndVirtualTimeIsNot) {
  options.warn_before_motion = true;
  for (const char* line : {"MX, 1", "SO, 2, 1", "MX, 2"})
    interp().run(Script::from_text(line, "console"), /*typed=*/true);
  EXPECT_EQ(stream(moves()), "4+ w2 L 4- 2+ 4+ w2 L 4-");  // typed: switch 2 stays on
  sink.moves.clear();
  options.warn_before_motion = false;
  interp_.reset();
  run("MX, 1\n");
  EXPECT_EQ(stream(moves()), "L");
}

TEST_F(InterpreterTest, SoRefusesSwitchesThatDoNotExistOrAreNotWired) {
  Diagnostic d = run_error("SO, 13, 1\n");
  EXPECT_EQ(d.message, "output switch 13 does not exist; switches are 1 to 12");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
  EXPECT_EQ(run_error("SO, 2, 5\n").message,
            "SO state 5 is not 0 (off) or 1 (on); only switch 4 has automatic modes (-1 to -4)");
  EXPECT_EQ(run_error("SO, 2, -1\n").message,
            "SO state -1 is not 0 (off) or 1 (on); only switch 4 has automatic modes (-1 to -4)");
  EXPECT_EQ(run_error("SO, 4, -5\n").message,
            "SO state -5 is not 0 (off), 1 (on) or an automatic mode -1 to -4");
  EXPECT_EQ(run_error("SO, 1.5, 1\n").message,
            "output switch 1.5 does not exist; switches are 1 to 12");
  EXPECT_EQ(run_error("SO\n").message, "SO needs its parameter 1 (switch)");
  EXPECT_TRUE(moves().empty());
}

TEST_F(InterpreterTest, SoRefusesASwitchTheProfileDoesNotWire) {
  settings.outputs.aux_bits = {18, 19, 20, 21, 22, 23, 24, 25};  // SB3's eight
  const Diagnostic d = run_error("SO, 9, 1\n");
  EXPECT_EQ(d.message,
            "output switch 9 is not wired in this profile (outputs.aux_bits wires 8); nothing "
            "was switched");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
}

TEST_F(InterpreterTest, MsSetsMoveSpeedsOnly) {
  run("MS, 3, 1, 20, 30, 40\nMX, 1\nJX, 2\n");
  expect_speeds(state().speeds.move, 3, 1, 20, 30, 40);
  expect_speeds(state().speeds.jog, 6.0, 3.0, 45, 45, 45);
  ASSERT_EQ(moves().size(), 3u);
  EXPECT_EQ(moves()[0].kind, MoveKind::Stop);  // MS punctuates the moves around it
  expect_speeds(moves()[1].speeds, 3, 1, 20, 30, 40);
  expect_speeds(moves()[2].speeds, 6.0, 3.0, 45, 45, 45);
}

TEST_F(InterpreterTest, MsBlankKeepsThatSpeed) {
  run("MS, , 1\n");
  expect_speeds(state().speeds.move, 2.0, 1, 10, 10, 10);
}

TEST_F(InterpreterTest, JsSetsJogSpeedsOnly) {
  run("JS, 7, 2, , , 60\nJY, 1\nMY, 2\n");
  expect_speeds(state().speeds.jog, 7, 2, 45, 45, 60);
  expect_speeds(state().speeds.move, 2.0, 0.5, 10, 10, 10);
  ASSERT_EQ(moves().size(), 3u);
  EXPECT_EQ(moves()[0].kind, MoveKind::Stop);  // so does JS
  expect_speeds(moves()[1].speeds, 7, 2, 45, 45, 60);
  expect_speeds(moves()[2].speeds, 2.0, 0.5, 10, 10, 10);
}

TEST_F(InterpreterTest, VsTakesMoveXyZABThenJogXyZAB) {
  run("VS, 1, .2, 3, 4, 5, 1.5, 30, 40\nMX, 1\nJX, 2\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_speeds(moves()[0].speeds, 1, 0.2, 3, 4, 10);
  expect_speeds(moves()[1].speeds, 5, 1.5, 30, 40, 45);
}

TEST_F(InterpreterTest, VsBlanksKeepTheirSpeeds) {
  run("VS, , , , , 7\nMX, 1\nJX, 2\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_speeds(moves()[0].speeds, 2.0, 0.5, 10, 10, 10);
  expect_speeds(moves()[1].speeds, 7, 3.0, 45, 45, 45);
}

// The handbook: VS changes made in a file last until that file ends; MS and JS stay, also
// when they change a speed VS had set (here Z).
TEST_F(InterpreterTest, VsChangesEndWithTheFileButMsStays) {
  run("VS, 1, .2\nMS, , .3\nMX, 1\n");
  expect_speeds(state().speeds.move, 2.0, 0.3, 10, 10, 10);
  run("MS, 1.5\n");
  expect_speeds(state().speeds.move, 1.5, 0.3, 10, 10, 10);
}

// SB3 ignores parameters past the last (docs/language.md §1): a warning at the first one.
TEST_F(InterpreterTest, VsIgnoresANinthParameterWithAWarning) {
  run("VS, 1, 1, 1, 1, 1, 1, 1, 1, 1\nMX, 1\n");
  ASSERT_EQ(io.warnings().size(), 1u);
  EXPECT_EQ(where(io.warnings()[0].loc), "part.sbp:1:29");
  EXPECT_EQ(io.warnings()[0].message,
            "VS takes 8 parameters; parameter 9 and those after it are ignored, as SB3 ignores "
            "them");
  ASSERT_EQ(moves().size(), 1u);
  EXPECT_EQ(moves()[0].speeds.xy, 1);  // the eight values are taken
}

TEST_F(InterpreterTest, EachMoveKeepsTheSpeedInForceWhenIssued) {
  run("MX, 1\nMS, 3\nMX, 2\nVS, 1.5\nMX, 3\n");
  ASSERT_EQ(moves().size(), 4u);  // MS stops the machine between its moves; VS does not
  EXPECT_DOUBLE_EQ(moves()[0].speeds.xy, 2.0);
  EXPECT_EQ(moves()[1].kind, MoveKind::Stop);
  EXPECT_DOUBLE_EQ(moves()[2].speeds.xy, 3.0);
  EXPECT_EQ(moves()[3].kind, MoveKind::Line);
  EXPECT_DOUBLE_EQ(moves()[3].speeds.xy, 1.5);
}

TEST_F(InterpreterTest, SpeedEqualToMaxSpeedIsAllowed) {
  run("MS, 8, 4, 90, 90, 90\n");
  expect_speeds(state().speeds.move, 8, 4, 90, 90, 90);
}

TEST_F(InterpreterTest, ZeroSpeedIsAnErrorAtTheParameter) {
  const Diagnostic d = run_error("MS, 0\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
  EXPECT_EQ(d.message,
            "XY speed 0 is out of range; allowed: above 0 and up to 8 in/s (the axis max_speed "
            "in the profile)");
}

TEST_F(InterpreterTest, NegativeSpeedIsAnErrorAtTheParameter) {
  const Diagnostic d = run_error("SA\nMS, , -1\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:7");
  EXPECT_EQ(d.message,
            "Z speed -1 is out of range; allowed: above 0 and up to 4 in/s (the axis max_speed "
            "in the profile)");
}

TEST_F(InterpreterTest, SpeedAboveAxisMaxSpeedIsAnError) {
  const Diagnostic d = run_error("JS, 8.5\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
  EXPECT_EQ(d.message,
            "XY speed 8.5 is out of range; allowed: above 0 and up to 8 in/s (the axis "
            "max_speed in the profile)");
}

TEST_F(InterpreterTest, CSpeedIsCheckedAgainstTheCAxis) {
  settings.axes[5].max_speed = 50;
  const Diagnostic d = run_error("MS, , , , , 60\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:13");
  EXPECT_EQ(d.message,
            "C speed 60 is out of range; allowed: above 0 and up to 50 in/s (the axis max_speed "
            "in the profile)");
}

TEST_F(InterpreterTest, XySpeedLimitIsTheSlowerOfXAndY) {
  settings.axes[1].max_speed = 5;
  const Diagnostic d = run_error("MS, 6\n");
  EXPECT_EQ(d.message,
            "XY speed 6 is out of range; allowed: above 0 and up to 5 in/s (the axis max_speed "
            "in the profile)");
}

TEST_F(InterpreterTest, VsJogSpeedErrorIsAtItsParameter) {
  const Diagnostic d = run_error("VS, , , , , , , , 91\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:19");
  EXPECT_EQ(d.message,
            "B speed 91 is out of range; allowed: above 0 and up to 90 in/s (the axis max_speed "
            "in the profile)");
}

TEST_F(InterpreterTest, SpeedErrorChangesNoSpeed) {
  EXPECT_EQ(run_error("MS, 3, 0\n").message.rfind("Z speed 0", 0), 0u);
  expect_speeds(state().speeds.move, 2.0, 0.5, 10, 10, 10);
}

TEST_F(InterpreterTest, VsJogErrorChangesNoMoveSpeed) {
  EXPECT_EQ(run_error("VS, 1, , , , 0\n").message.rfind("XY speed 0", 0), 0u);
  expect_speeds(state().speeds.move, 2.0, 0.5, 10, 10, 10);
  expect_speeds(state().speeds.jog, 6.0, 3.0, 45, 45, 45);
}

// ---- zero-length moves, labels, END

TEST_F(InterpreterTest, ZeroLengthMovesEmitNothing) {
  run("MX, 0\nSR\nMX, 0\nM2, 0, 0\nSA\nM3\nM2, ,\nJ5, 0, 0, 0, 0, 0\n");
  EXPECT_TRUE(moves().empty());
  EXPECT_EQ(interp().moves_emitted(), 0u);
  EXPECT_EQ(interp().statements_executed(), 8u);
}

TEST_F(InterpreterTest, RepeatedTargetEmitsOnlyTheFirstMove) {
  run("MX, 5\nMX, 5\nM2, 5, 0\n");
  EXPECT_EQ(moves().size(), 1u);
  EXPECT_EQ(interp().moves_emitted(), 1u);
}

TEST_F(InterpreterTest, LabelsDoNothing) {
  run("START:\nMX, 1\nLOOP:\n");
  EXPECT_EQ(moves().size(), 1u);
  EXPECT_EQ(interp().statements_executed(), 3u);
}

TEST_F(InterpreterTest, EndStopsExecution) {
  run("MX, 1\nEND\nMX, 2\nQQ\n");
  ASSERT_EQ(moves().size(), 1u);
  expect_vec(state().position, at(1));
  EXPECT_EQ(interp().statements_executed(), 2u);
  EXPECT_EQ(sink.flushes, 1);
}

TEST_F(InterpreterTest, RunFlushesTheSinkOnceAtTheEnd) {
  run("MX, 1\nMX, 2\n");
  EXPECT_EQ(sink.flushes, 1);
}

TEST_F(InterpreterTest, ProgressIsReportedAfterEachStatement) {
  std::vector<std::pair<size_t, size_t>> calls;
  interp().on_progress([&](size_t done, size_t total) { calls.emplace_back(done, total); });
  run("SA\nMX, 1\nEND\nMX, 2\n");
  EXPECT_EQ(calls, (std::vector<std::pair<size_t, size_t>>{{1, 4}, {2, 4}, {3, 4}}));
}

// ---- errors

TEST_F(InterpreterTest, UnknownCommandIsAnErrorAtTheCommand) {
  const Diagnostic d = run_error("SA\n  QQ, 1, 2\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:3");
  EXPECT_EQ(d.message, "unknown command 'QQ'; see docs/commands.md for the commands Gantry knows");
  EXPECT_EQ(format(d),
            "part.sbp:2:3: error: unknown command 'QQ'; see docs/commands.md for the commands "
            "Gantry knows");
}

TEST_F(InterpreterTest, TooManyParametersIsAnErrorAtTheFirstExtraParameter) {
  const Diagnostic d = run_error("MX, 1, 2, 3\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:8");
  EXPECT_EQ(d.message, "MX takes 1 parameter; this is parameter 2");
  EXPECT_TRUE(moves().empty());
}

TEST_F(InterpreterTest, ParameterToACommandWithoutParametersIsIgnoredWithAWarning) {
  run("SA 1\nSA, , 2\n");
  ASSERT_EQ(io.warnings().size(), 1u);  // once per command and file
  EXPECT_EQ(where(io.warnings()[0].loc), "part.sbp:1:4");
  EXPECT_EQ(io.warnings()[0].message,
            "SA takes 0 parameters; parameter 1 and those after it are ignored, as SB3 ignores "
            "them");
}

// A move, a jog or a zero command refuses them: the value is likely meant for another
// command (M2 for M3), and ignoring it would move the tool where the file did not mean.
TEST_F(InterpreterTest, ExtraParametersOnMovesJogsAndZerosAreErrors) {
  for (const char* line : {"M2, 1, 2, 3\n", "J2, 1, 2, 3\n", "ZX, 1\n"}) {
    SCOPED_TRACE(line);
    const Diagnostic d = run_error(line);
    EXPECT_NE(d.message.find("; this is parameter "), std::string::npos) << d.message;
  }
  EXPECT_TRUE(moves().empty());
  EXPECT_TRUE(io.warnings().empty());
}

TEST_F(InterpreterTest, TooManyParametersForMultiAxisCommand) {
  const Diagnostic d = run_error("M2, 1, 2, 3\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:11");
  EXPECT_EQ(d.message, "M2 takes 2 parameters; this is parameter 3");
  EXPECT_TRUE(moves().empty());
}

TEST_F(InterpreterTest, MissingRequiredParameterIsAnErrorAtTheCommand) {
  const Diagnostic d = run_error("SA\n  MX\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:3");
  EXPECT_EQ(d.message, "MX needs its parameter 1 (X location)");
  EXPECT_TRUE(moves().empty());
}

TEST_F(InterpreterTest, TrailingBlankDoesNotSatisfyARequiredParameter) {
  const Diagnostic d = run_error("JZ, \n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:1");
  EXPECT_EQ(d.message, "JZ needs its parameter 1 (Z location)");
}

TEST_F(InterpreterTest, NonNumericParameterIsAnErrorAtTheParameter) {
  const Diagnostic d = run_error("MX, abc\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
  EXPECT_EQ(d.message, "expected a number for X location (MX), found 'abc'");
  EXPECT_TRUE(moves().empty());
}

TEST_F(InterpreterTest, NonNumericSecondParameterNamesItsAxis) {
  const Diagnostic d = run_error("M3, 1, two, 3\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:8");
  EXPECT_EQ(d.message, "expected a number for Y location (M3), found 'two'");
  EXPECT_TRUE(moves().empty());
}

TEST_F(InterpreterTest, NonNumericSpeedNamesTheSpeed) {
  const Diagnostic d = run_error("VS, , , , , fast\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:13");
  EXPECT_EQ(d.message, "expected a number for XY jog speed (VS), found 'fast'");
}

// ---- soft limits

TEST_F(InterpreterTest, MoveBeyondMaxSoftLimitIsAnErrorAndEmitsNothing) {
  const Diagnostic d = run_error("SA\nMX, 25\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:1");
  EXPECT_EQ(d.message,
            "move to X=25.0000 is outside the soft limits 0.0000 to 24.0000 in (axes.x.min/max "
            "in the profile); nothing was moved");
  EXPECT_TRUE(moves().empty());
  expect_vec(state().position, Vec6::Zero());
}

TEST_F(InterpreterTest, MoveBelowMinSoftLimitIsAnError) {
  const Diagnostic d = run_error("MX, 1\nJX, -0.5\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:1");
  EXPECT_EQ(d.message,
            "move to X=-0.5000 is outside the soft limits 0.0000 to 24.0000 in (axes.x.min/max "
            "in the profile); nothing was moved");
  EXPECT_EQ(moves().size(), 1u);
  expect_vec(state().position, at(1));
}

TEST_F(InterpreterTest, MoveToExactlyTheSoftLimitsIsAllowed) {
  run("M3, 24, 18, 5.5\nM3, 0, 0, -4\n");
  ASSERT_EQ(moves().size(), 2u);
  expect_vec(moves()[0].to, at(24, 18, 5.5));
  expect_vec(moves()[1].to, at(0, 0, -4));
}

TEST_F(InterpreterTest, OneAxisOutsideLimitsStopsTheWholeMove) {
  const Diagnostic d = run_error("M2, 1, 18.5\n");
  EXPECT_EQ(d.message,
            "move to Y=18.5000 is outside the soft limits 0.0000 to 18.0000 in (axes.y.min/max "
            "in the profile); nothing was moved");
  EXPECT_TRUE(moves().empty());
  expect_vec(state().position, Vec6::Zero());
}

TEST_F(InterpreterTest, RelativeMoveIsCheckedAtItsTarget) {
  const Diagnostic d = run_error("SR\nMX, 20\nMX, 5\n");
  EXPECT_EQ(where(d.loc), "part.sbp:3:1");
  EXPECT_EQ(d.message.rfind("move to X=25.0000 is outside", 0), 0u) << d.message;
  EXPECT_EQ(moves().size(), 1u);
  expect_vec(state().position, at(20));
}

TEST_F(InterpreterTest, SoftLimitsComeFromTheSettings) {
  settings.axes[0].max = 10;
  const Diagnostic d = run_error("MX, 10.5\n");
  EXPECT_EQ(d.message,
            "move to X=10.5000 is outside the soft limits 0.0000 to 10.0000 in (axes.x.min/max "
            "in the profile); nothing was moved");
}

TEST_F(InterpreterTest, OverflowingNumberIsNotANumber) {
  const Diagnostic d = run_error("MX, 1e999\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
  EXPECT_EQ(d.message, "the number 1e999 is too large");
  EXPECT_TRUE(moves().empty());
}

// ---- run and check

TEST_F(InterpreterTest, RunStopsAtTheFirstError) {
  const Diagnostic d = run_error("MX, 1\nQQ\nMX, 2\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:1");
  ASSERT_EQ(moves().size(), 1u);
  expect_vec(state().position, at(1));
}

TEST_F(InterpreterTest, RunRefusesAProgramWithParseErrorsBeforeAnyMotion) {
  const Diagnostic d = run_error("MX, 1\nPAUSEX 3\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:1");
  EXPECT_EQ(d.message.rfind("unknown statement 'PAUSEX'", 0), 0u) << d.message;
  EXPECT_TRUE(moves().empty());
  EXPECT_EQ(interp().statements_executed(), 0u);
}

TEST_F(InterpreterTest, CheckCollectsEveryErrorAndContinues) {
  const std::vector<Diagnostic> errors = check(
      "SA\n"        // 1
      "MX, 1\n"     // 2
      "QQ\n"        // 3
      "MY, abc\n"   // 4
      "MS, 0\n"     // 5
      "MZ, 1, 2\n"  // 6
      "MX, 30\n"    // 7
      "MX, 2\n"     // 8
      "MY\n");      // 9
  ASSERT_EQ(errors.size(), 6u);
  EXPECT_EQ(where(errors[0].loc), "part.sbp:3:1");
  EXPECT_EQ(where(errors[1].loc), "part.sbp:4:5");
  EXPECT_EQ(where(errors[2].loc), "part.sbp:5:5");
  EXPECT_EQ(where(errors[3].loc), "part.sbp:6:8");
  EXPECT_EQ(where(errors[4].loc), "part.sbp:7:1");
  EXPECT_EQ(where(errors[5].loc), "part.sbp:9:1");
  EXPECT_EQ(errors[0].message.rfind("unknown command 'QQ'", 0), 0u);
  EXPECT_EQ(errors[3].message, "MZ takes 1 parameter; this is parameter 2");
  // The good moves still ran, and the check went on from X=30, where the refused move meant
  // the tool to be.
  ASSERT_EQ(moves().size(), 2u);
  expect_vec(moves()[1].from, at(30));
  expect_vec(moves()[1].to, at(2));
  EXPECT_EQ(interp().statements_executed(), 9u);
  EXPECT_EQ(sink.flushes, 1);
}

TEST_F(InterpreterTest, CheckReportsParseErrorsFirst) {
  const std::vector<Diagnostic> errors = check("QQ\nPAUSEX 3\nMX, 1\n");
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(where(errors[0].loc), "part.sbp:2:1");
  EXPECT_EQ(errors[0].message.rfind("unknown statement 'PAUSEX'", 0), 0u);
  EXPECT_EQ(where(errors[1].loc), "part.sbp:1:1");
  EXPECT_EQ(errors[1].message.rfind("unknown command 'QQ'", 0), 0u);
  EXPECT_EQ(moves().size(), 1u);
}

TEST_F(InterpreterTest, CheckOfAGoodProgramFindsNothing) {
  EXPECT_TRUE(check("SA\nM3, 1, 1, .2\nSR\nMZ, -.45\nJZ, .45\nJX, 1.5\n").empty());
  EXPECT_EQ(moves().size(), 4u);
}

TEST_F(InterpreterTest, CheckStopsAtEnd) {
  const std::vector<Diagnostic> errors = check("MX, 1\nEND\nMX, 2\n");
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(moves().size(), 1u);
  EXPECT_EQ(interp().statements_executed(), 2u);
}

TEST_F(InterpreterTest, CheckOfTheManyErrorsFileNamesTheFile) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/tests/data/many_errors.sbp";
  const std::shared_ptr<const Script> script = Script::load(path);
  ASSERT_TRUE(script->ok());
  const std::vector<Diagnostic> errors = interp().check(script);
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_EQ(where(errors[0].loc), path + ":3:1");
  EXPECT_EQ(where(errors[1].loc), path + ":4:5");
  EXPECT_EQ(where(errors[2].loc), path + ":5:5");
  EXPECT_EQ(where(errors[3].loc), path + ":6:8");
  EXPECT_EQ(moves().size(), 2u);
}

// ---- numbers in parameters (the expression grammar itself is tested in expression_test)

TEST_F(InterpreterTest, ParametersAcceptOpenSbpNumerals) {
  const std::pair<const char*, double> cases[] = {{"5", 5},
                                                  {"-.45", -0.45},
                                                  {"+3.", 3},
                                                  {"1e-3", 0.001},
                                                  {".5", 0.5},
                                                  {"0", 0},
                                                  {"007", 7},
                                                  {"1E3", 1000},
                                                  {"12.75", 12.75},
                                                  {"5.", 5},
                                                  {"+.25", 0.25},
                                                  {"12+11/16", 12.6875},
                                                  {"-(2+7/32)", -2.21875}};
  for (const auto& [text, value] : cases) {
    SCOPED_TRACE(text);
    settings.axes[2].min = -1e6;
    settings.axes[2].max = 1e6;
    sink.moves.clear();
    run(std::string("SA\nMZ, 777\nMZ, ") + text + "\n");
    ASSERT_EQ(moves().size(), 2u);
    EXPECT_DOUBLE_EQ(moves()[1].to[2], value);
  }
}

TEST_F(InterpreterTest, AParameterThatIsNotANumberIsLocated) {
  // Broken expressions are located where they break; bare words at the parameter.
  const std::pair<const char*, const char*> cases[] = {{"1.2.3", "part.sbp:2:8"},
                                                       {"5x", "part.sbp:2:6"},
                                                       {"1 2", "part.sbp:2:7"},
                                                       {"e5", "part.sbp:2:5"},
                                                       {"abc", "part.sbp:2:5"}};
  for (const auto& [text, at] : cases) {
    SCOPED_TRACE(text);
    const Diagnostic d = run_error(std::string("SA\nMZ, ") + text + "\n");
    EXPECT_EQ(where(d.loc), at);
  }
  const Diagnostic d = run_error("MZ, abc\n");
  EXPECT_EQ(d.message, "expected a number for Z location (MZ), found 'abc'");
  EXPECT_TRUE(moves().empty());
}

// ---- codes that cannot run here (command_catalogue_test.cpp lists them)

TEST_F(InterpreterTest, ACodeThatCannotRunHereIsNamedAtItsLineAndChangesNothing) {
  const ModalState before = interp().state();
  const Diagnostic d = run_error("SA\n  UI\nMX, 1\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_EQ(d.loc.column, 3);
  EXPECT_TRUE(d.message.starts_with("UI (install control box firmware) cannot run on this machine"))
      << d.message;
  EXPECT_TRUE(moves().empty());  // the file stopped there: MX never ran
  EXPECT_EQ(interp().state().position, before.position);
  EXPECT_EQ(interp().state().speeds.move.xy, before.speeds.move.xy);
}

TEST_F(InterpreterTest, TextParametersReachTheCommand) {
  // O/I/T is a word: O cuts outside a 10 x 5 rectangle, so the path is a cutter wider.
  run("CR, 10, 5, O\n");
  double x = 0, y = 0;
  for (const CanonMove& m : moves()) x = std::max(x, m.to[0]), y = std::max(y, m.to[1]);
  EXPECT_DOUBLE_EQ(x, 10.25);
  EXPECT_DOUBLE_EQ(y, 5.25);
}

// MO and M0 (SB3 accepts a zero for the letter O): every output switch off, at rest.
TEST_F(InterpreterTest, MotorsOffTurnsEveryOutputOff) {
  run("SO, 1, 1\nSO, 3, 1\nMX, 1\nMO\nMX, 2\nSO, 2, 1\nM0\n");
  EXPECT_EQ(interp().state().outputs, 0u);
  std::vector<std::pair<int, bool>> switched;
  for (const CanonMove& m : moves())
    if (m.kind == MoveKind::Output) switched.emplace_back(m.output, m.output_on);
  const std::vector<std::pair<int, bool>> expected = {{1, true},  {3, true}, {1, false},
                                                      {3, false}, {2, true}, {2, false}};
  EXPECT_EQ(switched, expected);
}

TEST_F(InterpreterTest, CheckCountsEachSuchLineAndEveryOtherError) {
  const std::vector<Diagnostic> errors = check("MX, 1\nVK\nQQ\nUI\nMY, 2\n");
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[0].loc.line, 2);
  EXPECT_EQ(errors[0].message.rfind("VK cannot run", 0), 0u) << errors[0].message;
  EXPECT_EQ(errors[1].loc.line, 3);
  EXPECT_EQ(errors[1].message.rfind("unknown command 'QQ'", 0), 0u);
  EXPECT_EQ(errors[2].loc.line, 4);
  EXPECT_EQ(errors[2].message.rfind("UI (install control box firmware) cannot run", 0), 0u);
  EXPECT_EQ(moves().size(), 2u);  // the good lines still ran dry
}

}  // namespace
}  // namespace gantry
