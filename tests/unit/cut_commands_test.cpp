// The cut commands CA, CC, CG, CP and CR through the interpreter: the testable facts of
// shared/spec/commands.md §8.2-8.6 (each test names its fact), the decisions of docs/cuts.md,
// located errors that move nothing, soft limits, FP's transforms (tabs and plunge from Z 0
// included), VB's tabs on plain moves and CommandContext::arc_to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/memory_files.hpp"
#include "gantry/commands/command_table.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/file_system.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/canon/arc_geometry.hpp"
#include "gantry/motion/lookahead_planner.hpp"
#include "gantry/motion/planned_segment.hpp"

namespace gantry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct P3 {
  double x, y, z;
};

double dist2(double ax, double ay, double bx, double by) {
  return std::hypot(ax - bx, ay - by);
}

class CutCommands : public KeptInterpreterFixture {
 protected:
  CutCommands() {
    settings.machine.limit_checking = false;
    options.files = &files;
  }

  // Each run starts with no recorded moves (the interpreter keeps its state).
  void run(std::string_view text) {
    sink.moves.clear();
    run_program(Script::from_text(std::string(text), "part.sbp"));
  }
  Diagnostic run_error(std::string_view text) {
    sink.moves.clear();
    auto script = Script::from_text(std::string(text), "part.sbp");
    if (!script->ok()) return script->errors().front();
    return program_error(script, text);
  }

  // Lines and arcs, in order.
  std::vector<CanonMove> motion() const {
    std::vector<CanonMove> out;
    for (const CanonMove& m : sink.moves)
      if (m.kind == MoveKind::Line || m.kind == MoveKind::Arc) out.push_back(m);
    return out;
  }
  // The moves of source line `line`.
  std::vector<CanonMove> of_line(int line) const {
    std::vector<CanonMove> out;
    for (const CanonMove& m : motion())
      if (m.loc.line == line) out.push_back(m);
    return out;
  }
  std::vector<CanonMove> arcs(int line = 0) const {
    std::vector<CanonMove> out;
    for (const CanonMove& m : line ? of_line(line) : motion())
      if (m.kind == MoveKind::Arc) out.push_back(m);
    return out;
  }
  // Points along the moves of `line` (all lines when 0) that cut: move speed, XY moving.
  std::vector<P3> cut_points(int line = 0, int per = 64) const {
    std::vector<P3> out;
    for (const CanonMove& m : line ? of_line(line) : motion()) {
      if (m.speed_class != SpeedClass::Move) continue;
      if (m.kind == MoveKind::Line && m.from[0] == m.to[0] && m.from[1] == m.to[1]) continue;
      for (int i = 0; i <= per; ++i) out.push_back(point(m, static_cast<double>(i) / per));
    }
    return out;
  }
  static P3 point(const CanonMove& m, double f) {
    const Vec6 p = m.from + (m.to - m.from) * f;
    P3 q{p[0], p[1], p[2]};
    if (m.kind == MoveKind::Arc) {
      const double r = arc_radius(m);
      const double a = std::atan2(m.from[1] - m.center_y, m.from[0] - m.center_x) + f * m.sweep;
      q.x = m.center_x + r * std::cos(a);
      q.y = m.center_y + r * std::sin(a);
    }
    return q;
  }
  static double arc_r(const CanonMove& m) { return arc_radius(m); }

  MemoryFiles files;
};

std::vector<std::string_view> names(std::string_view code, Dialect d = Dialect::SB3) {
  std::vector<std::string_view> out;
  for (const ParamSpec& p : CommandTable::standard().find(code)->params_for(d))
    out.push_back(p.name);
  return out;
}

void expect_xy(const CanonMove& m, double x, double y, bool end = true, double tol = 1e-9) {
  const Vec6& p = end ? m.to : m.from;
  EXPECT_NEAR(p[0], x, tol);
  EXPECT_NEAR(p[1], y, tol);
}

// ===========================================================================================
// §8.2 CA — Cut Arch
// ===========================================================================================

TEST(CutFacts, Fact21_CaParameterOrder) {
  const std::vector<std::string_view> want = {"arch length", "arch height",     "O/I/T",
                                              "direction",   "alignment angle", "plunge",
                                              "repetitions", "proportion X",    "proportion Y",
                                              "tabs",        "no pull up",      "plunge from Z 0"};
  EXPECT_EQ(names("CA"), want);
}

TEST_F(CutCommands, Fact22_FabMoCaSkipsParameter10) {
  EXPECT_EQ(names("CA", Dialect::FabMo)[9], "skip");
  settings.dialect = Dialect::FabMo;
  run("CA, 10, 5, T, 1, 0, -0.5, 1, 1, 1, 1, 1\n");  // a 1 in position 10: no tabs
  for (const P3& p : cut_points()) EXPECT_NEAR(p.z, -0.5, 1e-12);
}

TEST_F(CutCommands, Fact23_ArchLengthAndHeightAreRequired) {
  const Diagnostic d = run_error("CA, 10\n");
  EXPECT_NE(d.message.find("arch height"), std::string::npos) << d.message;
  EXPECT_TRUE(motion().empty());
}

TEST_F(CutCommands, Fact24_ASpanTwiceTheHeightIsAHalfCircle) {
  run("CA, 10, 5\n");
  ASSERT_EQ(arcs().size(), 1u);
  EXPECT_NEAR(std::abs(arcs()[0].sweep), M_PI, 1e-12);
  EXPECT_NEAR(arc_r(arcs()[0]), 5, 1e-12);
}

TEST_F(CutCommands, Fact25_CaStartsHereAndEndsAtTheOtherEndOfTheSpan) {
  run("J2, 2, 3\nCA, 6, 1\n");
  const CanonMove a = arcs(2).at(0);
  expect_xy(a, 2, 3, false);
  expect_xy(a, 8, 3);
}

TEST_F(CutCommands, Fact26_CaSideDefaultsToTrue) {
  run("CA, 10, 2\n");
  EXPECT_NEAR(arc_r(arcs()[0]), 7.25, 1e-12);  // the arch itself, not offset
}

TEST_F(CutCommands, Fact27_CaDirectionDefaultsToClockwise) {
  run("CA, 10, 2\nJ2, 0, 0\nCA, 10, 2, T, -1\n");
  EXPECT_LT(arcs(1).at(0).sweep, 0);  // clockwise, bulging up (+Y)
  EXPECT_NEAR(arcs(1)[0].center_y, -5.25, 1e-12);
  EXPECT_GT(arcs(3).at(0).sweep, 0);  // counter-clockwise: the mirror image, bulging down
  EXPECT_NEAR(arcs(3)[0].center_y, 5.25, 1e-12);
  double low = kInf;
  for (const P3& p : cut_points(3)) low = std::min(low, p.y);
  EXPECT_NEAR(low, -2, 1e-6);
}

TEST_F(CutCommands, Fact28_AlignmentZeroRunsRightHorizontally) {
  run("CA, 10, 3\n");
  double top = -kInf;
  for (const P3& p : cut_points(1, 4000)) top = std::max(top, p.y);
  EXPECT_NEAR(top, 3, 1e-5);
  expect_xy(arcs()[0], 10, 0);
}

TEST_F(CutCommands, Fact29_Alignment90IsVerticalTopToBottom) {
  run("CA, 10, 5, T, 1, 90\n");
  const CanonMove a = arcs().at(0);
  expect_xy(a, 0, -10);  // below the start
  EXPECT_NEAR(a.center_x, 0, 1e-9);
  EXPECT_NEAR(a.center_y, -5, 1e-9);
  double right = -kInf;
  for (const P3& p : cut_points()) right = std::max(right, p.x);
  EXPECT_NEAR(right, 5, 1e-9);  // bulges to +X, the left of travel down
}

