// The Friendly Motion front end (docs/friendlymotion.md): the digest's testable facts, golden
// canonical moves for programs written from the manual's examples, the refusals of what the
// manual leaves undefined, and the language's selection.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>  // getpid

#include "../support/interpreter_fixture.hpp"
#include "gantry/commands/stroke_font.hpp"
#include "gantry/core/diagnostic_log.hpp"
#include "gantry/interp/fm_executor.hpp"
#include "gantry/interp/fm_scribe.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/fm.hpp"
#include "gantry/lang/script.hpp"

namespace gantry {
namespace {

// An operator who answers prompts from `answers` (by variable, "&V1"), presses `button` (or
// each default) and keeps what was printed, asked and warned.
class FmIO : public OperatorIO {
 public:
  void print(std::string_view text) override { printed += text; }
  bool confirm(std::string_view q, const SourceLoc&) override {
    asked.emplace_back(q);
    return true;
  }
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view, const SourceLoc&) override {
    asked.emplace_back(prompt);
    auto it = answers.find(std::string(variable));
    if (it == answers.end()) return std::nullopt;
    return it->second;
  }
  std::string choose(std::string_view text, const std::vector<std::string>& b, size_t d,
                     std::string_view, const SourceLoc&) override {
    asked.emplace_back(text);
    if (!buttons.empty()) {
      const std::string next = buttons.front();
      buttons.erase(buttons.begin());
      return next;
    }
    return b.at(d);
  }
  void warn(const Diagnostic& d) override { warnings.push_back(d); }
  std::string printed;
  std::vector<std::string> asked;
  std::map<std::string, std::string> answers;
  std::vector<std::string> buttons;
  std::vector<Diagnostic> warnings;
};

std::string num(double v) {
  const std::string s = fmt::format("{:.4f}", std::abs(v) < 5e-5 ? 0.0 : v);
  return s;
}

// The moves as one line: L x,y (and z,a,b,c when any is not 0) for lines, A x,y @cx,cy
// sweep/pi for arcs, O2+ / O2- for outputs, D3.75 for dwells; stops left out (counted apart).
std::string summary(const std::vector<CanonMove>& moves) {
  std::string out;
  for (const CanonMove& m : moves) {
    std::string item;
    const bool more =
        std::abs(m.to[2]) + std::abs(m.to[3]) + std::abs(m.to[4]) + std::abs(m.to[5]) > 1e-9;
    auto point = [&] {
      std::string p = num(m.to[0]) + "," + num(m.to[1]);
      if (more)
        p += "," + num(m.to[2]) + "," + num(m.to[3]) + "," + num(m.to[4]) + "," + num(m.to[5]);
      return p;
    };
    switch (m.kind) {
      case MoveKind::Line:
        item = "L " + point();
        break;
      case MoveKind::Arc:
        item = "A " + point() + " @" + num(m.center_x) + "," + num(m.center_y) + " " +
               num(m.sweep / M_PI);
        break;
      case MoveKind::Output:
        item = fmt::format("O{}{}", m.output, m.output_on ? "+" : "-");
        break;
      case MoveKind::Dwell:
        item = "D" + num(m.dwell_s);
        break;
      default:
        continue;
    }
    out += (out.empty() ? "" : "; ") + item;
  }
  return out;
}

int stops(const std::vector<CanonMove>& moves) {
  int n = 0;
  for (const CanonMove& m : moves) n += m.kind == MoveKind::Stop;
  return n;
}

class FmTest : public InterpreterFixture<FmIO> {
 protected:
  void SetUp() override { settings.machine.limit_checking = false; }
  std::shared_ptr<const Script> script(const std::string& text, const std::string& name = "t.fm") {
    return Script::from_text(text, name);
  }
  // Runs `text` as a Friendly Motion file: every move (stops, outputs and dwells too).
  const std::vector<CanonMove>& run(const std::string& text, const std::string& name = "t.fm") {
    auto s = script(text, name);
    EXPECT_TRUE(s->ok()) << (s->errors().empty() ? "" : format(s->errors().front()));
    return run_script(s);
  }
  std::string moves_of(const std::string& text) { return summary(run(text)); }
  // The first error a check finds (the load pass's included).
  Diagnostic error(const std::string& text) {
    return first_error_of(check_script(script(text)), text);
  }
  // The error a run stops at.
  Diagnostic run_error(const std::string& text) {
    try {
      run_script(script(text));
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    ADD_FAILURE() << "no error from:\n" << text;
    return {};
  }
  // The message of the error a run of `text` as the file `name` stops at.
  std::string run_error_in(const std::string& text, const std::string& name) {
    try {
      run_script(Script::from_text(text, name));
    } catch (const GantryError& e) {
      return e.diagnostic().message;
    }
    ADD_FAILURE() << "no error from:\n" << text;
    return {};
  }
  // What G58 shows for `expr` after the lines `before`.
  std::string shown(const std::string& before, const std::string& g58) {
    io.printed.clear();
    run(before + "\nG58" + g58 + "\n");
    std::string p = io.printed;
    if (!p.empty() && p.back() == '\n') p.pop_back();
    return p;
  }
};

// ---- lexical facts -------------------------------------------------------------------------

TEST(FmParse, SeveralCommandsOnALineEachItsOwnToken) {  // facts 1-3
  FmLine line;
  Diagnostic e;
  ASSERT_TRUE(parse_fm_line("G90 M100 X1.0", nullptr, 1, &line, &e));
  ASSERT_EQ(line.commands.size(), 3u);
  EXPECT_EQ(line.commands[0].op, FmOp::G);
  EXPECT_EQ(line.commands[0].code, 90);
  EXPECT_EQ(line.commands[1].op, FmOp::M);
  EXPECT_EQ(line.commands[1].code, 100);
  EXPECT_EQ(line.commands[2].op, FmOp::Move);
  EXPECT_EQ(line.commands[2].column, 10);
  // X1Y1 is one command, X1 Y1 two.
  ASSERT_TRUE(parse_fm_line("X1Y1", nullptr, 1, &line, &e));
  EXPECT_EQ(line.commands.size(), 1u);
  ASSERT_TRUE(parse_fm_line("x1 y1", nullptr, 1, &line, &e));  // any case
  EXPECT_EQ(line.commands.size(), 2u);
  // Longest match on the codes: G68.1 is G68 .1, G70 is not G7 0, G4X3.75Q is G4.
  ASSERT_TRUE(parse_fm_line("G68.1 G70 G4X3.75Q G192", nullptr, 1, &line, &e));
  EXPECT_EQ(line.commands[0].code, 68);
  EXPECT_EQ(line.exprs[static_cast<size_t>(line.commands[0].expr)].literal(), 0.1);
  EXPECT_EQ(line.commands[1].code, 70);
  EXPECT_EQ(line.commands[2].code, 4);
  EXPECT_TRUE(line.commands[2].quick);
  EXPECT_EQ(line.commands[3].code, 19);
}

TEST(FmParse, CommentsAndQuotes) {  // fact 4, 7-9
  FmLine line;
  Diagnostic e;
  ASSERT_TRUE(parse_fm_line("!This is a comment", nullptr, 1, &line, &e));
  EXPECT_TRUE(line.commands.empty());
  ASSERT_TRUE(parse_fm_line("X1.0 !Move 1 inch", nullptr, 1, &line, &e));
  EXPECT_EQ(line.commands.size(), 1u);
  // A ! inside quotes is text; the manual's curly quotes are quotes; G16's text may run to
  // the token's end (the manual's own G16"HELLO,_MARY).
  ASSERT_TRUE(parse_fm_line("G16\"HI!\" G16\xE2\x80\x9COK\xE2\x80\x9D G16\"HELLO,_MARY", nullptr, 1,
                            &line, &e));
  ASSERT_EQ(line.commands.size(), 3u);
  EXPECT_EQ(line.commands[0].text, "HI!");
  EXPECT_EQ(line.commands[1].text, "OK");
  EXPECT_EQ(line.commands[2].text, "HELLO,_MARY");
  EXPECT_FALSE(parse_fm_line("G10fontfile.txt", nullptr, 1, &line, &e));  // fact 9
  EXPECT_NE(e.message.find("quotation marks"), std::string::npos);
  // A prompt's text may hold spaces (the manual's "enter size on square").
  ASSERT_TRUE(parse_fm_line("V1=?(enter size on square) G91", nullptr, 1, &line, &e));
  ASSERT_EQ(line.commands.size(), 2u);
  EXPECT_EQ(line.commands[0].text, "enter size on square");
}

TEST_F(FmTest, SequenceNumbersFirstOnTheLineAndInRange) {  // fact 5
  Diagnostic d = error("X1 N10\n");
  EXPECT_EQ(d.loc.line, 1);
  EXPECT_EQ(d.loc.column, 4);
  EXPECT_NE(d.message.find("first command"), std::string::npos);
  EXPECT_NE(error("N0\n").message.find("N1 to N99999"), std::string::npos);
  EXPECT_NE(error("N100000\n").message.find("N1 to N99999"), std::string::npos);
  EXPECT_TRUE(script("N99999 X1\n")->ok());
}

TEST_F(FmTest, M6MustBeAlone) {  // fact 6
  const Diagnostic d = error("KN10\nM0\nN10 X1\nX2 M6\n");
  EXPECT_EQ(d.loc.line, 4);
  EXPECT_EQ(d.loc.column, 4);
  EXPECT_NE(d.message.find("by itself"), std::string::npos);
}

TEST_F(FmTest, MalformedInputIsLocatedAndNothingMoves) {
  const std::string text = "G91 X1\nX1 Q5\nY1Y2\nG77\nV1=3+SIN45\nJN77\n";
  const std::vector<Diagnostic> found = errors_of(check_script(script(text)));
  ASSERT_GE(found.size(), 5u);
  EXPECT_EQ(found[0].loc.line, 2);
  EXPECT_EQ(found[0].loc.column, 4);
  EXPECT_NE(found[0].message.find("'Q' is not a Friendly Motion command letter"),
            std::string::npos);
  EXPECT_EQ(found[1].loc.line, 3);
  EXPECT_EQ(found[1].loc.column, 3);
  EXPECT_NE(found[1].message.find("Y is given twice"), std::string::npos);
  EXPECT_EQ(found[2].loc.line, 4);
  EXPECT_EQ(found[3].loc.line, 5);
  EXPECT_EQ(found[3].loc.column, 6);  // the function after '+'
  EXPECT_EQ(found[4].loc.line, 6);
  EXPECT_NE(found[4].message.find("N77"), std::string::npos);
  // A file with errors does not run.
  auto s = script(text);
  EXPECT_FALSE(s->ok());
}

TEST_F(FmTest, ErrorsAreCappedAsInTheOtherLanguages) {
  std::string text;
  for (int i = 0; i < 50; ++i) text += "X1 Q\n";
  DiagnosticLog log(10);
  Interpreter interp(settings, sink, io, store, {});
  interp.check(script(text), log);
  EXPECT_EQ(log.kept().size(), 10u);
  EXPECT_NE(log.summary().find("40"), std::string::npos) << log.summary();
}

// ---- variables and expressions -----------------------------------------------------------

TEST_F(FmTest, ExpressionsAsTheManualEvaluatesThem) {  // facts 19-27
  EXPECT_EQ(shown("V1=5*3+2", "V1"), "17.0000");
  EXPECT_EQ(shown("V1=5*(3+2)", "V1"), "25.0000");
  EXPECT_EQ(shown("V1=3 V1=V1+1", "V1"), "4.0000");
  EXPECT_EQ(shown("V1=3 V1=-V1", "V1"), "-3.0000");
  EXPECT_EQ(shown("V2=4 V3=5 V1=V2*V3", "V1"), "20.0000");
  EXPECT_EQ(shown("V1=SIN30", "V1"), "0.5000");
  EXPECT_EQ(shown("V2=COS45+45", "V2"), "0.0000");  // cos 90: the function takes the rest
  EXPECT_EQ(shown("V3=1 V1=ATANV3", "V1"), "45.0000");
  EXPECT_EQ(shown("V1=2^3", "V1"), "8.0000");
  EXPECT_EQ(shown("V1=2+3*2^2", "V1"), "14.0000");  // ^ before * before +
  EXPECT_EQ(shown("V1=ASIN1 V2=ACOS-1 V3=ATAN-1", "V1V2V3"), "90.0000 180.0000 -45.0000");
  const Diagnostic d = error("V1=3+SIN45\n");
  EXPECT_EQ(d.loc.column, 6);
  EXPECT_NE(d.message.find("right after the '='"), std::string::npos);
  EXPECT_NE(error("V1=(((((((1)))))))\n").message.find("six sets"), std::string::npos);
  EXPECT_TRUE(script("V1=((((((1))))))\n")->ok());
  EXPECT_NE(error("V1=1/0\n").message.find("division by zero"), std::string::npos);
  EXPECT_NE(error("V1=ASIN2\n").message.find("undefined"), std::string::npos);
}

TEST_F(FmTest, OneHundredVariablesAndReadOnlyMachineOnes) {  // facts 10, 15, 16, 18
  EXPECT_TRUE(script("V0=1 V99\n")->ok());
  EXPECT_NE(error("V100=1\n").message.find("V0 to V99"), std::string::npos);
  EXPECT_NE(error("V91=1\n").message.find("read-only"), std::string::npos);
  EXPECT_NE(error("V95=1\n").message.find("read-only"), std::string::npos);
  // V91/V92 follow the table; F sets V95.
  EXPECT_EQ(shown("G90 X1.5Y2 F0.5", "V91V92V95"), "1.5000 2.0000 0.5000");
  // V86-V89 may be written (fact 14), and convert with the units (fact 17).
  EXPECT_EQ(shown("G70 V86=0.5 G71", "V86"), "12.7000");
}

TEST_F(FmTest, AVariableOrALiteralMovesTheSame) {  // fact 12
  EXPECT_EQ(moves_of("X0.5"), moves_of("V3=0.5\nXV3"));
  EXPECT_EQ(moves_of("X0.5"), "L 0.5000,0.0000");
}

TEST_F(FmTest, VariablesInEveryArgumentTheManualLists) {  // fact 13
  io.answers["&V1"] = "2";
  const std::string m = moves_of(
      "V1=?\nV2=1 V3=102 V4=0.25 V5=2\nG91 XV1 YV2 CV1*45 FV4 G4XV4 MV3 KN10RV5\nM0\nN10 X1\nM6\n");
  EXPECT_EQ(m,
            "L 2.0000,0.0000; L 2.0000,1.0000; L 2.0000,1.0000,0.0000,0.0000,0.0000,90.0000; "
            "D0.2500; O2+; L 3.0000,1.0000,0.0000,0.0000,0.0000,90.0000; "
            "L 4.0000,1.0000,0.0000,0.0000,0.0000,90.0000; "
            "L 5.0000,1.0000,0.0000,0.0000,0.0000,90.0000; O2-");  // off at the end
}

TEST_F(FmTest, OperatorPromptsThroughTheOperatorQuestions) {  // fact 28
  io.answers["&V1"] = "1.5";
  EXPECT_EQ(moves_of("V1=?(enter size on square)\nG91\nXV1\nYV1\nX-V1\nY-V1\nM0\n"),
            "L 1.5000,0.0000; L 1.5000,1.5000; L 0.0000,1.5000; L 0.0000,0.0000");
  EXPECT_EQ(io.asked.front(), "enter size on square");
  // Unanswered, a check stops there saying how to answer.
  ScriptedIO nobody(false, {});
  InterpreterOptions o;
  o.dry_run = true;
  Interpreter interp(settings, sink, nobody, store, o);
  const std::vector<Diagnostic> found = interp.check(script("V7=?\nX1\n"));
  ASSERT_FALSE(found.empty());
  EXPECT_NE(found.front().message.find("--input '&V7=VALUE'"), std::string::npos)
      << found.front().message;
}

TEST_F(FmTest, StringsSetShownAndAsked) {  // facts 11, 29, 30
  EXPECT_EQ(shown("A0=123A3", "@0"), "123A3");
  EXPECT_EQ(shown("@9=X-1", "A9"), "X-1");
  io.printed.clear();
  run("V4=2.5\nV4\n@2=AB\n@2\n");
  EXPECT_EQ(io.printed, "V4=2.5000\n@2=AB\n");
  EXPECT_NE(error("A3\n").message.find("ambiguous"), std::string::npos);
  EXPECT_NE(error("@10=X\n").message.find("'='"), std::string::npos);
}

TEST_F(FmTest, G58ShowsTextValuesAndStringsUpperCaseOneSpaceApart) {  // facts 103, 104
  EXPECT_EQ(shown("V1=3", "\"The\"\"value\"\"of\"\"V1\"\"is\"V1"), "THE VALUE OF V1 IS 3.0000");
  EXPECT_EQ(shown("A0=312A3", "\"The\"\"Part\"\"Number\"\"is\"A0"), "THE PART NUMBER IS 312A3");
}

// ---- motion and modes ----------------------------------------------------------------------

TEST_F(FmTest, IncrementalAtPowerUpAbsoluteFromZero) {  // facts 31, 33
  EXPECT_EQ(moves_of("X1\nX1"), "L 1.0000,0.0000; L 2.0000,0.0000");
  EXPECT_EQ(moves_of("G90 X1\nX1"), "L 1.0000,0.0000");  // already there: no move
  EXPECT_EQ(moves_of("G90 Y-3.2"), "L 0.0000,-3.2000");
}

TEST_F(FmTest, InchesAndMillimetres) {  // facts 32, 45
  EXPECT_EQ(moves_of("G70 G91 X2"), "L 2.0000,0.0000");
  const auto& m = run("G71 G91 X2 F25.4");
  EXPECT_NEAR(m[0].to[0], 2 / 25.4, 1e-12);
  run("G71 F25.4 X1");
  EXPECT_NEAR(sink.moves[0].speeds.xy, 1.0, 1e-12);  // 25.4 mm/s = 1 in/s
  run("G70 F0.5 X1");
  EXPECT_NEAR(sink.moves[0].speeds.xy, 0.5, 1e-12);
}

TEST_F(FmTest, SpaceSeparatedMovesRunInTurnJoinedOnesInterpolate) {  // facts 35-37
  EXPECT_EQ(moves_of("X1.0 Y1.0"), "L 1.0000,0.0000; L 1.0000,1.0000");
  const auto& m = run("G91 X1Y1");
  ASSERT_EQ(lines_and_arcs(m).size(), 1u);
  EXPECT_NEAR((m[0].to - m[0].from).norm(), std::sqrt(2.0), 1e-12);  // 45 degrees, 1.414
  EXPECT_EQ(moves_of("G90 X1Y1"), "L 1.0000,1.0000");
}

TEST_F(FmTest, TheTableStopsAfterEachMoveOutsideAProfile) {  // facts 51, 52
  EXPECT_EQ(stops(run("X1\nY1\nX1\n")), 3);
  EXPECT_EQ(stops(run("G9\nX1\nY1\nX1\nG0\n")), 1);  // G0's
}

TEST_F(FmTest, ArcsAsTheManualDrawsThem) {  // facts 38-43
  // G90: the centre is absolute; G2 clockwise from (0,2) to ZERO about (0,1).
  EXPECT_EQ(moves_of("G90 X0Y2\nG2 X0Y0I0J1"),
            "L 0.0000,2.0000; A 0.0000,0.0000 @0.0000,1.0000 -1.0000");
  // G91: both relative to the start; end = start is a full circle of radius 1.
  EXPECT_EQ(moves_of("G91 G2 X0Y0I0J1"), "A 0.0000,0.0000 @0.0000,1.0000 -2.0000");
  EXPECT_EQ(moves_of("G91 G3 X0Y0I0J1"), "A 0.0000,0.0000 @0.0000,1.0000 2.0000");
  // G2 and G3 only set the direction; G2 by default.
  EXPECT_EQ(moves_of("G3\nG90 X1Y0\nX0Y1I0J0"),
            "L 1.0000,0.0000; A 0.0000,1.0000 @0.0000,0.0000 0.5000");
  EXPECT_EQ(moves_of("G90 X1Y0\nX0Y1I0J0"),
            "L 1.0000,0.0000; A 0.0000,1.0000 @0.0000,0.0000 -1.5000");
  // An end off the circle is an error at the arc.
  const Diagnostic d = error("G90 X1Y0\nX0Y2I0J0\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_NE(d.message.find("from its centre"), std::string::npos);
  EXPECT_NE(error("X1Y1I0\n").message.find("all four"), std::string::npos);
}

TEST_F(FmTest, CirclesRepeatRTimes) {  // fact 53
  EXPECT_EQ(moves_of("G91 X0Y0I1J0R3"),
            "A 0.0000,0.0000 @1.0000,0.0000 -2.0000; A 0.0000,0.0000 @1.0000,0.0000 -2.0000; "
            "A 0.0000,0.0000 @1.0000,0.0000 -2.0000");
  EXPECT_NE(error("G91 X1Y1I1J0R2\n").message.find("repeats circles"), std::string::npos);
  EXPECT_NE(error("G91 X0Y0I1J0R70\n").message.find("1 to 69"), std::string::npos);
  EXPECT_NE(error("X1R2\n").message.find("R repeats only"), std::string::npos);
}

TEST_F(FmTest, FeedsPerAxisGroup) {  // facts 46, 47, 48
  run("F0.25 X1");
  EXPECT_NEAR(sink.moves[0].speeds.xy, 0.25, 1e-12);
  run("FX2 X1 FY0.5 Y1");
  EXPECT_NEAR(sink.moves[2].speeds.xy, 0.5, 1e-12);  // FX and FY set the one X-Y feed
  run("FC30 C90 G90 C45");
  EXPECT_NEAR(sink.moves[0].speeds.c, 30, 1e-12);
  EXPECT_NEAR(sink.moves[0].to[5], 90, 1e-12);
  EXPECT_NEAR(sink.moves[2].to[5], 45, 1e-12);  // G90: the angle from ZERO
  EXPECT_NE(error("F0\n").message.find("above 0"), std::string::npos);
}

TEST_F(FmTest, Delays) {  // facts 49, 50
  EXPECT_EQ(moves_of("G4X3.75"), "D3.7500");
  EXPECT_EQ(moves_of("G4X3.75Q"), "D3.7500");  // at rest anyway outside a profile
  EXPECT_NE(error("G4X0.0005\n").message.find("0.001"), std::string::npos);
  EXPECT_NE(error("G9 X1 G4X1Q\n").message.find("mid-motion"), std::string::npos);
}

TEST_F(FmTest, ScalingAndMirrors) {  // facts 54, 55
  EXPECT_EQ(moves_of("G68X2 G91 X1 Y1"), "L 2.0000,0.0000; L 2.0000,1.0000");
  EXPECT_EQ(moves_of("G68.1 G91 X1 Y1"), "L 0.1000,0.0000; L 0.1000,0.1000");
  EXPECT_EQ(moves_of("G68X-1 G90 X1"), "L -1.0000,0.0000");
  // A mirror in one axis turns the arcs the other way.
  EXPECT_EQ(moves_of("G68X-1 G91 G2 X0Y0I1J0"), "A 0.0000,0.0000 @-1.0000,0.0000 2.0000");
  EXPECT_NE(error("G68X2 G91 X0Y0I1J0\n").message.find("ellipse"), std::string::npos);
  EXPECT_NE(error("G68 0\n").message.find("needs a number"), std::string::npos);
  EXPECT_NE(error("G680\n").message.find("cannot be 0"), std::string::npos);
}

TEST_F(FmTest, UserCoordinateSystem) {  // facts 56-61
  // G60A: origin (1,1), 90 degrees: user +X is table +Y.
  // X2 keeps the user Y (1) the table was at: user (2,1) is table (0,3).
  EXPECT_EQ(moves_of("V81=1 V82=1 V85=90 G60A G90 X2 X0Y0"), "L 0.0000,3.0000; L 1.0000,1.0000");
  // V91/V92 read user coordinates.
  EXPECT_EQ(shown("V81=1 V82=1 V85=90 G60A G90 X2Y0.5", "V91V92"), "2.0000 0.5000");
  // G60C: machine coordinates again.
  EXPECT_EQ(moves_of("V81=1 V82=1 V85=90 G60A G60C G90 X2"), "L 2.0000,0.0000");
  EXPECT_NE(error("V81=1 V85=10 G60A M98\n").message.find("G60C"), std::string::npos);
  EXPECT_NE(error("V81=1 V83=1 G60X\n").message.find("is the origin"), std::string::npos);
}

TEST_F(FmTest, OtherAxesMoveAsXAndY) {  // digest 7.21
  EXPECT_EQ(moves_of("G91 Z-0.1 A1.5 B2"),
            "L 0.0000,0.0000,-0.1000,0.0000,0.0000,0.0000; "
            "L 0.0000,0.0000,-0.1000,1.5000,0.0000,0.0000; "
            "L 0.0000,0.0000,-0.1000,1.5000,2.0000,0.0000");
}

// ---- flow --------------------------------------------------------------------------------

TEST_F(FmTest, JumpsUnconditionalAndOnAVariable) {  // facts 62, 63, 65
  EXPECT_EQ(moves_of("JN50\nX1\nN50 Y1\n"), "L 0.0000,1.0000");
  EXPECT_EQ(moves_of("V13=0 JV13N50 X1\nN50 Y1\n"), "L 1.0000,0.0000; L 1.0000,1.0000");
  EXPECT_EQ(moves_of("V13=0.5 JV13N50 X1\nN50 Y1\n"), "L 0.0000,1.0000");
  // A loop: three passes.
  EXPECT_EQ(moves_of("V1=3\nN10 X1\nV1=V1-1\nJV1N10\n"),
            "L 1.0000,0.0000; L 2.0000,0.0000; L 3.0000,0.0000");
}

TEST_F(FmTest, InputTestsAndWaits) {  // facts 63, 64
  // No machine: the inputs are open, so M200 is not active and the jump is not taken.
  EXPECT_EQ(moves_of("JM200N50 X1\nN50 Y1\n"), "L 1.0000,0.0000; L 1.0000,1.0000");
  EXPECT_NE(error("JM232N50\nN50\n").message.find("M200 to M231"), std::string::npos);
  EXPECT_NE(error("JM215N50\nN50\n").message.find("1 to 12"), std::string::npos);
  EXPECT_NE(error("JV0N50\nN50\n").message.find("V1 to V99"), std::string::npos);
}

TEST_F(FmTest, SubroutinesReturnToTheCommandAfterTheCall) {  // facts 66, 67, 68
  // M6 returns to the command after K, on the same line.
  EXPECT_EQ(moves_of("G91 KN100 Y1\nM0\nN100 X1\nM6\n"), "L 1.0000,0.0000; L 1.0000,1.0000");
  // KN100R6: called 7 times.
  EXPECT_EQ(moves_of("G91 KN100R6\nM0\nN100 X1\nM6\n"),
            "L 1.0000,0.0000; L 2.0000,0.0000; L 3.0000,0.0000; L 4.0000,0.0000; "
            "L 5.0000,0.0000; L 6.0000,0.0000; L 7.0000,0.0000");
  // Nested, and conditional.
  EXPECT_EQ(moves_of("G91 V2=1 KV2N10 KV3N20\nM0\nN10 X1 KN20\nM6\nN20 Y1\nM6\n"),
            "L 1.0000,0.0000; L 1.0000,1.0000");
  EXPECT_NE(run_error("N1 KN1\n").message.find("10 deep"), std::string::npos);
  // A command after J or K on its line is read so, with a warning (the manual writes them
  // alone).
  const auto s = script("KN10 X1\nM0\nN10 Y1\nM6\n");
  ASSERT_FALSE(s->errors().empty());
  EXPECT_EQ(s->errors().front().severity, Severity::Warning);
  EXPECT_EQ(s->errors().front().loc.column, 6);
  EXPECT_NE(run_error("X1\nM6\n").message.find("none was called"), std::string::npos);
}

TEST_F(FmTest, M0StopsIntoStepAndM2RepeatsOnce) {  // facts 71, 72
  io.buttons = {"Step", "Step", "Auto"};
  EXPECT_EQ(moves_of("X1\nM0\nX1\nX1\nX1\n"),
            "L 1.0000,0.0000; L 2.0000,0.0000; L 3.0000,0.0000; L 4.0000,0.0000");
  // M0, then a STEP question before each of the next two lines; Auto runs the rest.
  ASSERT_EQ(io.asked.size(), 3u);
  EXPECT_NE(io.asked[1].find("STEP: line 3"), std::string::npos);
  EXPECT_NE(io.asked[2].find("STEP: line 4"), std::string::npos);
  io.buttons = {"Stop"};
  EXPECT_NE(run_error("X1\nM0\nX1\n").message.find("stopped by the operator"), std::string::npos);
  // M2 in a check passes once; a run nobody attends runs once and says so.
  EXPECT_TRUE(errors_of(check_script(script("X1\nM2\n"))).empty());
  InterpreterOptions unattended;
  unattended.operator_present = false;
  sink = RecordingSink();
  Interpreter interp(settings, sink, io, store, unattended);
  interp.run(script("G91 X1\nM2\n"));
  EXPECT_EQ(summary(sink.moves), "L 1.0000,0.0000");
  ASSERT_FALSE(io.warnings.empty());
  EXPECT_NE(io.warnings.back().message.find("ran once"), std::string::npos);
}

// ---- golden programs, written from the manual's examples ----------------------------------

struct Golden {
  const char* name;
  const char* program;
  const char* moves;  // summary(): worked out by hand from the program
};

const Golden kGolden[] = {
    {"three commands on a line (4.1)", "G90 M100 X1.0\nM101\n", "O1+; L 1.0000,0.0000; O1-"},
    {"a variable as the distance (4.2)", "V3=0.5\nXV3\nXV3\n", "L 0.5000,0.0000; L 1.0000,0.0000"},
    {"the square of any size (4.3)", "V1=?(enter_size)\nG91\nXV1\nYV1\nX-V1\nY-V1\nM0\n",
     "L 2.0000,0.0000; L 2.0000,2.0000; L 0.0000,2.0000; L 0.0000,0.0000"},
    {"comments (4.4)", "!This is a comment\nX1.0 !Move 1 inch\n", "L 1.0000,0.0000"},
    {"inches then millimetres (4.16)", "G70 G91 X2\nG71 G91 X25.4\n",
     "L 2.0000,0.0000; L 3.0000,0.0000"},
    {"absolute and incremental (4.16, 4.25)", "G90 X1\nG91 X1\nG90 Y-3.2\n",
     "L 1.0000,0.0000; L 2.0000,0.0000; L 2.0000,-3.2000"},
    {"sequential and interpolated (4.25)", "X1.0 Y1.0\nX1Y1\n",
     "L 1.0000,0.0000; L 1.0000,1.0000; L 2.0000,2.0000"},
    {"the G90 arc to ZERO (4.26)", "G90 X0Y2\nG90 G2 X0Y0I0J1\n",
     "L 0.0000,2.0000; A 0.0000,0.0000 @0.0000,1.0000 -1.0000"},
    {"the G91 full circle (4.26)", "G91 G2 X0Y0I0J1\n", "A 0.0000,0.0000 @0.0000,1.0000 -2.0000"},
    {"a trepanned hole, R3 (4.26)", "G90 X1Y1\nG91 X0.05\nM100\nG3 X0Y0I-0.05J0R3\nM101\nX-0.05\n",
     "L 1.0000,1.0000; L 1.0500,1.0000; O1+; A 1.0500,1.0000 @1.0000,1.0000 2.0000; "
     "A 1.0500,1.0000 @1.0000,1.0000 2.0000; A 1.0500,1.0000 @1.0000,1.0000 2.0000; O1-; "
     "L 1.0000,1.0000"},
    {"a row of spots: a loop calling a subroutine (4.17, 4.18)",
     "G90\nV10=0\nN10 XV10Y1\nKN100\nV10=V10+1\nV1=2-V10\nJV1N10\nM0\n"
     "N100 M100 G4X0.5 M101\nM6\n",
     "L 0.0000,1.0000; O1+; D0.5000; O1-; L 1.0000,1.0000; O1+; D0.5000; O1-"},
    {"scaling, X then both (4.15)", "G68X2\nG91 X1Y1\nG68.1\nX10\n",
     "L 2.0000,1.0000; L 3.0000,1.0000"},
    {"a mirror image (4.15)", "G68X-1\nG90 X1Y1\nG91 G2 X0Y0I1J0\n",
     "L -1.0000,1.0000; A -1.0000,1.0000 @-2.0000,1.0000 2.0000"},
    {"a taught frame, G60X (4.14)",
     "G90 X2Y1\nV81=V91\nV82=V92\nX5Y5\nV83=V91\nV84=V92\nG60X\nG90 X0Y0\nX0.5Y0.5\nG60C\n",
     "L 2.0000,1.0000; L 5.0000,5.0000; L 2.0000,1.0000; L 1.9000,1.7000"},
    {"an arc in a turned frame, G60A", "V81=1 V82=1 V85=90 G60A\nG90 X1Y0\nG3 X0Y1I0J0\n",
     "L 1.0000,2.0000; A 0.0000,1.0000 @1.0000,1.0000 0.5000"},
    {"KN100R2: three calls (4.23)", "G91 KN100R2 Y1\nM0\nN100 X1\nM6\n",
     "L 1.0000,0.0000; L 2.0000,0.0000; L 3.0000,0.0000; L 3.0000,1.0000"},
    {"nested subroutines in a counted loop",
     "G91\nV1=2\nN5 KN100\nV1=V1-1\nJV1N5\nM0\nN100 X1 KN200\nM6\nN200 Y1\nM6\n",
     "L 1.0000,0.0000; L 1.0000,1.0000; L 2.0000,1.0000; L 2.0000,2.0000"},
    {"the rotary axis (4.6)", "FC90 G91 C90 C-45 G90 C0\n",
     "L 0.0000,0.0000,0.0000,0.0000,0.0000,90.0000; "
     "L 0.0000,0.0000,0.0000,0.0000,0.0000,45.0000; L 0.0000,0.0000"},
    {"a delay inside a profile (4.7)", "G9\nX1\nG4X0.25\nY1\nG0\n",
     "L 1.0000,0.0000; D0.2500; L 1.0000,1.0000"},
    {"outputs by a variable (4.20)", "V5=104\nMV5\nV5=V5+1\nMV5\n", "O3+; O3-"},
    {"axis zero (4.19)", "G91 X2\nM98\nG90 X1\n", "L 2.0000,0.0000; L 3.0000,0.0000"},
    {"a conditional jump on a variable (4.17)",
     "V13=1\nJV13N50\nX1\nN50 Y1\nV13=0 JV13N60 X1\nN60\n", "L 0.0000,1.0000; L 1.0000,1.0000"},
};

TEST_F(FmTest, GoldenPrograms) {
  for (const Golden& g : kGolden) {
    SCOPED_TRACE(g.name);
    io.answers["&V1"] = "2";
    EXPECT_EQ(moves_of(g.program), g.moves);
  }
}

// ---- I/O ---------------------------------------------------------------------------------

TEST_F(FmTest, OutputMFunctionsEvenOnOddOff) {  // facts 78-80, 3
  EXPECT_EQ(moves_of("G90 M100 X1.0 M101"), "O1+; L 1.0000,0.0000; O1-");
  EXPECT_EQ(moves_of("M102 M103 M110"), "O2+; O2-; O6+; O6-");  // all off at the job's end
  EXPECT_NE(error("M124\n").message.find("1 to 12"), std::string::npos);
  // G43: dry run, the moves without the outputs; G44 normal again.
  EXPECT_EQ(moves_of("G43 M100 X1 G44 M102"), "L 1.0000,0.0000; O2+; O2-");
}

TEST_F(FmTest, ZeroingAndTheRotaryAxis) {  // facts 74-76
  run("G91 X2 Y3 M98X G90 X1");            // X ZERO where X was: G90 X1 is table 3
  EXPECT_EQ(summary(sink.moves), "L 2.0000,0.0000; L 2.0000,3.0000; L 3.0000,3.0000");
  EXPECT_NEAR(state.zero[0], 2, 1e-12);
  EXPECT_NEAR(state.zero[1], 0, 1e-12);
  EXPECT_NEAR(state.position[0], 1, 1e-12);
  run("FC90 G90 C350 M97");
  EXPECT_NEAR(sink.moves.back().to[5], 360, 1e-9);  // back to the nearest 360, then ZERO
  EXPECT_NEAR(state.position[5], 0, 1e-12);
}

TEST_F(FmTest, InputWaitsAnalogValuesAndTheFreeRunningC) {
  // M200 alone waits for input 1 (no machine here: the operator is asked to go on).
  io.asked.clear();
  EXPECT_EQ(moves_of("M200 X1"), "L 1.0000,0.0000");
  ASSERT_EQ(io.asked.size(), 1u);
  EXPECT_NE(io.asked[0].find("waiting for input 1 to close"), std::string::npos) << io.asked[0];
  EXPECT_NE(error("M212\n").message.find("1 to 12"), std::string::npos);
  // Sf and SC: checked, recorded, said once.
  io.warnings.clear();
  run("Sf10.5 SC20 Sf11\n");
  ASSERT_EQ(io.warnings.size(), 1u);
  EXPECT_NE(io.warnings[0].message.find("no analog output"), std::string::npos);
  // M94 turns C on its own at the C feed; M96 stops it and C is ZERO there.
  run("FC90 M94 G4X1 M96\n");
  bool turned = false;
  for (const CanonMove& m : sink.moves) turned = turned || m.kind == MoveKind::Independent;
  EXPECT_TRUE(turned);
  EXPECT_NEAR(state.position[5], 0, 1e-12);
}

TEST_F(FmTest, HomingEndsTheUserCoordinatesAndMakesHomeZero) {  // fact 61, 77
  EXPECT_EQ(shown("V81=1 V85=30 G60A M99X G90 X0", "V91"), "0.0000");
  EXPECT_TRUE(errors_of(check_script(script("V81=1 V85=30 G60A M99 M98\n"))).empty());
  EXPECT_NE(error("M99Y M99B\n").message.find("unexpected"), std::string::npos);
}

TEST_F(FmTest, RefusedNamedWithWhy) {
  EXPECT_NE(error("T1\n").message.find("T (resistor trim)"), std::string::npos);
  EXPECT_NE(error("PA1\n").message.find("relay matrix"), std::string::npos);  // unwired
  EXPECT_NE(error("L5\n").message.find("never described"), std::string::npos);
  EXPECT_NE(error("G7ABC\n").message.find("G7"), std::string::npos);
  EXPECT_NE(error("G0R2\n").message.find("G0R#"), std::string::npos);
  EXPECT_NE(error("G19X2\n").message.find("ratio and direction"), std::string::npos);
  EXPECT_NE(error("G10\"mine.txt\"\n").message.find("font file"), std::string::npos);
  EXPECT_NE(error("S5\n").message.find("Sf#"), std::string::npos);
}

// ---- the laser table's hardware: the beam's output, the relay matrix, the feed range -------

TEST_F(FmTest, TheLaserIsTheProfilesOutputWithItsOnAndOffWaits) {
  // Left out: output 1, no waits (the golden programs above).
  settings.friendly_motion.laser_output = 3;
  settings.friendly_motion.laser_on_s = 0.05;
  settings.friendly_motion.laser_off_s = 0.02;
  // The beam switches at rest and waits before the next move starts: on at the move's start,
  // off at its end. Other outputs keep their numbers and switch without waiting.
  EXPECT_EQ(moves_of("M100 X1 M101 M102"), "O3+; D0.0500; L 1.0000,0.0000; O3-; D0.0200; O2+; O2-");
  // G16's strokes switch the same output, with the same waits.
  const std::string scribed = moves_of("G19.1 G16\"I\"");
  EXPECT_NE(scribed.find("O3+; D0.0500; L "), std::string::npos) << scribed;
  EXPECT_NE(scribed.find("O3-; D0.0200"), std::string::npos) << scribed;
  EXPECT_EQ(scribed.find("O1"), std::string::npos) << scribed;
  // G43 dry run: the moves, no beam and no waits.
  EXPECT_EQ(moves_of("G43 M100 X1 M101"), "L 1.0000,0.0000");
  // No laser output: M100 is refused by name; G16 traces with the beam off, and says so.
  settings.friendly_motion.laser_output = 0;
  EXPECT_NE(error("M100\n").message.find("names no laser output"), std::string::npos);
  io.warnings.clear();
  EXPECT_EQ(moves_of("G19.1 G16\"I\"").find("O"), std::string::npos);
  ASSERT_FALSE(io.warnings.empty());
  EXPECT_NE(io.warnings[0].message.find("laser off"), std::string::npos);
}

TEST_F(FmTest, TheRelayMatrixSwitchesTheProfilesOutputs) {  // fact 82
  // Without the profile's relays P is refused by name, before anything moves.
  EXPECT_NE(error("X1 PA1\n").message.find("wires none"), std::string::npos);
  // Probe 1 on bus A is output 7, probe 3 output 8 (probe 2 has no relay); probe 1 on bus B 9.
  settings.friendly_motion.relay_a = {7, 0, 8};
  settings.friendly_motion.relay_b = {9};
  EXPECT_TRUE(settings_problems(settings).empty());
  // PA1 connects probe 1 to bus A; PB1 moves it to bus B (it lets go of A first: a probe on
  // both would join the buses); PA3 adds probe 3; PD opens every relay that is closed.
  EXPECT_EQ(moves_of("PA1 X1 PB1 PA3 PD X2"),
            "O7+; L 1.0000,0.0000; O7-; O9+; O8+; O8-; O9-; L 3.0000,0.0000");
  EXPECT_EQ(moves_of("G90 V4=3 PAV4"), "O8+; O8-");  // a variable; off at the job's end
  // A probe the profile gives no relay, and a probe number that is none, are located errors.
  Diagnostic e = error("X1 PA2\n");
  EXPECT_EQ(e.loc.column, 4);
  EXPECT_NE(e.message.find("probe 2 has no relay to bus A"), std::string::npos) << e.message;
  EXPECT_NE(error("PB2\n").message.find("probe 2 has no relay to bus B"), std::string::npos);
  EXPECT_NE(error("PA1.5\n").message.find("no relay"), std::string::npos);
  EXPECT_NE(error("PC1\n").message.find("PA# or PB#"), std::string::npos);
  EXPECT_NE(error("PD1\n").message.find("unexpected"), std::string::npos);
  // G43: the relays stay as they are, as the other outputs do.
  EXPECT_EQ(moves_of("G43 PA1 PD X1"), "L 1.0000,0.0000");
  // The profile's rules: a relay is a wired output switch, not the laser's, not another's.
  Settings s = settings;
  s.friendly_motion.relay_b = {7};
  EXPECT_FALSE(settings_problems(s).empty());
  s.friendly_motion.relay_b = {1};
  const std::vector<std::string> laser = settings_problems(s);
  ASSERT_FALSE(laser.empty());
  EXPECT_NE(laser[0].find("gates the laser"), std::string::npos) << laser[0];
  s.friendly_motion.relay_b = {13};
  EXPECT_FALSE(settings_problems(s).empty());
}

TEST_F(FmTest, TheRelaySettingsLoadAndAreLeftOutWhenUnused) {
  const SettingsLoad load =
      parse_settings(default_profile_text() +
                         std::string("\n[friendly_motion]\nlaser_output = 2\nlaser_on_s = 0.01\n"
                                     "relay_a = \"5, 6\"\nrelay_b = \"0, 7\"\nfeed_max = 10\n"),
                     "t.toml");
  ASSERT_TRUE(load.ok()) << load.errors.front().message;
  EXPECT_EQ(load.settings.friendly_motion.laser_output, 2);
  EXPECT_EQ(load.settings.friendly_motion.relay_a, (std::vector<int>{5, 6}));
  EXPECT_EQ(load.settings.friendly_motion.relay_b, (std::vector<int>{0, 7}));
  EXPECT_EQ(load.settings.friendly_motion.feed_max, 10.0);
  EXPECT_FALSE(load.settings.friendly_motion.feed_min);
  // The shipped default has no [friendly_motion]: output 1, no relays, the manual's range.
  const Settings d = default_settings();
  EXPECT_EQ(d.friendly_motion.laser_output, 1);
  EXPECT_TRUE(d.friendly_motion.relay_a.empty());
}

TEST_F(FmTest, FeedsOutsideTheTablesRangeAreErrors) {  // fact 46, digest 7.18
  EXPECT_EQ(moves_of("F6 X1 F0.005 X1"), "L 1.0000,0.0000; L 2.0000,0.0000");
  Diagnostic e = error("X1 F6.5\n");
  EXPECT_EQ(e.loc.column, 4);
  EXPECT_NE(e.message.find("F6.5: the X-Y feed must be 0.005 to 6 in/s"), std::string::npos)
      << e.message;
  EXPECT_NE(error("FX0.004\n").message.find("0.005 to 6 in/s"), std::string::npos);
  EXPECT_NE(error("V1=7 FYV1\n").message.find("0.005 to 6"), std::string::npos);
  // In millimetres the same range: 0.127 to 152.4 mm/s.
  EXPECT_EQ(moves_of("G71 F152.4 X25.4"), "L 1.0000,0.0000");
  EXPECT_NE(error("G71 F153\n").message.find("0.127 to 152.4 mm/s"), std::string::npos);
  // FC (degrees per second) is not the X-Y range's.
  EXPECT_EQ(moves_of("FC90 C10"), "L 0.0000,0.0000,0.0000,0.0000,0.0000,10.0000");
  // A profile's own range.
  settings.friendly_motion.feed_max = 10;
  EXPECT_EQ(moves_of("F8 X1"), "L 1.0000,0.0000");
  EXPECT_NE(error("F11\n").message.find("friendly_motion.feed_min and feed_max"),
            std::string::npos);
}

TEST_F(FmTest, WritingTheTrimAndDiagnosticVariablesIsWarned) {  // digest 7.1, 7.18
  auto warnings = [&](const std::string& text) {
    std::vector<std::string> out;
    const auto loaded = script(text);  // kept: errors() is the script's
    for (const Diagnostic& d : loaded->errors())
      if (d.severity == Severity::Warning)
        out.push_back(fmt::format("{}:{} {}", d.loc.line, d.loc.column, d.message));
    return out;
  };
  const std::vector<std::string> w = warnings("V1=2 V74=1\nV72=?\nV79=0 V80=1 V71=1\n");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].rfind("1:6 V74 is one of the resistor trim's (T) variables", 0), 0u) << w[0];
  EXPECT_EQ(w[1].rfind("2:1 V72 is the manual's diagnostic mode", 0), 0u) << w[1];
  EXPECT_EQ(w[2].rfind("3:1 V79", 0), 0u) << w[2];
  // V73 is G16's value: warned only in a file that scribes nothing.
  EXPECT_EQ(warnings("V73=66.55\nG16\"%f\"\n").size(), 0u);
  ASSERT_EQ(warnings("V73=66.55\n").size(), 1u);
  EXPECT_NE(warnings("V73=66.55\n")[0].find("scribes nothing"), std::string::npos);
  // A warning is not an error: the program still runs.
  EXPECT_TRUE(errors_of(check_script(script("V74=1 X1\n"))).empty());
}

// The facts not tested above, each as the manual states it.
TEST_F(FmTest, TheRemainingFacts) {
  // Fact 34: +X moves the table (the X axis) in its + direction.
  EXPECT_EQ(moves_of("X0.5"), "L 0.5000,0.0000");
  // Fact 44: G codes do not move, G16 excepted.
  EXPECT_EQ(moves_of("G90 G91 G2 G3 G70 G71 G70 G9 G0 G43 G44 G68.5 G19.5 G10\"fontfile.txt\""),
            "");
  EXPECT_NE(moves_of("G19.1 G16\"I\"").find("L "), std::string::npos);
  // Fact 81: M201 (fault reset), M205 (stop trimming), M206 (probes up) are inputs 2, 6, 7.
  io.asked.clear();
  run("M201 M205 M206");
  ASSERT_EQ(io.asked.size(), 3u);
  EXPECT_NE(io.asked[0].find("input 2 to close"), std::string::npos) << io.asked[0];
  EXPECT_NE(io.asked[1].find("input 6 to close"), std::string::npos) << io.asked[1];
  EXPECT_NE(io.asked[2].find("input 7 to close"), std::string::npos) << io.asked[2];
  // Fact 91: the default font file is fontfile.txt (G10 names it without error).
  EXPECT_TRUE(errors_of(check_script(script("G10\"fontfile.txt\" G16\"A\"\n"))).empty());
  // Facts 106-112: T needs a resistor trimmer and is refused by name; V75 is 1 at load; V74
  // and V76-V79 are the trim's (ordinary variables here, warned when written).
  EXPECT_NE(error("T\n").message.find("T (resistor trim)"), std::string::npos);
  EXPECT_EQ(shown("", "V75"), "1.0000");
  EXPECT_EQ(shown("V76=2.5", "V76"), "2.5000");
}

// ---- STEP at the start and the Alt-F keys' subroutines -------------------------------------

TEST_F(FmTest, ARunMayStartInStep) {  // fact 71 (gantry run --step)
  InterpreterOptions o;
  o.fm_step = true;
  io.buttons = {"Step", "Auto"};
  run_script(script("X1\nX1\nX1\n"), o);
  EXPECT_EQ(summary(sink.moves), "L 1.0000,0.0000; L 2.0000,0.0000; L 3.0000,0.0000");
  ASSERT_EQ(io.asked.size(), 2u);  // line 1 (Step), line 2 (Auto), then it runs on
  EXPECT_NE(io.asked[0].find("STEP: line 1"), std::string::npos);
  EXPECT_NE(io.asked[1].find("STEP: line 2"), std::string::npos);
  // A check asks nothing.
  io.asked.clear();
  EXPECT_TRUE(errors_of(check_script(script("X1\nX1\n"), o)).empty());
  EXPECT_TRUE(io.asked.empty());
}

TEST_F(FmTest, AltFKeysCallTheirSubroutinesThenStep) {  // fact 70
  // The keys the operator presses, one per poll (before each line): Alt-F1 before line 2.
  std::vector<int> keys = {0, 1};
  InterpreterOptions o;
  o.fm_hot_key = [&] {
    if (keys.empty()) return 0;
    const int k = keys.front();
    keys.erase(keys.begin());
    return k;
  };
  io.buttons = {"Auto"};
  const char* program = "G90 X1\nX2\nX3\nM0\nN10001 Y1 M100\nM101\nM6\n";
  run_script(script(program), o);
  // N10001 runs before line 2, then line 2 waits for the operator (STEP), who runs on.
  EXPECT_EQ(summary(sink.moves),
            "L 1.0000,0.0000; L 1.0000,1.0000; O1+; O1-; L 2.0000,1.0000; L 3.0000,1.0000");
  ASSERT_EQ(io.asked.size(), 1u);  // the M0 before the subroutines ends the program
  EXPECT_NE(io.asked[0].find("STEP: line 2"), std::string::npos);
  EXPECT_NE(io.printed.find("Alt-F1: N10001"), std::string::npos);
  // A key whose subroutine the program lacks: the manual's error message, and the run goes on.
  keys = {3};
  io.warnings.clear();
  io.asked.clear();
  run_script(script(program), o);
  EXPECT_EQ(summary(sink.moves), "L 1.0000,0.0000; L 2.0000,0.0000; L 3.0000,0.0000");
  ASSERT_EQ(io.warnings.size(), 1u);
  EXPECT_NE(io.warnings[0].message.find("Alt-F3 calls subroutine N10003, which this program "
                                        "does not have"),
            std::string::npos);
  EXPECT_EQ(io.warnings[0].loc.line, 1);
  EXPECT_TRUE(io.asked.empty());
}

// ---- scribing ------------------------------------------------------------------------------

TEST(FmScribe, PrintfAsTheManualShowsIt) {  // facts 85, 87-89
  const SourceLoc at;
  EXPECT_EQ(fm_scribe_insert("%f", 66.55, "ABCD", at), "66.55");
  EXPECT_EQ(fm_scribe_insert("%I", 66.55, "ABCD", at), "66");
  EXPECT_EQ(fm_scribe_insert("%c", 66.55, "ABCD", at), "B");
  EXPECT_EQ(fm_scribe_insert("%s", 66.55, "ABCD", at), "ABCD");
  EXPECT_EQ(fm_scribe_insert("%sEFGH", 66.55, "ABCD", at), "ABCDEFGH");
  // With a width, C's printf (the manual's COUNT=066 is not reproduced: docs).
  EXPECT_EQ(fm_scribe_insert("V73=%6.2f", 66.55, "", at), "V73= 66.55");
  EXPECT_EQ(fm_scribe_insert("COUNT=_%3i", 66.55, "", at), "COUNT=_ 66");
  EXPECT_EQ(fm_scribe_insert("COUNT=_%03i", 66.55, "", at), "COUNT=_066");
  EXPECT_THROW(fm_scribe_insert("%i%f", 1, "", at), GantryError);  // fact 88
}

TEST_F(FmTest, ScribingFollowsTheStrokeFontWithTheLaserOnAlongTheStrokes) {  // facts 84-86, 90
  const auto& m = run("G90 X1Y1\nG16\"H\"\n");
  const double w = StrokeFont::glyph('H')->width;
  // H: three strokes, each with the laser on along it; the last move takes the stage to where
  // the next character would start.
  int on = 0, off = 0;
  size_t last = 0;
  for (size_t k = 0; k < m.size(); ++k)
    if (m[k].kind == MoveKind::Line) last = k;
  double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9;
  for (size_t k = 1; k < m.size(); ++k) {
    if (m[k].kind == MoveKind::Output) (m[k].output_on ? on : off) += m[k].output == 1;
    if (m[k].kind != MoveKind::Line || k == last) continue;
    min_x = std::min(min_x, m[k].to[0]);
    max_x = std::max(max_x, m[k].to[0]);
    min_y = std::min(min_y, m[k].to[1]);
    max_y = std::max(max_y, m[k].to[1]);
  }
  EXPECT_EQ(on, 3);
  EXPECT_EQ(off, 3);
  // From the lower left corner (1,1): 1" high, half as wide (2:1).
  EXPECT_NEAR(min_x, 1, 1e-12);
  EXPECT_NEAR(min_y, 1, 1e-12);
  EXPECT_NEAR(max_y, 2, 1e-12);
  EXPECT_NEAR(max_x, 1.5, 1e-12);
  EXPECT_NEAR(m[last].to[0], 1 + 0.5 * (w + StrokeFont::kGap) / w, 1e-12);
  EXPECT_NEAR(m[last].to[1], 1, 1e-12);
  // G19.25: a quarter of that; G60A 90: the text runs up the table.
  const auto& r = run("G19.25 V85=90 G60A G16\"H\"\n");
  double rx = -1e9, ry = -1e9;
  for (const CanonMove& k : r)
    if (k.kind == MoveKind::Line) rx = std::max(rx, k.to[0]), ry = std::max(ry, k.to[1]);
  EXPECT_NEAR(rx, 0, 1e-12);                                  // nothing to the right of the start
  EXPECT_NEAR(ry, 0.125 * (w + StrokeFont::kGap) / w, 1e-9);  // the pen ends past the H
}

// ---- data files ----------------------------------------------------------------------------

class FmFilesTest : public FmTest {
 protected:
  void SetUp() override {
    FmTest::SetUp();
    dir = std::filesystem::temp_directory_path() / fmt::format("gantry_fm_{}", ::getpid());
    std::filesystem::create_directories(dir);
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string read(const std::string& name) {
    std::ifstream in(dir / name, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::filesystem::path dir;
};

TEST_F(FmFilesTest, WriteThenReadRecordsInALoop) {  // facts 92-102
  const std::string name = (dir / "loop.fm").string();
  const std::string text =
      "G20pts\nV1=1\nN10 G26V1,V1*2\nV1=V1+1\nV2=4-V1\nJV2N10\nG25\"end\"V1\nG22\n"
      "G23pts\nG90\nV5=0\nN20 G27V1,V2\nXV1YV2\nV5=V5+1\nV6=3-V5\nJV6N20\n"
      "G27R2,V7\nG27VV5\n"  // record 2's first value into V7; V[V5] = V3 the next one
      "G24\n";
  auto s = Script::from_text(text, name);
  ASSERT_TRUE(s->ok());
  run_script(s);
  EXPECT_EQ(summary(sink.moves), "L 1.0000,2.0000; L 2.0000,4.0000; L 3.0000,6.0000");
  EXPECT_EQ(read("pts.dat"), "1.0000,2.0000\r\n2.0000,4.0000\r\n3.0000,6.0000\r\nEND 4.0000\r\n");
  io.printed.clear();
  run_script(Script::from_text("G23pts.dat\nG27R2,V7\nG27VV8\nG58V7V0\n", name));
  EXPECT_EQ(io.printed, "2.0000 4.0000\n");  // V8 is 0: into V0
}

TEST_F(FmFilesTest, ReadingPastTheEndAndMissingFilesAreErrors) {
  const std::string name = (dir / "e.fm").string();
  std::ofstream(dir / "one.dat") << "5\n";
  EXPECT_NE(run_error_in("G23one G27V1,V2\n", name).find("past the end"), std::string::npos);
  EXPECT_NE(run_error_in("G23none\n", name).find("no file"), std::string::npos);
  EXPECT_NE(run_error_in("G26V1\n", name).find("no output file"), std::string::npos);
}

// ---- selection -----------------------------------------------------------------------------

TEST(FmLanguage, ChosenByExtensionFirstLineOrName) {
  EXPECT_EQ(file_language("job.fm", "X1"), Language::FriendlyMotion);
  EXPECT_EQ(file_language("JOB.FM", ""), Language::FriendlyMotion);
  EXPECT_EQ(file_language("teach.nc", "\n! taught path\nX1"), Language::FriendlyMotion);
  EXPECT_EQ(file_language("teach.nc", "G0 X1"), Language::Gcode);
  EXPECT_EQ(file_language("job.sbp", "!x"), Language::OpenSbp);
  EXPECT_EQ(language_named("fm"), Language::FriendlyMotion);
  EXPECT_EQ(language_named("GCODE"), Language::Gcode);
  EXPECT_EQ(language_named("sbp"), Language::OpenSbp);
  EXPECT_FALSE(language_named("basic"));
  // --language reads a file as Friendly Motion whatever its name.
  auto s = Script::from_text("X1 Y1\n", "job.txt", {}, Language::FriendlyMotion);
  EXPECT_TRUE(s->fm());
  EXPECT_TRUE(s->ok());
}

TEST(FmTable, EveryRefusedCommandIsRefusedAndEveryCodeIsKnown) {
  for (const FmCommandInfo& c : fm_commands()) {
    EXPECT_FALSE(c.name.empty());
    EXPECT_FALSE(c.summary.empty()) << c.code;
    if (c.code.size() > 1 && (c.code[0] == 'G' || c.code[0] == 'M') &&
        std::isdigit(static_cast<unsigned char>(c.code[1]))) {
      const int n = std::stoi(std::string(c.code.substr(1)));
      EXPECT_TRUE(c.code[0] == 'G' ? fm_is_g_code(n) : fm_is_m_code(n)) << c.code;
    }
  }
}

TEST(FmTable, TheDocsPageHoldsTheTable) {
  std::ifstream in(std::string(GANTRY_SOURCE_DIR) + "/docs/friendlymotion.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  const std::string open = "<!-- fm-commands -->\n", close = "<!-- /fm-commands -->";
  const size_t a = page.find(open), b = page.find(close);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(page.substr(a + open.size(), b - a - open.size()), fm_commands_markdown())
      << "run `gantry help fm --markdown` and paste it between the markers";
}

}  // namespace
}  // namespace gantry
