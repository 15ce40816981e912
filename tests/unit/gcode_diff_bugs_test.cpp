// The differences the differential test against LinuxCNC found (tests/data/gcode/differences.txt),
// fixed: every golden value below is what LinuxCNC 2.9's rs274 printed for the same program.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "gantry/core/diagnostic.hpp"
namespace gantry {
namespace {

using QuietIO = AnsweringIO;

class GcodeDiffBugs : public InterpreterFixture<QuietIO> {
 protected:
  // The lines and arcs `text` makes, run as a G-code file.
  std::vector<CanonMove> run(const std::string& text) {
    return lines_and_arcs(run_script(Script::from_text(text, "t.ngc")));
  }
  // The first error the check before a run finds; a failure when there is none.
  Diagnostic error(const std::string& text) {
    return first_error_of(check_script(Script::from_text(text, "t.ngc")), text);
  }
  // The X and Y of each move `text` makes, for comparing with rs274's canonical calls.
  std::vector<std::pair<double, double>> xy(const std::string& text) {
    std::vector<std::pair<double, double>> out;
    for (const CanonMove& m : run(text)) out.emplace_back(m.to[0], m.to[1]);
    return out;
  }
};

using XY = std::vector<std::pair<double, double>>;

void expect_xy(const XY& got, const XY& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(got[i].first, want[i].first, 1e-9) << "move " << i;
    EXPECT_NEAR(got[i].second, want[i].second, 1e-9) << "move " << i;
  }
}

// gen_param_indirect.ngc: rs274 STRAIGHT_FEED(0.25, 0) then (1.5, 0).
TEST_F(GcodeDiffBugs, IndirectParameterReadAndSet) {
  expect_xy(xy("G20 G90 F30\n#1 = 2\n#[#1 + 1] = 0.25\nG1 X#3 Y#[1+1]\n#[#1 * 5] = 1.5\n"
               "G1 X#10\nM2\n"),
            {{0.25, 0}, {1.5, 0}});
  // The target's number is read with the values before the block: #1 = 5 #[#1] = 3 sets #2
  // (rs274: STRAIGHT_FEED(3, 0)).
  expect_xy(xy("G20 G90 F30\n#1 = 2\n#1 = 5 #[#1] = 3\nG1 X#2 Y#5\nM2\n"), {{3, 0}});
  // Within 0.0001 of a whole number is that number (rs274: #[2.00001] sets #2).
  expect_xy(xy("G20 G90 F30\n#1 = 2.00001\n#[#1] = 3\nG1 X#2\nM2\n"), {{3, 0}});
}

TEST_F(GcodeDiffBugs, IndirectParameterThatIsNotWholeIsALocatedError) {
  // rs274: "Non integer value for integer" on line 3.
  const Diagnostic d = error("G20 G90 F30\n#1 = 2.3\n#[#1] = 3\nG1 X#2\nM2\n");
  EXPECT_EQ(d.loc.line, 3);
  EXPECT_EQ(d.loc.column, 1);
  EXPECT_NE(d.message.find("not a parameter"), std::string::npos) << d.message;
  // After a move too: the check before a run finds it, so the run never starts.
  EXPECT_EQ(error("G20 G90 F30\nG1 X1\n#1 = 2.3\n#[#1] = 3\nG1 X#2\nM2\n").loc.line, 4);
  // Gantry's numbered parameters above #5000 are read-only, set directly or indirectly.
  const Diagnostic ro = error("G20\n#[5000 + 21] = 1\nM2\n");
  EXPECT_EQ(ro.loc.line, 2);
  EXPECT_NE(ro.message.find("read-only"), std::string::npos) << ro.message;
}

// err_g53_alone.ngc: rs274 "Must use g0 or g1 with g53" and no move.
TEST_F(GcodeDiffBugs, G53WithoutAMotionIsRefused) {
  const Diagnostic d = error("G21\nG53 G90 G40\nG0 X1\nM2\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_NE(d.message.find("G0 or G1"), std::string::npos) << d.message;
  // rs274: G53 F100 (no axis word) refused too.
  EXPECT_EQ(error("G21\nG53 G0 G90\nG53 F100\nM2\n").loc.line, 3);
  // rs274 (e2.ngc): G53 X2 in G1 mode moves, G53 G0 Y3 moves; the bare G53 on line 5 is refused.
  EXPECT_EQ(error("G20 F30\nG1 X1\nG53 X2\nG53 G0 Y3\nG53\nM2\n").loc.line, 5);
  expect_xy(xy("G20 F30\nG1 X1\nG53 X2\nG53 G0 Y3\nM2\n"), {{1, 0}, {2, 0}, {2, 3}});
}

TEST_F(GcodeDiffBugs, WinCncBareG53IsNotRefusedAsAMissingMotion) {
  settings.gcode_dialect = GcodeDialect::WinCNC;
  sink = RecordingSink();
  InterpreterOptions o;
  o.dry_run = true;
  Interpreter interp(settings, sink, io, store, o);
  for (const Diagnostic& d : interp.check(Script::from_text("G20\nG53\nM2\n", "t.ngc")))
    EXPECT_EQ(d.message.find("G0 or G1"), std::string::npos) << d.message;
}

// edge_after_percent.ngc: rs274 traverses to (1, 0), feeds to (1, 1), and stops at the second %.
TEST_F(GcodeDiffBugs, ProgramEndsAtTheClosingPercent) {
  expect_xy(xy("%\nG20 G90 F30\nG0 X1\nG1 Y1\n%\nG0 X5\nG1 Y5\n"), {{1, 0}, {1, 1}});
  // What follows is not read at all (rs274 accepts `foo bar` there).
  expect_xy(xy("%\nG20 G90 F30\nG0 X1\n%\nfoo bar\n"), {{1, 0}});
  // A file that does not open with % has no closing one: Gantry reads on past a % line.
  expect_xy(xy("G20 G90 F30\nG0 X1\n%\nG0 X2\n"), {{1, 0}, {2, 0}});
}

// edge_compare_tolerance.ngc and the comparisons around the tolerance (rs274's moves).
TEST_F(GcodeDiffBugs, EqAndNeCompareWithinATenThousandth) {
  expect_xy(xy("G20 G90 F30\nG1 X[0.1 + 0.2 EQ 0.3] Y[1 EQ 1.00001]\n"
               "G1 X[1 NE 1.00001] Y[[2 AND 3] + [0 OR 0.5]]\nM2\n"),
            {{1, 1}, {0, 2}});
  expect_xy(xy("G20 G90 F30\nG1 X[1 EQ 1.00009] Y[1 NE 1.00009]\nG1 X[1 EQ 1.00011] "
               "Y[1 NE 1.00011]\nM2\n"),
            {{1, 0}, {0, 1}});
  // GT, GE, LT and LE stay exact (rs274: 1 GT 1.00001 is 0, 1.00001 GT 1 is 1, ...).
  expect_xy(xy("G20 G90 F30\nG1 X[1 + [1 GT 1.00001]] Y[1.00001 GT 1]\n"
               "G1 X[2 + [1 GE 1.00001]] Y[1 LT 1.00001]\n"
               "G1 X[3 + [1.00001 LE 1]] Y[[0.1+0.2] LE 0.3]\n"
               "G1 X[4 + [0.3 GE [0.1+0.2]]] Y[1 LE 0.99999]\nM2\n"),
            {{1, 1}, {2, 1}, {3, 0}, {4, 0}});
}

// edge_spaces_in_numbers.ngc: rs274 traverses to (1.5, -0.25), then feeds to (2, -0.25) at F20.
TEST_F(GcodeDiffBugs, SpacesInsideANumberAreIgnored) {
  const auto m = run("G20 G90 F30\nG0 X 1 . 5 Y 0 . 2 5\ng 1 x2 f 2 0\nM2\n");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_NEAR(m[0].to[0], 1.5, 1e-12);
  EXPECT_NEAR(m[0].to[1], 0.25, 1e-12);
  EXPECT_EQ(m[1].speed_class, SpeedClass::Move);
  EXPECT_NEAR(m[1].to[0], 2, 1e-12);
  EXPECT_NEAR(m[1].to[1], 0.25, 1e-12);
  EXPECT_NEAR(m[1].speeds.xy, 20.0 / 60, 1e-12);  // F20 in/min
  // In a parameter's number and inside expressions too (rs274: STRAIGHT_FEED(1.25, 1.5)).
  expect_xy(xy("G20 G90 F30\n#1 0 = 1 . 2 5\nG1 X#10 Y[1 2 / 8]\nM2\n"), {{1.25, 1.5}});
}

}  // namespace
}  // namespace gantry