TEST_F(CutCommands, Fact30_CaPlungeIsPerRepetitionNegativeDown) {
  run("CA, 10, 5, T, 1, 0, -0.25, 3\n");
  const auto a = arcs();
  ASSERT_EQ(a.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k].to[2], -0.25 * (k + 1), 1e-12);
  run("CA, 10, 5\n");                          // default 0: the arch at the current height
  EXPECT_NEAR(arcs().back().to[2], 0, 1e-12);  // (the first command returned to its start, 0)
}

TEST_F(CutCommands, Fact31_CaRepetitionsDefaultToOne) {
  run("CA, 10, 5, T, 1, 0, -0.25\n");
  EXPECT_EQ(arcs().size(), 1u);
}

TEST_F(CutCommands, Fact32_CaProportionsDefaultToOne) {
  run("CA, 10, 5\n");
  EXPECT_EQ(arcs().size(), 1u);  // a circular arc
  run("J2, 10, 0\nCA, 10, 5, T, 1, 0, 0, 1, 2, 1\n");
  EXPECT_EQ(arcs().size(), 0u);  // an ellipse: lines
  double x1 = -kInf;
  for (const P3& p : cut_points(2)) x1 = std::max(x1, p.x);
  EXPECT_NEAR(x1 - 10, 20, 1e-9);  // twice as long in X
}

TEST_F(CutCommands, Fact33_CaTabsDefaultOff) {
  run("CA, 10, 5, T, 1, 0, -0.5\n");
  for (const P3& p : cut_points()) EXPECT_NEAR(p.z, -0.5, 1e-12);
  run("J3, 0, 0, 0\nCA, 10, 5, T, 1, 0, -0.5, 1, 1, 1, 1\n");  // tabs: 3 along the 15.7 arc
  double top = -kInf;
  for (const P3& p : cut_points(2)) top = std::max(top, p.z);
  EXPECT_NEAR(top, -0.4, 1e-12);
}

// The pull-up returns to the start Z (D9; FabMo's CG). Before issue 21 it went to Safe-Z (1).
TEST_F(CutCommands, Fact34_CaPullsUpUnlessNoPullUp) {
  run("CA, 10, 5, T, 1, 0, -0.5\n");
  EXPECT_NEAR(motion().back().to[2], 0, 1e-12);  // where it started
  EXPECT_EQ(motion().back().speed_class, SpeedClass::Jog);
  run("J3, 0, 0, 0\nCA, 10, 5, T, 1, 0, -0.5, 1, 1, 1, 0, 1\n");
  EXPECT_NEAR(motion().back().to[2], -0.5, 1e-12);  // stays at depth
}

TEST_F(CutCommands, Fact35_CaPlungeFromZZero) {
  run("JZ, 0.4\nCA, 10, 5, T, 1, 0, -0.25, 2, 1, 1, 0, 0, 1\n");
  const auto m = of_line(2);
  EXPECT_NEAR(m.at(0).to[2], 0, 1e-12);  // to Z 0 first
  EXPECT_NEAR(arcs(2).at(0).to[2], -0.25, 1e-12);
  EXPECT_NEAR(arcs(2).at(1).to[2], -0.5, 1e-12);
}

// ===========================================================================================
// §8.3 CC — Cut Circle
// ===========================================================================================

TEST(CutFacts, Fact36_CcParameterOrder) {
  const std::vector<std::string_view> want = {"diameter",    "O/I/T",        "direction",
                                              "begin angle", "end angle",    "plunge",
                                              "repetitions", "proportion X", "proportion Y",
                                              "feature",     "no pull up",   "plunge from Z 0"};
  EXPECT_EQ(names("CC"), want);
}

TEST_F(CutCommands, Fact37_FabMoCcFeatures2To4) {
  settings.dialect = Dialect::FabMo;
  run("CC, 2, I, 1, , , -0.2, 1, 1, 1, 2\n");  // pocket
  EXPECT_GT(arcs().size(), 2u);
  run("J3, 0, 0, 0\nCC, 2, T, 1, , , -0.2, 1, 1, 1, 3\n");  // spiral
  EXPECT_NEAR(arcs(2).at(0).from[2], 0, 1e-12);
  EXPECT_NEAR(arcs(2).at(0).to[2], -0.2, 1e-12);
  run("J3, 0, 0, 0\nCC, 2, T, 1, , , -0.2, 1, 1, 1, 4\n");  // spiral and bottom pass
  EXPECT_EQ(arcs(2).size(), 2u);
}

TEST_F(CutCommands, Fact38_DiameterIsTheOnlyRequiredCcParameter) {
  const Diagnostic d = run_error("CC\n");
  EXPECT_NE(d.message.find("diameter"), std::string::npos) << d.message;
  run("CC, 2\n");
  EXPECT_EQ(arcs().size(), 1u);
}

TEST_F(CutCommands, Fact39_CcAloneCutsATrueCircleFromTwelveOClock) {
  run("J2, 5, 5\nCC, 2\n");
  const CanonMove a = arcs(2).at(0);
  EXPECT_NEAR(a.center_x, 5, 1e-12);
  EXPECT_NEAR(a.center_y, 4, 1e-12);  // the tool is at the top
  EXPECT_NEAR(std::abs(a.sweep), 2 * M_PI, 1e-12);
  EXPECT_NEAR(arc_r(a), 1, 1e-12);
}

TEST_F(CutCommands, Fact40_CcOutsideIsBiggerThanInside) {
  run("CC, 2, O\nJ3, 0, 0, 0\nCC, 2, I\nJ3, 0, 0, 0\nCC, 2\n");
  EXPECT_NEAR(arc_r(arcs(1).at(0)), 1.125, 1e-12);  // D7
  EXPECT_NEAR(arcs(1)[0].center_y, -1.125, 1e-12);
  EXPECT_NEAR(arc_r(arcs(3).at(0)), 0.875, 1e-12);  // D8
  EXPECT_NEAR(arcs(3)[0].center_y, -0.875, 1e-12);
  EXPECT_NEAR(arc_r(arcs(5).at(0)), 1, 1e-12);
}

TEST_F(CutCommands, Fact41_CcDirectionDefaultsToClockwise) {
  run("CC, 2\nJ3, 0, 0, 0\nCC, 2, T, -1\n");
  EXPECT_LT(arcs(1).at(0).sweep, 0);
  EXPECT_GT(arcs(3).at(0).sweep, 0);
}

TEST_F(CutCommands, Fact42_AnglesAreDegreesFromTwelveOClockClockwise) {
  run("CC, 2, T, 1, 90\n");  // the tool at 3 o'clock: the centre is to its left
  EXPECT_NEAR(arcs()[0].center_x, -1, 1e-12);
  EXPECT_NEAR(arcs()[0].center_y, 0, 1e-12);
}

TEST_F(CutCommands, Fact43_AllCcCutsBeginAtTheToolLocation) {
  run("J2, 3, 4\nCC, 2, O, -1, 45, 100, -0.1, 2, 1.5, 1\n");
  const auto m = of_line(2);
  ASSERT_FALSE(m.empty());
  expect_xy(m.front(), 3, 4, false);
  for (const CanonMove& c : m)
    if (c.speed_class == SpeedClass::Move && c.from[2] == c.to[2]) {
      expect_xy(c, 3, 4, false, 1e-9);  // the first cutting move too
      break;
    }
}

TEST_F(CutCommands, Fact44_ZeroTo360IsBelowTheStartClockwiseFromTheTop) {
  run("CC, 2, T, 1, 0, 360\n");
  const CanonMove a = arcs().at(0);
  EXPECT_NEAR(a.center_y, -1, 1e-12);
  // D1: (0,0) -> (1,-1) -> (0,-2) -> (-1,-1) -> (0,0).
  const P3 q1 = point(a, 0.25), q2 = point(a, 0.5), q3 = point(a, 0.75);
  EXPECT_NEAR(q1.x, 1, 1e-12);
  EXPECT_NEAR(q1.y, -1, 1e-12);
  EXPECT_NEAR(q2.x, 0, 1e-12);
  EXPECT_NEAR(q2.y, -2, 1e-12);
  EXPECT_NEAR(q3.x, -1, 1e-12);
  EXPECT_NEAR(q3.y, -1, 1e-12);
}

TEST_F(CutCommands, Fact45_180To540IsAboveTheStart) {
  run("CC, 2, T, 1, 180, 540\n");
  EXPECT_NEAR(arcs()[0].center_y, 1, 1e-12);
  EXPECT_NEAR(std::abs(arcs()[0].sweep), 2 * M_PI, 1e-12);
  expect_xy(arcs()[0], 0, 0);
}

TEST_F(CutCommands, Fact46_270To630IsToTheRight) {
  run("CC, 2, T, 1, 270, 630\n");
  EXPECT_NEAR(arcs()[0].center_x, 1, 1e-12);
  EXPECT_NEAR(arcs()[0].center_y, 0, 1e-12);
}

TEST_F(CutCommands, Fact47_90To180ClockwiseIsTheLowerRightQuadrant) {
  run("CC, 2, T, 1, 90, 180\n");
  const CanonMove a = arcs().at(0);
  EXPECT_NEAR(a.center_x, -1, 1e-12);
  EXPECT_NEAR(a.sweep, -M_PI / 2, 1e-12);
  expect_xy(a, -1, -1);
  for (const P3& p : cut_points()) EXPECT_TRUE(p.x >= -1 - 1e-9 && p.y <= 1e-9);  // lower right
}

TEST_F(CutCommands, Fact48_90To180CounterClockwiseIsTheOther270Degrees) {
  run("CC, 2, T, -1, 90, 180\nJ3, 0, 0, 0\nCC, 2, T, -1, 90, -180\n");
  for (int line : {1, 3}) {
    const CanonMove a = arcs(line).at(0);
    EXPECT_NEAR(a.sweep, 3 * M_PI / 2, 1e-12);
    expect_xy(a, -1, -1);
  }
}

TEST_F(CutCommands, Fact49_RoundedLowerRightCornerAfterABottomEdge) {
  run("M2, 4, 0\nCC, 2, T, -1, 180, 90\n");
  const CanonMove a = arcs(2).at(0);
  // It continues the edge (+X at the start), turns up, and ends heading +Y at 3 o'clock.
  EXPECT_NEAR(a.center_x, 4, 1e-12);
  EXPECT_NEAR(a.center_y, 1, 1e-12);
  EXPECT_NEAR(a.sweep, M_PI / 2, 1e-12);
  expect_xy(a, 5, 1);
}

TEST_F(CutCommands, Fact50_BlankBeginIsZeroClockwise360CounterClockwise) {
  run("CC, 2, T, -1\n");
  EXPECT_NEAR(arcs()[0].center_y, -1, 1e-12);  // D2: starts at the top
  const P3 q = point(arcs()[0], 0.25);
  EXPECT_NEAR(q.x, -1, 1e-12);  // counter-clockwise: 9 o'clock first
}

TEST_F(CutCommands, Fact51_BlankEndIsAFullCircle) {
  run("CC, 2, T, 1, 90\nJ3, 0, 0, 0\nCC, 2, T, -1, 200\n");
  for (int line : {1, 3}) {
    EXPECT_NEAR(std::abs(arcs(line).at(0).sweep), 2 * M_PI, 1e-12);
    expect_xy(arcs(line)[0], 0, 0);
  }
}

TEST_F(CutCommands, Fact52_CcPlungePerRepetition) {
  run("CC, 2, T, 1, , , -0.5, 3\n");  // D10
  const auto a = arcs();
  ASSERT_EQ(a.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a[k].from[2], -0.5 * (k + 1), 1e-12);
    EXPECT_NEAR(a[k].to[2], -0.5 * (k + 1), 1e-12);
  }
  // Then back up to the start Z, 0 (D9; Safe-Z, 1, before issue 21).
  EXPECT_NEAR(motion().back().to[2], 0, 1e-12);
  EXPECT_EQ(motion().back().speed_class, SpeedClass::Jog);
}

TEST_F(CutCommands, Fact53_CcRepetitionsDefaultToOne) {
  run("CC, 2, T, 1, , , -0.5\n");
  EXPECT_EQ(arcs().size(), 1u);
}

TEST_F(CutCommands, Fact54_Diameter16Proportions3And1IsAn48By16Ellipse) {
  run("CC, 16, T, 1, , , 0, 1, 3, 1\n");  // D9
  double x0 = kInf, x1 = -kInf, y0 = kInf, y1 = -kInf;
  for (const P3& p : cut_points(1, 8)) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  EXPECT_NEAR(x0, -24, 1e-3);
  EXPECT_NEAR(x1, 24, 1e-3);
  EXPECT_NEAR(y0, -16, 1e-9);
  EXPECT_NEAR(y1, 0, 1e-9);
}

TEST_F(CutCommands, Fact55_CcFeatureDefaultsToNone) {
  run("CC, 6, T, 1, , , -0.5\n");
  EXPECT_EQ(arcs().size(), 1u);  // one flat circle: no tabs, pocket or spiral
  EXPECT_EQ(arcs()[0].from[2], arcs()[0].to[2]);
}

TEST_F(CutCommands, Fact56_CcTabsOnTheLastPassOnly) {
  run("CC, 6, T, 1, , , -0.25, 3, 1, 1, 1\n");
  for (const P3& p : cut_points()) {
    if (p.z > -0.6) {
      EXPECT_NEAR(std::fmod(p.z, 0.25), 0, 1e-9) << p.z;  // the first passes are flat
    }
  }
  double top_last = -kInf;
  for (const CanonMove& m : motion())
    if (m.speed_class == SpeedClass::Move && m.to[2] < -0.5 - 1e-9)
      top_last = std::max(top_last, m.to[2]);
  EXPECT_NEAR(top_last, -0.65, 1e-12);  // 0.1 above the last pass
}

TEST_F(CutCommands, Fact57_PocketNeedsAFullCircleAndTakesNoTabs) {
  const Diagnostic d = run_error("CC, 2, T, 1, 0, 90, -0.2, 1, 1, 1, 2\n");
  EXPECT_EQ(d.loc.column, 36) << d.message;  // at the feature
  EXPECT_NE(d.message.find("full circle"), std::string::npos);
  EXPECT_TRUE(motion().empty());
  run("VB, , , , , 1\nCC, 2, T, 1, , , -0.2, 1, 1, 1, 2\n");  // tabs on in the file: ignored
  for (const P3& p : cut_points(2)) EXPECT_NEAR(p.z, -0.2, 1e-12);
}

TEST_F(CutCommands, Fact58_PocketCutsSmallerCirclesInside) {
  run("CC, 3, I, 1, , , -0.2, 1, 1, 1, 2\n");
  const auto a = arcs();
  ASSERT_GT(a.size(), 3u);
  for (size_t i = 1; i < a.size(); ++i) {
    EXPECT_LT(arc_r(a[i]), arc_r(a[i - 1]));
    EXPECT_NEAR(a[i].center_x, a[0].center_x, 1e-12);
    EXPECT_NEAR(a[i].center_y, a[0].center_y, 1e-12);
  }
}

TEST_F(CutCommands, Fact59_SpiralWithOneRepetitionIsOneDescendingTurn) {
  run("CC, 2, T, 1, , , -0.5, 1, 1, 1, 3\n");
  ASSERT_EQ(arcs().size(), 1u);
  EXPECT_NEAR(arcs()[0].from[2], 0, 1e-12);
  EXPECT_NEAR(arcs()[0].to[2], -0.5, 1e-12);
  EXPECT_NEAR(std::abs(arcs()[0].sweep), 2 * M_PI, 1e-12);
}

TEST_F(CutCommands, Fact60_SpiralDescendsThePlungeEachTurn) {
  run("CC, 2, T, 1, , , -0.5, 3, 1, 1, 3\n");  // D11
  const auto a = arcs();
  ASSERT_EQ(a.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a[k].from[2], -0.5 * k, 1e-12);
    EXPECT_NEAR(a[k].to[2], -0.5 * (k + 1), 1e-12);
  }
}

TEST_F(CutCommands, Fact61_SpiralAndBottomPassEndsWithAFlatTurn) {
  run("CC, 2, T, 1, , , -0.5, 1, 1, 1, 4\n");  // D12
  const auto a = arcs();
  ASSERT_EQ(a.size(), 2u);
  EXPECT_NEAR(a[1].from[2], -0.5, 1e-12);
  EXPECT_NEAR(a[1].to[2], -0.5, 1e-12);
}

TEST_F(CutCommands, Fact62_TabsOnInTheFileStayOnForEachCircle) {
  run("VB, , , , , 1\nCC, 6, T, 1, , , -0.5\nJ3, 0, 0, 0\nCC, 6, T, 1, , , -0.5\n");
  for (int line : {2, 4}) {
    double top = -kInf;
    for (const P3& p : cut_points(line)) top = std::max(top, p.z);
    EXPECT_NEAR(top, -0.4, 1e-12) << line;
  }
  run("VB, , , , , 0\nJ3, 0, 0, 0\nCC, 6, T, 1, , , -0.5\n");  // off again
  for (const P3& p : cut_points(3)) EXPECT_NEAR(p.z, -0.5, 1e-12);
}

TEST_F(CutCommands, Fact63_CirclesRunAsShortChordsWithinTheTolerance) {
  // Gantry sends true arcs; the planner runs each as chords no farther than the profile's
  // chord tolerance from the circle (SB3's segment length becomes a tolerance).
  run("CC, 4\n");
  const CanonMove a = arcs().at(0);
  const std::vector<Vec6> chords = arc_chords(a, settings.planner.chord_tolerance);
  EXPECT_GT(chords.size(), 50u);
  Vec6 from = a.from;
  for (const Vec6& to : chords) {
    const Vec6 mid = (from + to) / 2;
    EXPECT_LE(2 - std::hypot(mid[0] - a.center_x, mid[1] - a.center_y),
              settings.planner.chord_tolerance + 1e-12);
    from = to;
  }
}

TEST_F(CutCommands, Fact64_SmallCirclesGetFinerChords) {
  run("CC, 0.1\nCC, 10\n");
  const auto a = arcs();
  auto chord = [&](const CanonMove& m) {
    const auto c = arc_chords(m, settings.planner.chord_tolerance);
    return std::hypot(c[0][0] - m.from[0], c[0][1] - m.from[1]);
  };
  EXPECT_LT(chord(a.at(0)), settings.calibration.circle_resolution);
  EXPECT_LT(chord(a.at(0)), chord(a.at(1)) / 5);  // and the large one is coarse again
}

// ===========================================================================================
// §8.4 CG — Cut G-code Circle
// ===========================================================================================

TEST(CutFacts, Fact65_CgParameterOrder) {
  const std::vector<std::string_view> want = {
      "diameter",     "X end",     "Y end",      "X center offset", "Y center offset",
      "O/I/T",        "direction", "plunge",     "repetitions",     "proportion X",
      "proportion Y", "feature",   "no pull up", "plunge from Z 0"};
  EXPECT_EQ(names("CG"), want);
}

TEST_F(CutCommands, Fact66_FabMoCgKeepsTheDiameterPosition) {
  // FabMo marks position 1 obsolete; the other positions are where SB3 has them, and a
  // diameter written there still works as SB3's (AMB-31).
  EXPECT_EQ(names("CG", Dialect::FabMo).size(), 14u);
  EXPECT_EQ(names("CG", Dialect::FabMo)[1], "X end");
  settings.dialect = Dialect::FabMo;
  run("CG, , 2, 0, 1, 0\n");
  EXPECT_NEAR(arcs().at(0).center_x, 1, 1e-12);
}

TEST_F(CutCommands, Fact67_CgStartsHereAndEndsAtTheEndPoint) {
  run("CG, , 2, 0, 1, 0\n");  // D16
  const CanonMove a = arcs().at(0);
  expect_xy(a, 0, 0, false);
  expect_xy(a, 2, 0);
  EXPECT_NEAR(a.sweep, -M_PI, 1e-12);
  const P3 mid = point(a, 0.5);
  EXPECT_NEAR(mid.x, 1, 1e-12);
  EXPECT_NEAR(mid.y, 1, 1e-12);
}

TEST_F(CutCommands, Fact68_CgDiameterMethodGivesTheArcUnder180Degrees) {
  run("CG, 4, 2, 0\nJ3, 0, 0, 0\nCG, 4, 2, 0, , , T, -1\n");
  for (int line : {1, 3}) {
    const CanonMove a = arcs(line).at(0);
    EXPECT_LT(std::abs(a.sweep), M_PI);
    EXPECT_NEAR(arc_r(a), 2, 1e-12);
    expect_xy(a, 2, 0);
  }
  EXPECT_LT(arcs(1)[0].center_y, 0);  // clockwise: bulges up, centre below
  EXPECT_GT(arcs(3)[0].center_y, 0);
  const Diagnostic d = run_error("J2, 0, 0\nCG, 1, 3, 0\n");  // the end beyond the diameter
  EXPECT_NE(d.message.find("farther than the diameter"), std::string::npos) << d.message;
}

TEST_F(CutCommands, Fact69_CgCentreOffsetsAreFromTheToolLocation) {
  run("J2, 3, 4\nCG, , 5, 4, 1, 0\n");
  EXPECT_NEAR(arcs(2).at(0).center_x, 4, 1e-12);
  EXPECT_NEAR(arcs(2)[0].center_y, 4, 1e-12);
}

TEST_F(CutCommands, Fact70_WithADiameterIAndJAreIgnored) {
  run("CG, 4, 2, 0, 5, 5\nJ3, 0, 0, 0\nCG, 4, 2, 0\n");
  EXPECT_NEAR(arcs(1).at(0).center_x, arcs(3).at(0).center_x, 1e-12);
  EXPECT_NEAR(arcs(1)[0].center_y, arcs(3)[0].center_y, 1e-12);
}

TEST_F(CutCommands, Fact71_CgWithoutAnEndPointEndsAtTheStart) {
  run("CG, , , , 0, -1\n");  // D15: the same circle as CC 2
  const CanonMove a = arcs().at(0);
  EXPECT_NEAR(a.center_y, -1, 1e-12);
  EXPECT_NEAR(a.sweep, -2 * M_PI, 1e-12);
  expect_xy(a, 0, 0);
}

TEST_F(CutCommands, Fact72_CgCannotMakeACircleFromADiameterAlone) {
  const Diagnostic d = run_error("CG, 2\n");
  EXPECT_NE(d.message.find("diameter alone"), std::string::npos) << d.message;
  EXPECT_TRUE(motion().empty());
}

TEST_F(CutCommands, Fact73_CgCentreOffsetsAreModal) {
  run("CG, , 2, 0, 1, 0\nCG, , 4, 0\nCG, , 6, 0, , 1\n");
  EXPECT_NEAR(arcs(2).at(0).center_x, 3, 1e-12);  // I 1, J 0 again, from (2, 0)
  EXPECT_NEAR(arcs(2)[0].center_y, 0, 1e-12);
  EXPECT_NEAR(arcs(3).at(0).center_x, 5, 1e-12);  // I kept, J now 1, from (4, 0)
  EXPECT_NEAR(arcs(3)[0].center_y, 1, 1e-12);
}

TEST_F(CutCommands, Fact74_CgProportionsDefaultToOne) {
  run("CG, , 2, 0, 1, 0\n");
  EXPECT_EQ(arcs().size(), 1u);  // circular
  run("J2, 0, 0\nCG, , 2, 0, 1, 0, T, 1, 0, 1, 2, 1\n");
  EXPECT_EQ(arcs().size(), 0u);  // an ellipse: lines
}

// ===========================================================================================
// §8.5 CP — Cut Circle from Center Point
// ===========================================================================================

TEST(CutFacts, Fact75_CpParameterOrder) {
  const std::vector<std::string_view> want = {
      "diameter",     "X center",  "Y center",   "O/I/T",          "direction",
      "start angle",  "end angle", "plunge",     "repetitions",    "proportion X",
      "proportion Y", "feature",   "no pull up", "plunge from Z 0"};
  EXPECT_EQ(names("CP"), want);
}

TEST_F(CutCommands, Fact76_CpMovesToTheStartPointAtTheCurrentHeight) {
  run("JZ, 0.5\nCP, 2, 5, 5\n");  // D14
  const auto m = of_line(2);
  ASSERT_GE(m.size(), 2u);
  EXPECT_EQ(m[0].kind, MoveKind::Line);
  EXPECT_EQ(m[0].speed_class, SpeedClass::Move);
  expect_xy(m[0], 5, 6);
  EXPECT_NEAR(m[0].to[2], 0.5, 1e-12);  // not lifted
  EXPECT_NEAR(arcs(2).at(0).center_x, 5, 1e-12);
  EXPECT_NEAR(arcs(2)[0].center_y, 5, 1e-12);
}

TEST_F(CutCommands, Fact77_CpNeedsDiameterAndCentre) {
  for (const char* text : {"CP\n", "CP, 2\n", "CP, 2, 5\n"}) {
    run_error(text);
    EXPECT_TRUE(motion().empty()) << text;
  }
}

TEST_F(CutCommands, Fact78_TheToolNeverGoesToTheCpCentre) {
  run("CP, 2, 5, 5, T, 1, 0, 0, -0.2, 2\n");
  for (const CanonMove& m : motion())
    for (int i = 0; i <= 64; ++i) {
      const P3 p = point(m, i / 64.0);
      EXPECT_GT(dist2(p.x, p.y, 5, 5), 0.5) << p.x << "," << p.y;
    }
}

TEST_F(CutCommands, Fact79_CpAnglesDefaultToAFullCircleFromTheTop) {
  run("CP, 2, 5, 5\n");
  EXPECT_NEAR(std::abs(arcs().at(0).sweep), 2 * M_PI, 1e-12);
  expect_xy(arcs()[0], 5, 6, false);
}

TEST_F(CutCommands, Fact80_CpZeroTo360FromTheTop180To540FromTheBottom) {
  run("CP, 2, 5, 5, T, 1, 0, 360\nCP, 2, 5, 5, T, 1, 180, 540\n");
  expect_xy(arcs(1).at(0), 5, 6, false);
  expect_xy(arcs(2).at(0), 5, 4, false);
  EXPECT_NEAR(std::abs(arcs(2)[0].sweep), 2 * M_PI, 1e-12);
}

TEST_F(CutCommands, Fact81_FabMoCpFeatures2To4) {
  settings.dialect = Dialect::FabMo;
  run("CP, 2, 5, 5, I, 1, 0, 0, -0.2, 1, 1, 1, 2\n");
  EXPECT_GT(arcs().size(), 2u);
  run("CP, 2, 5, 5, T, 1, 0, 0, -0.2, 1, 1, 1, 4\n");
  EXPECT_EQ(arcs(1).size(), 2u);
}

// ===========================================================================================
// §8.6 CR — Cut Rectangle
// ===========================================================================================

TEST(CutFacts, Fact82_CrParameterOrder) {
  const std::vector<std::string_view> want = {"length X",    "length Y",     "O/I/T",
                                              "direction",   "start corner", "plunge",
                                              "repetitions", "feature",      "plunge from Z 0"};
  EXPECT_EQ(names("CR"), want);
}

// The XY corners a rectangle cut visits, in order, from the moves of `line`.
std::vector<std::pair<double, double>> corners(const std::vector<CanonMove>& m) {
  std::vector<std::pair<double, double>> out;
  for (const CanonMove& c : m)
    if (c.speed_class == SpeedClass::Move && (c.from[0] != c.to[0] || c.from[1] != c.to[1])) {
      if (out.empty()) out.emplace_back(c.from[0], c.from[1]);
      out.emplace_back(c.to[0], c.to[1]);
    }
  return out;
}
using Corners = std::vector<std::pair<double, double>>;

TEST_F(CutCommands, Fact83_FabMoCrPocketsOutsideInAndInsideOut) {
  settings.dialect = Dialect::FabMo;
  run("CR, 3, 2, T, 1, 4, -0.2, 1, 2\n");
  const Corners oi = corners(of_line(1));
  EXPECT_EQ(oi[1], std::make_pair(0.0, 2.0));  // the outline first
  run("J3, 0, 0, 0\nCR, 3, 2, T, 1, 4, -0.2, 1, 3\n");
  const Corners io = corners(of_line(2));
  EXPECT_GT(io[1].first, 0.5);  // the innermost ring first
  EXPECT_EQ(io.back(), std::make_pair(0.0, 0.0));
}

TEST_F(CutCommands, Fact84_CrWithOnlyXCutsASquare) {
  run("CR, 4\n");  // D20
  EXPECT_EQ(corners(motion()), (Corners{{0, 0}, {0, 4}, {4, 4}, {4, 0}, {0, 0}}));
}

TEST_F(CutCommands, Fact85_CrLengthXIsRequired) {
  run_error("CR\n");
  EXPECT_TRUE(motion().empty());
}

TEST_F(CutCommands, Fact86_CrOutsideIsBiggerThanInside) {
  run("CR, 4, 2, O\nJ3, 0, 0, 0\nCR, 4, 2, I\n");
  EXPECT_EQ(corners(of_line(1)), (Corners{{0, 0}, {0, 2.25}, {4.25, 2.25}, {4.25, 0}, {0, 0}}));
  EXPECT_EQ(corners(of_line(3)), (Corners{{0, 0}, {0, 1.75}, {3.75, 1.75}, {3.75, 0}, {0, 0}}));
}

TEST_F(CutCommands, Fact87_CrDirectionDefaultsToClockwise) {
  run("CR, 4, 2\nCR, 4, 2, T, -1\n");  // D17, D18
  EXPECT_EQ(corners(of_line(1)), (Corners{{0, 0}, {0, 2}, {4, 2}, {4, 0}, {0, 0}}));
  EXPECT_EQ(corners(of_line(2)), (Corners{{0, 0}, {4, 0}, {4, 2}, {0, 2}, {0, 0}}));
}

TEST_F(CutCommands, Fact88_CrStartCornerCodes) {
  run("CR, 4, 2, T, 1, 1\nCR, 4, 2, T, 1, 2\nCR, 4, 2, T, 1, 3\nCR, 4, 2\n");
  EXPECT_EQ(corners(of_line(1)), (Corners{{0, 0}, {4, 0}, {4, -2}, {0, -2}, {0, 0}}));
  EXPECT_EQ(corners(of_line(2)), (Corners{{0, 0}, {0, -2}, {-4, -2}, {-4, 0}, {0, 0}}));
  EXPECT_EQ(corners(of_line(3)), (Corners{{0, 0}, {-4, 0}, {-4, 2}, {0, 2}, {0, 0}}));
  EXPECT_EQ(corners(of_line(4)), (Corners{{0, 0}, {0, 2}, {4, 2}, {4, 0}, {0, 0}}));
}

TEST_F(CutCommands, Fact89_CrStartsHereCorner3IsUpperLeftOfIt) {
  run("J2, 10, 5\nCR, 4, 2, T, 1, 3\n");  // D19
  const Corners c = corners(of_line(2));
  EXPECT_EQ(c.front(), std::make_pair(10.0, 5.0));
  for (const auto& p : c) EXPECT_TRUE(p.first <= 10 && p.second >= 5);
}

TEST_F(CutCommands, Fact90_CrPlungeDefaultsToZeroRepetitionsToOne) {
  run("JZ, 0.3\nCR, 4, 2\n");
  for (const CanonMove& m : of_line(2))
    if (m.speed_class == SpeedClass::Move) {
      EXPECT_NEAR(m.to[2], 0.3, 1e-12);
    }
  EXPECT_EQ(corners(of_line(2)).size(), 5u);  // once round
}

TEST_F(CutCommands, Fact91_CrTabsOnTheLastCutPocketInsideDefaultsOff) {
  run("CR, 8, 6, T, 1, 4, -0.25, 2, 1\n");
  double top_last = -kInf;
  int flat_first = 0;
  for (const CanonMove& m : of_line(1))
    if (m.speed_class == SpeedClass::Move) {
      if (m.to[2] < -0.26) top_last = std::max(top_last, m.to[2]);
      if (std::abs(m.to[2] + 0.25) < 1e-12 && std::abs(m.from[2] + 0.25) < 1e-12) ++flat_first;
    }
  EXPECT_EQ(flat_first, 4);                              // the first pass: 4 flat sides
  EXPECT_NEAR(top_last, -0.4, 1e-12);                    // the last: tabs 0.1 up
  run("J3, 0, 0, 0\nCR, 8, 6, T, 1, 4, -0.25, 1, 2\n");  // pocket: smaller rectangles inside
  EXPECT_GT(corners(of_line(2)).size(), 10u);
  run("J3, 0, 0, 0\nCR, 8, 6\n");  // default: neither
  EXPECT_EQ(corners(of_line(2)).size(), 5u);
}

// ===========================================================================================
// Errors: located, and nothing moves
// ===========================================================================================

struct BadCut {
  const char* text;
  int param;  // 1-based: the parameter at fault
  const char* words;
};

// The 1-based column where parameter `n` (1-based) of a command line starts.
int param_column(std::string_view line, int n) {
  size_t at = 2;  // after the code
  for (int k = 0; k < n; ++k) at = line.find(',', at) + 1;
  while (line[at] == ' ') ++at;
  return static_cast<int>(at) + 1;
}

TEST_F(CutCommands, BadParametersAreLocatedErrorsAndMoveNothing) {
  const BadCut cases[] = {
      {"CC, -2\n", 1, "diameter"},
      {"CC, 0\n", 1, "above 0"},
      {"CC, 2, T, 1, , , -0.5, 0\n", 7, "repetitions"},
      {"CC, 2, T, 0\n", 3, "direction"},
      {"CC, 2, X\n", 2, "O/I/T"},
      {"CC, 0.2, I\n", 2, "no path inside"},
      {"CC, 2, T, 1, , , 0, 1, 0\n", 8, "proportion X"},
      {"CA, 10, 6\n", 2, "half as high"},
      {"CA, 10, 0\n", 2, "height"},
      {"CA, -1, 0.2\n", 1, "arch length"},
      {"CR, 4, 2, T, 1, 5\n", 5, "start corner"},
      {"CR, 0.2, 0.2, I\n", 3, "no path inside"},
      {"CG, , 3, 0, 1, 0\n", 2, "not on the circle"},
      {"CG, , 3, 0, 0, 0\n", 4, "centre"},
      {"CP, 2, 5, 5, T, 1, 0, 0, 0, 1, 1, 1, 5\n", 12, "feature"},
  };
  for (const BadCut& c : cases) {
    const Diagnostic d = run_error(c.text);
    EXPECT_EQ(d.severity, Severity::Error) << c.text;
    EXPECT_EQ(d.loc.line, 1) << c.text;
    EXPECT_EQ(d.loc.column, param_column(c.text, c.param)) << c.text << d.message;
    EXPECT_NE(d.message.find(c.words), std::string::npos) << c.text << d.message;
    EXPECT_TRUE(motion().empty()) << c.text;
  }
}

TEST_F(CutCommands, ACircleCrossingTheSoftLimitsBetweenItsEndsMovesNothing) {
  settings.machine.limit_checking = true;
  // From (1, 5) a 2.5 circle spans X -0.25 to 2.25: only its 9 o'clock point is outside.
  const Diagnostic d = run_error("J2, 1, 5\nCC, 2.5\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_NE(d.message.find("soft limits"), std::string::npos) << d.message;
  EXPECT_EQ(motion().size(), 1u);  // the jog only
  run("J2, 1, 5\nCC, 2\n");        // X 0 to 2: inside
  EXPECT_EQ(arcs().size(), 1u);
}

// ===========================================================================================
// Decisions of docs/cuts.md and the transforms
// ===========================================================================================

// D9 for all five commands, as a CAM post uses them: the post's M3 puts the tool at depth
// and each cut, with no plunge, runs there and leaves it there (no Z move at all); with a
// plunge, Z goes back at the end to where the command started, at jog speed.
TEST_F(CutCommands, EveryCutCommandEndsAtItsStartZ) {
  struct Cut {
    const char* shape;   // the command with its shape, from (1, 1)
    const char* passes;  // the rest of its parameters, up to two passes of 0.25
  };
  const Cut cuts[] = {{"CA, 4, 1", ", T, 1, 0, -0.25, 2"},
                      {"CC, 2", ", T, 1, , , -0.25, 2"},
                      {"CG, , 2, 0, 1, 0", ", T, 1, -0.25, 2"},
                      {"CP, 2, 3, 0", ", T, 1, 0, 0, -0.25, 2"},
                      {"CR, 3, 2", ", T, 1, 4, -0.25, 2"}};
  for (const Cut& cut : cuts) {
    run(std::string("J3, 0, 0, 0.5\nM3, 1, 1, -0.22\n") + cut.shape + "\n");
    const std::vector<CanonMove> flat = of_line(3);
    ASSERT_FALSE(flat.empty()) << cut.shape;
    for (const CanonMove& m : flat) {
      EXPECT_NEAR(m.to[2], -0.22, 1e-12) << cut.shape;  // no lift, no plunge
      EXPECT_EQ(m.speed_class, SpeedClass::Move) << cut.shape;
    }
    // The same cut in two passes from Z 0.5: down to 0, then back up to 0.5.
    const std::string deeper = std::string(cut.shape) + cut.passes;
    run("J3, 1, 1, 0.5\n" + deeper + "\n");
    const std::vector<CanonMove> d = of_line(2);
    ASSERT_FALSE(d.empty()) << deeper;
    double low = kInf;
    for (const CanonMove& m : d) low = std::min(low, m.to[2]);
    EXPECT_NEAR(low, 0, 1e-12) << deeper;
    EXPECT_NEAR(d.back().to[2], 0.5, 1e-12) << deeper;
    EXPECT_EQ(d.back().speed_class, SpeedClass::Jog) << deeper;
    EXPECT_EQ(d.back().from[0], d.back().to[0]) << deeper;  // straight up
  }
}

TEST_F(CutCommands, CpCentreAndCgEndFollowRelativeMode) {
  run("J2, 1, 1\nSR\nCP, 2, 4, 4\nSA\nJ2, 1, 1\nSR\nCG, , 2, 0, 1, 0\n");
  EXPECT_NEAR(arcs(3).at(0).center_x, 5, 1e-12);
  EXPECT_NEAR(arcs(3)[0].center_y, 5, 1e-12);
  expect_xy(arcs(7).at(0), 3, 1);
}

TEST_F(CutCommands, FpScalingXAndYAlikeKeepsArcsUnevenlyMakesEllipsesAsLines) {
  files.texts["circle.sbp"] = "CC, 2\n";
  run("J2, 5, 5\nFP, circle.sbp, 2, 2, 1, 1, 2\n");
  ASSERT_EQ(arcs().size(), 1u);
  EXPECT_NEAR(arc_r(arcs()[0]), 2, 1e-12);
  run("J2, 5, 5\nFP, circle.sbp, 2, 1, 1, 1, 2\n");
  EXPECT_TRUE(arcs().empty());
  // The ellipse 4 x 2 centred at (5, 4): every point within the chord tolerance of it.
  double worst = 0;
  for (const CanonMove& m : motion()) {
    if (m.loc.line != 1 || m.speed_class != SpeedClass::Move) continue;
    for (int i = 0; i <= 8; ++i) {
      const P3 p = point(m, i / 8.0);
      const double r = std::hypot((p.x - 5) / 2, (p.y - 4) / 1);  // 1 on the ellipse
      worst = std::max(worst, std::abs(r - 1));
    }
  }
  EXPECT_GT(worst, 0);
  EXPECT_LE(worst, settings.planner.chord_tolerance);
}

TEST_F(CutCommands, MdTurnsFromTheDirectionAtTheEndOfAnArc) {
  // A clockwise quarter from 3 o'clock ends at 6 o'clock heading -X (west).
  run("CC, 2, T, 1, 90, 180, 0, 1, 1, 1, 0, 1\nMD, 1, 0R\n");
  const CanonMove m = motion().back();
  expect_xy(m, -2, -1);
}

TEST_F(CutCommands, APreviewSendsNoArcs) {
  run("SP\nCC, 2\nSM\n");
  EXPECT_TRUE(arcs().empty());
}

TEST_F(CutCommands, VbTabCountEndsTabbingWhenUsedUp) {
  settings.tabs = {0.1, 4, 1, 0.5};
  run("VB, , , , , 1, 2\nCC, 6, T, 1, , , -0.5\nJ3, 0, 0, 0\nCC, 6, T, 1, , , -0.5\n");
  auto tabs_of = [&](int line) {
    int rises = 0;
    for (const CanonMove& m : of_line(line))
      if (m.speed_class == SpeedClass::Move && m.to[2] > m.from[2] + 1e-9 && m.to[0] != m.from[0])
        ++rises;
    return rises;
  };
  EXPECT_EQ(tabs_of(2), 2);  // 4 would fit on 18.8; the count allows 2
  EXPECT_EQ(tabs_of(4), 0);  // used up: tabbing is off
  EXPECT_FALSE(interp().state().tabs_on);
}

// ---- tabs on plain moves (VB on, FP's tab feature) and FP's plunge from Z 0 -----------------

// The end points of the moves of `line` (all lines when 0) in `file` (all files when null).
std::vector<P3> ends_of(const std::vector<CanonMove>& moves, int line, const char* file = nullptr) {
  std::vector<P3> out;
  for (const CanonMove& m : moves)
    if ((line == 0 || m.loc.line == line) && (!file || (m.loc.file && *m.loc.file == file)))
      out.push_back({m.to[0], m.to[1], m.to[2]});
  return out;
}

void expect_points(const std::vector<P3>& got, const std::vector<P3>& want, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].x, want[i].x, 1e-12) << what << " " << i;
    EXPECT_NEAR(got[i].y, want[i].y, 1e-12) << what << " " << i;
    EXPECT_NEAR(got[i].z, want[i].z, 1e-12) << what << " " << i;
  }
}

// SB3's VB turns tab insertion on and off "in a file": the file's own cutting moves get
// tabs, the first at VB's distance from where the tool came down, then every spacing; a tab
// may run over several moves; lifting to Safe-Z starts a new series; OFF ends it.
TEST_F(CutCommands, VbOnTabsThePlainMovesOfAFile) {
  settings.tabs = {0.1, 4, 1, 0.5};  // up 0.1, every 4, level 1, leads 0.5
  settings.cutter.safe_z = 0.5;
  run("J3, 0, 0, 0.5\n"       // 1
      "VB, , , , , 1, , 2\n"  // 2: on, the first tab 2 along
      "M3, 0, 0, -0.25\n"     // 3
      "M2, 6, 0\n"            // 4: 0 to 6 along: the tab 2 to 4
      "M2, 6, 6\n"            // 5: 6 to 12: tabs 6 to 8 and 10 to 12
      "JZ, 0.5\n"             // 6: up to Safe-Z: the path ends
      "MZ, -0.25\n"           // 7
      "M2, 6, 9\n"            // 8: a new path, 0 to 3: up the tab that starts at 2
      "M2, 3, 9\n"            // 9: 3 to 6: the rest of it
      "VB, , , , , 0\n"       // 10: off
      "M2, 0, 9\n");          // 11
  const double cut = -0.25, tab = -0.15;
  expect_points(ends_of(motion(), 3), {{0, 0, cut}}, "line 3");
  expect_points(ends_of(motion(), 4),
                {{2, 0, cut}, {2.5, 0, tab}, {3.5, 0, tab}, {4, 0, cut}, {6, 0, cut}}, "line 4");
  expect_points(ends_of(motion(), 5),
                {{6, 0.5, tab},
                 {6, 1.5, tab},
                 {6, 2, cut},
                 {6, 4, cut},
                 {6, 4.5, tab},
                 {6, 5.5, tab},
                 {6, 6, cut}},
                "line 5");
  expect_points(ends_of(motion(), 8), {{6, 8, cut}, {6, 8.5, tab}, {6, 9, tab}}, "line 8");
  expect_points(ends_of(motion(), 9), {{5.5, 9, tab}, {5, 9, cut}, {3, 9, cut}}, "line 9");
  expect_points(ends_of(motion(), 11), {{0, 9, cut}}, "line 11");
  for (const CanonMove& m : motion())
    if (m.loc.line != 1 && m.loc.line != 6) {
      EXPECT_EQ(m.speed_class, SpeedClass::Move);
    }
}

// VB's number: that many tabs after the ON, then tabbing is off.
TEST_F(CutCommands, VbTabCountOnPlainMovesEndsTabbingWhenUsedUp) {
  settings.tabs = {0.1, 4, 1, 0.5};
  run("VB, , , , , 1, 2\nMZ, -0.25\nM2, 20, 0\nM2, 20, 4\n");
  int rises = 0;
  for (const CanonMove& m : of_line(3))
    if (m.to[2] > m.from[2] + 1e-9) ++rises;
  EXPECT_EQ(rises, 2);  // at 4 and 8; 12 and 16 would fit
  expect_points(ends_of(motion(), 4), {{20, 4, -0.25}}, "line 4");
  EXPECT_FALSE(interp().state().tabs_on);
  EXPECT_EQ(interp().state().tab_count, 0);
}

// FP 8: tabs on the last repetition only (a 2D template cut in two passes), measured along
// the file's path from where the pass starts; the plunge of each pass carries none.
TEST_F(CutCommands, FpTabFeatureTabsTheLastRepetitionOnly) {
  settings.tabs = {0.1, 4, 1, 0.5};
  files.texts["square.sbp"] = "M2, 4, 0\nM2, 4, 4\nM2, 0, 4\nM2, 0, 0\n";
  run("FP, square.sbp, , , , 2, , -0.25, 1\n");
  const double a = -0.25, b = -0.5, t = -0.4;
  expect_points(ends_of(motion(), 0, "square.sbp"),
                {{4, 0, a},
                 {4, 4, a},
                 {0, 4, a},
                 {0, 0, a},  // pass 1: none
                 {4, 0, b},  // 0 to 4: the first at 4
                 {4, 0.5, t},
                 {4, 1.5, t},
                 {4, 2, b},
                 {4, 4, b},  // 4 to 8
                 {3.5, 4, t},
                 {2.5, 4, t},
                 {2, 4, b},
                 {0, 4, b},  // 8 to 12
                 {0, 3.5, t},
                 {0, 2.5, t},
                 {0, 2, b},
                 {0, 0, b}},  // 12 to 16 (none at 16)
                "square.sbp");
  expect_points(ends_of(motion(), 1, "part.sbp"), {{0, 0, a}, {0, 0, b}}, "the plunges");
  EXPECT_FALSE(interp().state().tabs_on);     // FP's tabs are not VB's: nothing is left on
  run("FP, square.sbp, , , , 2, , -0.25\n");  // without: flat (from -0.5, where it ended)
  for (const P3& p : ends_of(motion(), 0, "square.sbp")) EXPECT_TRUE(p.z == -0.75 || p.z == -1);
}

// "If TABbing is turned on for a File, it remains on for individual sub-files within the
// file", and the cut commands in it leave tabs on their last pass; jogs carry none.
TEST_F(CutCommands, FpTabsReachSubFilesAndCutCommands) {
  settings.tabs = {0.1, 4, 1, 0.5};
  files.texts["square.sbp"] = "M2, 4, 0\nM2, 4, 4\nM2, 0, 4\nM2, 0, 0\n";
  files.texts["outer.sbp"] =
      "M3, 0, 0, -0.5\nFP, square.sbp\nJZ, 1\nJ3, 10, 10, 0\nCC, 6, T, 1, , , -0.5\n";
  run("FP, outer.sbp, , , , , , , 1\nM3, 0, 0, -0.5\nM2, 20, 0\n");
  int rises = 0;
  for (const CanonMove& m : motion())
    if (m.loc.file && *m.loc.file == "square.sbp" && m.to[2] > m.from[2] + 1e-9) ++rises;
  EXPECT_EQ(rises, 3);
  double top = -kInf;
  for (const CanonMove& m : motion())
    if (m.loc.file && *m.loc.file == "outer.sbp" && m.loc.line == 5 &&
        m.speed_class == SpeedClass::Move && m.to[2] < 0)
      top = std::max(top, m.to[2]);
  EXPECT_NEAR(top, -0.4, 1e-12);  // the CC's tabs, 0.1 above its depth
  expect_points(ends_of(motion(), 4, "outer.sbp"), {{10, 10, 0}}, "a jog is never tabbed");
  // After the FP the feature is off: the main file's own cut is flat.
  expect_points(ends_of(motion(), 3, "part.sbp"), {{20, 0, -0.5}}, "after the FP");
}

// FP 9: Z first goes to 0 (at move speed, where the tool is), and the plunges count from 0.
// Fact 103: FP's tabs "work with 3D moves": the tab rises above a ramp as it goes down.
TEST_F(CutCommands, Fact103_FpTabsWorkWith3DMoves) {
  settings.tabs = {0.1, 4, 1, 0.5};
  files.texts["ramp.sbp"] = "M3, 8, 0, -0.4\n";
  run("FP, ramp.sbp, , , , , , , 1\n");
  expect_points(ends_of(motion(), 0, "ramp.sbp"),
                {{4, 0, -0.2}, {4.5, 0, -0.125}, {5.5, 0, -0.175}, {6, 0, -0.3}, {8, 0, -0.4}},
                "ramp");
}

TEST_F(CutCommands, FpPlungeFromZeroMovesZToZeroFirst) {
  files.texts["square.sbp"] = "M2, 4, 0\nM2, 4, 4\nM2, 0, 4\nM2, 0, 0\n";
  run("M3, 1, 1, 0.5\nFP, square.sbp, , , , 2, , -0.25, , 1\n");
  expect_points(ends_of(motion(), 2, "part.sbp"), {{1, 1, 0}, {1, 1, -0.25}, {0, 0, -0.5}},
                "from Z 0");
  for (const CanonMove& m : motion())
    if (m.loc.file && *m.loc.file == "part.sbp" && m.loc.line == 2) {
      EXPECT_EQ(m.speed_class, SpeedClass::Move);
    }
  run("M3, 1, 1, 0.5\nFP, square.sbp, , , , 2, , -0.25\n");  // from where Z is
  expect_points(ends_of(motion(), 2, "part.sbp"), {{1, 1, 0.25}, {0, 0, 0}}, "from Z 0.5");
  // With the 3D offset, the file's 0 is placed after the move to Z 0: on the surface.
  run("M3, 1, 1, 0.5\nFP, square.sbp, , , , , 1, -0.25, , 1\n");
  expect_points(ends_of(motion(), 0, "square.sbp"),
                {{5, 1, -0.25}, {5, 5, -0.25}, {1, 5, -0.25}, {1, 1, -0.25}}, "3D offset");
}

TEST_F(CutCommands, FpTabAndFromZeroFlagsAreZeroOrOne) {
  files.texts["c.sbp"] = "MX, 1\n";
  const Diagnostic tabs = run_error("FP, c.sbp, , , , , , , 2\n");
  EXPECT_EQ(format(tabs),
            "part.sbp:1:24: error: FP parameter 8 (tab feature) is 2; allowed: 0 to 1");
  const Diagnostic zero = run_error("FP, c.sbp, , , , , , , , -1\n");
  EXPECT_EQ(zero.message, "FP parameter 9 (plunge from Z 0) is -1; allowed: 0 to 1");
  EXPECT_TRUE(motion().empty());
}

TEST(CutPlanner, SmallArcsRunAtTheRampSpeedLikeSmallCircles) {
  const Settings s = default_settings();
  CanonMove c;
  c.kind = MoveKind::Arc;
  c.from = Vec6::Zero();
  c.from[0] = 5.1;
  c.from[1] = 5;
  c.to = c.from;
  c.to[0] = 5;
  c.to[1] = 5.1;
  c.center_x = 5;
  c.center_y = 5;
  c.sweep = M_PI / 2;  // a quarter of a 0.2 circle
  c.speeds = s.speeds.move;
  struct Top : SegmentSink {
    void segment(const PlannedSegment& seg) override { v = std::max(v, seg.profile.v_cruise); }
    void flush() override {}
    double v = 0;
  } top;
  LookAheadPlanner p(s, top);
  p.move(c);
  p.flush();
  EXPECT_LE(top.v, s.ramps.move_ramp_speed.xy + 1e-12);
  EXPECT_GT(top.v, 0);
}

}  // namespace
}  // namespace gantry
