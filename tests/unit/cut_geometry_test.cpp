// The geometry of the cut generators (src/cuts), asserted numerically on the paths they
// return: points on the nominal circle, cutter offsets, ellipses within the chord tolerance,
// pocket coverage, spiral depths, tabs and repetitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <vector>

#include "gantry/cuts/cuts.hpp"

namespace gantry::cuts {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

CutSetup setup_at(double x = 0, double y = 0, double z = 0) {
  CutSetup s = CutSetup::from(default_settings(), V3(x, y, z));
  return s;
}

// Points along every move, `per` per move (both ends included), with the move's role.
struct Sample {
  V3 p;
  Role role;
};
std::vector<Sample> samples(const CutPath& path, int per = 64) {
  std::vector<Sample> out;
  V3 at = path.start;
  for (const CutMove& m : path.moves) {
    for (int i = 0; i <= per; ++i) {
      const double f = static_cast<double>(i) / per;
      V3 p = at + (m.to - at) * f;
      if (m.arc) {
        const V2 rel = at.head<2>() - m.centre;
        const double a = std::atan2(rel.y(), rel.x()) + f * m.sweep;
        p.head<2>() = m.centre + rel.norm() * V2(std::cos(a), std::sin(a));
      }
      out.push_back({p, m.role});
    }
    at = m.to;
  }
  return out;
}

// Cutting points only.
std::vector<V3> cut_points(const CutPath& path, int per = 64) {
  std::vector<V3> out;
  for (const Sample& s : samples(path, per))
    if (s.role == Role::Cut) out.push_back(s.p);
  return out;
}

// The cutting arcs, with their start points.
struct ArcMove {
  V3 from;
  CutMove m;
};
std::vector<ArcMove> arcs(const CutPath& path) {
  std::vector<ArcMove> out;
  V3 at = path.start;
  for (const CutMove& m : path.moves) {
    if (m.arc) out.push_back({at, m});
    at = m.to;
  }
  return out;
}

// Distance from p to the exact curve, by a dense search of its parameter refined by
// golden-section search.
double distance_to_curve(const Curve& c, const V2& p) {
  const int n = 2000;
  double best = kInf, best_t = 0;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    const double d = (c.point(t) - p).norm();
    if (d < best) best = d, best_t = t;
  }
  double lo = best_t - 2 * M_PI / n, hi = best_t + 2 * M_PI / n;
  for (int i = 0; i < 100; ++i) {
    const double m1 = lo + (hi - lo) * 0.382, m2 = lo + (hi - lo) * 0.618;
    if ((c.point(m1) - p).norm() < (c.point(m2) - p).norm())
      hi = m2;
    else
      lo = m1;
  }
  return std::min(best, (c.point((lo + hi) / 2) - p).norm());
}

// ---- circles: T, O, I ------------------------------------------------------------------

TEST(CutGeometry, EveryPointOfATrueCircleIsOnTheNominalCircle) {
  CircleParams p;
  p.diameter = 3.7;
  for (double begin : {0.0, 37.0, 180.0, 290.0})
    for (int dir : {1, -1}) {
      p.begin = begin;
      p.direction = dir;
      p.pass.feature = 1;  // tabs split the circle into several helices
      p.pass.plunge = -0.3;
      p.pass.repetitions = 2;
      const CutPath path = cut_circle(setup_at(5, 5), p);
      const V2 start(5, 5);
      // The centre: the start is at `begin` on the circle.
      const double b = begin * M_PI / 180;
      const V2 centre = start - 1.85 * V2(std::sin(b), std::cos(b));
      ASSERT_FALSE(arcs(path).empty());
      for (const ArcMove& a : arcs(path)) {
        EXPECT_NEAR((a.m.centre - centre).norm(), 0, 1e-12);
        EXPECT_NEAR((a.from.head<2>() - centre).norm(), 1.85, 1e-9);
        EXPECT_NEAR((a.m.to.head<2>() - centre).norm(), 1.85, 1e-9);
      }
      for (const V3& q : cut_points(path)) EXPECT_NEAR((q.head<2>() - centre).norm(), 1.85, 1e-9);
      EXPECT_GT(path.tabs, 0);
    }
}

TEST(CutGeometry, OutsideAndInsidePathsAreOffsetByExactlyTheCutterRadius) {
  for (double cutter : {0.125, 0.25, 0.5}) {
    CutSetup s = setup_at(3, 3);
    s.cutter = cutter;
    CircleParams p;
    p.diameter = 2;
    for (Side side : {Side::Out, Side::In, Side::True}) {
      p.side = side;
      const CutPath path = cut_circle(s, p);
      const double want = 1 + side_offset(side, cutter);
      ASSERT_EQ(arcs(path).size(), 1u);
      const ArcMove a = arcs(path).front();
      EXPECT_NEAR((a.from.head<2>() - a.m.centre).norm(), want, 1e-12);
      // The nominal circle and the path share the centre, and the start stays put.
      EXPECT_NEAR((a.from.head<2>() - V2(3, 3)).norm(), 0, 1e-12);
      EXPECT_NEAR((a.m.centre - V2(3, 3 - want)).norm(), 0, 1e-12);
    }
  }
}

TEST(CutGeometry, EllipsePathsAreExactOffsetsWithinTheChordTolerance) {
  // D 16 with proportions 3 and 1: semi-axes 24 and 8, cut outside, inside and on the line.
  for (Side side : {Side::Out, Side::In, Side::True}) {
    CutSetup s = setup_at(0, 0);
    s.cutter = 0.5;
    CircleParams p;
    p.diameter = 16;
    p.proportion_x = 3;
    p.proportion_y = 1;
    p.side = side;
    const CutPath path = cut_circle(s, p);
    EXPECT_TRUE(arcs(path).empty());  // an ellipse is sent as lines
    Curve nominal;
    nominal.a = 24;
    nominal.b = 8;
    Curve exact = nominal;
    exact.offset = side_offset(side, 0.5);
    exact.centre = V2(0, 0) - exact.relative(0);
    nominal.centre = exact.centre;
    double worst_vertex = 0, worst_chord = 0;
    V3 at = path.start;
    for (const CutMove& m : path.moves) {
      if (m.role != Role::Cut) {
        at = m.to;
        continue;
      }
      // Every vertex is on the exact offset curve: the cutter radius from the ellipse.
      worst_vertex = std::max(worst_vertex, std::abs(distance_to_curve(nominal, m.to.head<2>()) -
                                                     std::abs(exact.offset)));
      for (double f : {0.25, 0.5, 0.75})  // and the chords stay within the tolerance
        worst_chord =
            std::max(worst_chord, distance_to_curve(exact, (at + (m.to - at) * f).head<2>()));
      at = m.to;
    }
    EXPECT_LT(worst_vertex, 1e-7) << static_cast<int>(side);
    EXPECT_LE(worst_chord, s.tolerance) << static_cast<int>(side);
    EXPECT_GT(worst_chord, 0.2 * s.tolerance);  // not needlessly fine
  }
}

TEST(CutGeometry, AnInsidePathWiderThanTheHoleIsRefused) {
  CutSetup s = setup_at();
  CircleParams p;
  p.diameter = 0.25;  // the cutter's own diameter: no path left inside
  p.side = Side::In;
  try {
    cut_circle(s, p);
    FAIL() << "no error";
  } catch (const CutError& e) {
    EXPECT_EQ(e.param, 1u);
  }
  p.diameter = 2;
  p.proportion_y = 0.1;  // an ellipse whose ends curve tighter than the cutter
  EXPECT_THROW(cut_circle(s, p), CutError);
}

// ---- arches --------------------------------------------------------------------------------

TEST(CutGeometry, ArchRadiusSweepAndCentreFollowFromSpanAndHeight) {
  struct Case {
    double len, h, radius, sweep_deg, cx, cy;
  } cases[] = {{10, 5, 5, 180, 5, 0}, {10, 2, 7.25, 87.2056, 5, -5.25}, {6, 1, 5, 73.7398, 3, -4}};
  for (const Case& c : cases) {
    ArchParams p;
    p.length = c.len;
    p.height = c.h;
    const CutPath path = cut_arch(setup_at(), p);
    ASSERT_EQ(arcs(path).size(), 1u);
    const ArcMove a = arcs(path).front();
    EXPECT_NEAR(a.m.centre.x(), c.cx, 1e-12);
    EXPECT_NEAR(a.m.centre.y(), c.cy, 1e-12);
    EXPECT_NEAR((a.from.head<2>() - a.m.centre).norm(), c.radius, 1e-12);
    EXPECT_NEAR(-a.m.sweep * 180 / M_PI, c.sweep_deg, 1e-4);  // clockwise
    EXPECT_NEAR((a.m.to.head<2>() - V2(c.len, 0)).norm(), 0, 1e-12);
    // The apex: the highest point is h above the span.
    double top = -kInf;
    for (const V3& q : cut_points(path, 2000)) top = std::max(top, q.y());
    EXPECT_NEAR(top, c.h, 1e-6);
  }
}

TEST(CutGeometry, ArchOutsideAndInsideAreConcentricOffsets) {
  ArchParams p;
  p.length = 10;
  p.height = 2;
  for (Side side : {Side::Out, Side::In}) {
    p.side = side;
    const CutPath path = cut_arch(setup_at(), p);
    const ArcMove a = arcs(path).front();
    EXPECT_NEAR((a.from.head<2>() - a.m.centre).norm(), 7.25 + side_offset(side, 0.25), 1e-12);
    EXPECT_NEAR((a.from.head<2>() - V2(0, 0)).norm(), 0, 1e-12);  // starts at the tool
    EXPECT_NEAR(-a.m.sweep * 180 / M_PI, 87.2056, 1e-4);          // same angle as the arch
  }
}

// ---- rectangles ----------------------------------------------------------------------------

TEST(CutGeometry, RectangleOutsideAndInsideAreTheCutterWiderAndNarrower) {
  for (Side side : {Side::Out, Side::In, Side::True}) {
    RectParams p;
    p.length_x = 4;
    p.length_y = 2;
    p.side = side;
    const CutPath path = cut_rectangle(setup_at(1, 1), p);
    double x0 = kInf, x1 = -kInf, y0 = kInf, y1 = -kInf;
    for (const V3& q : cut_points(path)) {
      x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x());
      y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
    }
    const double grow = 2 * side_offset(side, 0.25);
    EXPECT_NEAR(x1 - x0, 4 + grow, 1e-12);
    EXPECT_NEAR(y1 - y0, 2 + grow, 1e-12);
    EXPECT_NEAR(x0, 1, 1e-12);  // the start corner (lower left) is where the tool is
    EXPECT_NEAR(y0, 1, 1e-12);
  }
}

// ---- pockets ---------------------------------------------------------------------------------

// Every point of `inside` (a predicate on XY) is within `reach` of a cutting point at depth.
double worst_gap(const std::vector<V3>& cuts, double depth, double x0, double x1, double y0,
                 double y1, const std::function<bool(const V2&)>& inside) {
  std::vector<V2> floor;
  for (const V3& q : cuts)
    if (std::abs(q.z() - depth) < 1e-9) floor.push_back(q.head<2>());
  double worst = 0;
  const int n = 120;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const V2 g(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n);
      if (!inside(g)) continue;
      double best = kInf;
      for (const V2& f : floor) best = std::min(best, (f - g).norm());
      worst = std::max(worst, best);
    }
  return worst;
}

TEST(CutGeometry, CirclePocketLeavesNoIslandWiderThanTheOverlapAllows) {
  CutSetup s = setup_at(5, 5);
  CircleParams p;
  p.diameter = 3;
  p.side = Side::In;
  p.pass.feature = 2;
  p.pass.plunge = -0.25;
  const CutPath path = cut_circle(s, p);
  // Rings one step-over apart at most: every point of the path's disc is within half a
  // step-over of a ring, so neighbouring sweeps overlap by at least overlap % of the cutter.
  const double step = 0.25 * 0.9;
  const V2 c(5, 5 - 1.375);
  const double gap = worst_gap(cut_points(path, 256), -0.25, c.x() - 1.5, c.x() + 1.5, c.y() - 1.5,
                               c.y() + 1.5, [&](const V2& g) { return (g - c).norm() <= 1.375; });
  EXPECT_LE(gap, step / 2 + 1e-3);
  // And the whole hole (diameter 3) is within the cutter's radius of the path.
  const double hole = worst_gap(cut_points(path, 256), -0.25, c.x() - 1.5, c.x() + 1.5, c.y() - 1.5,
                                c.y() + 1.5, [&](const V2& g) { return (g - c).norm() <= 1.5; });
  EXPECT_LE(hole, 0.125 + 1e-3);
  // Rings are concentric and get smaller.
  double last = kInf;
  for (const ArcMove& a : arcs(path)) {
    const double r = (a.from.head<2>() - a.m.centre).norm();
    EXPECT_NEAR((a.m.centre - c).norm(), 0, 1e-12);
    EXPECT_LT(r, last);
    last = r;
  }
  EXPECT_LE(last, step / 2 + 1e-12);
  // Back at the start, then up to the start Z (D9; to Safe-Z, 1, before issue 21).
  EXPECT_NEAR((path.end() - V3(5, 5, 0)).norm(), 0, 1e-12);
}

TEST(CutGeometry, EllipseAndRectanglePocketsLeaveNoIsland) {
  CutSetup s = setup_at(0, 0);
  s.pocket_overlap = 30;
  const double step = 0.25 * 0.7;
  CircleParams e;
  e.diameter = 2;
  e.proportion_x = 1.5;
  e.pass.feature = 2;
  const CutPath ellipse = cut_circle(s, e);
  // The ellipse (1.5 x 1) centred at (0, -1).
  const double gap_e = worst_gap(cut_points(ellipse, 8), 0, -1.5, 1.5, -2, 0, [](const V2& g) {
    return std::pow(g.x() / 1.5, 2) + std::pow((g.y() + 1) / 1, 2) <= 1;
  });
  EXPECT_LE(gap_e, step / 2 + 1e-3);
  for (int feature : {2, 3}) {
    RectParams r;
    r.length_x = 3;
    r.length_y = 1.3;
    r.feature = feature;
    const CutPath rect = cut_rectangle(s, r);
    const double gap_r =
        worst_gap(cut_points(rect, 512), 0, 0, 3, 0, 1.3, [](const V2&) { return true; });
    EXPECT_LE(gap_r, step / 2 + 1e-3) << feature;
    // Back at the start corner; no plunge, so Z stays (D9; up to Safe-Z before issue 21).
    EXPECT_NEAR((rect.end() - V3(0, 0, 0)).norm(), 0, 1e-12);
  }
}

TEST(CutGeometry, RectanglePocketOutsideInStartsOnTheOutlineInsideOutAtTheCentre) {
  RectParams r;
  r.length_x = 3;
  r.length_y = 2;
  r.plunge = -0.2;
  r.feature = 2;
  const CutPath oi = cut_rectangle(setup_at(), r);
  // The first cutting move runs along the outline (x = 0, up the left side).
  ASSERT_GE(oi.moves.size(), 2u);
  EXPECT_EQ(oi.moves[0].role, Role::Plunge);
  EXPECT_NEAR(oi.moves[1].to.x(), 0, 1e-12);
  EXPECT_NEAR(oi.moves[1].to.y(), 2, 1e-12);
  r.feature = 3;
  const CutPath io = cut_rectangle(setup_at(), r);
  // Across at the start height to the innermost ring, down, then outward; the outline last.
  EXPECT_EQ(io.moves[0].role, Role::Cut);
  EXPECT_NEAR(io.moves[0].to.z(), 0, 1e-12);
  EXPECT_GT(io.moves[0].to.x(), 0.5);
  EXPECT_EQ(io.moves[1].role, Role::Plunge);
  const std::vector<CutMove>& m = io.moves;
  EXPECT_NEAR(m[m.size() - 2].to.x(), 0, 1e-12);  // the outline's last side ends at the start
  EXPECT_NEAR(m[m.size() - 2].to.y(), 0, 1e-12);
}

// ---- passes: plunge, repetitions, spiral, tabs ----------------------------------------------

TEST(CutGeometry, RepetitionsEndAtTheRightDepth) {
  for (int reps : {1, 2, 5}) {
    CircleParams p;
    p.diameter = 2;
    p.pass.plunge = -0.3;
    p.pass.repetitions = reps;
    p.pass.no_pull_up = true;
    const CutPath path = cut_circle(setup_at(0, 0, 0.5), p);
    EXPECT_NEAR(path.end().z(), 0.5 - 0.3 * reps, 1e-12);
    EXPECT_EQ(static_cast<int>(arcs(path).size()), reps);
    int k = 0;
    for (const ArcMove& a : arcs(path)) {  // each pass flat, one plunge deeper
      ++k;
      EXPECT_NEAR(a.from.z(), 0.5 - 0.3 * k, 1e-12);
      EXPECT_NEAR(a.m.to.z(), 0.5 - 0.3 * k, 1e-12);
    }
  }
}

TEST(CutGeometry, SpiralDepthIsMonotoneAndReachesTheTarget) {
  for (int feature : {3, 4})
    for (int reps : {1, 3}) {
      CircleParams p;
      p.diameter = 2;
      p.pass.plunge = -0.5;
      p.pass.repetitions = reps;
      p.pass.feature = feature;
      const CutPath path = cut_circle(setup_at(), p);
      double last = 0;
      bool first = true;
      for (const V3& q : cut_points(path)) {
        if (!first) {
          EXPECT_LE(q.z(), last + 1e-12);
        }
        last = q.z();
        first = false;
      }
      EXPECT_NEAR(last, -0.5 * reps, 1e-12);
      // The helix: Z falls in proportion to the angle turned (0.5 per turn).
      const std::vector<ArcMove> a = arcs(path);
      ASSERT_EQ(a.size(), static_cast<size_t>(reps + (feature == 4 ? 1 : 0)));
      for (int k = 0; k < reps; ++k) {
        EXPECT_NEAR(a[k].from.z() - a[k].m.to.z(), 0.5, 1e-12);
        EXPECT_NEAR(std::abs(a[k].m.sweep), 2 * M_PI, 1e-12);
      }
      if (feature == 4) {
        EXPECT_NEAR(a.back().from.z(), a.back().m.to.z(), 1e-12);
      }
      // No plunge before the first turn: it starts at the start height.
      EXPECT_NEAR(a.front().from.z(), 0, 1e-12);
    }
}

TEST(CutGeometry, TabsHaveTheConfiguredCountLengthAndHeight) {
  CutSetup s = setup_at();
  s.tab_sizes = {0.15, 3, 0.8, 0.4};  // height, spacing, size, leads
  CircleParams p;
  p.diameter = 4;  // circumference 12.566: tabs start at 3, 6, 9 (the next would end past it)
  p.pass.plunge = -0.5;
  p.pass.repetitions = 2;
  p.pass.feature = 1;
  const CutPath path = cut_circle(s, p);
  EXPECT_EQ(path.tabs, 3);
  // The last pass: the cutting moves after the plunge to -1, measured along the path.
  size_t first = 0;
  for (size_t i = 0; i < path.moves.size(); ++i)
    if (path.moves[i].role == Role::Plunge && std::abs(path.moves[i].to.z() + 1) < 1e-12) first = i;
  ASSERT_GT(first, 0u);
  double s_along = 0, raised = 0, level = 0, top = -kInf;
  int rises = 0;
  bool was_up = false;
  V3 at = path.moves[first].to;
  for (size_t i = first + 1; i < path.moves.size() && path.moves[i].role == Role::Cut; ++i) {
    const CutMove& m = path.moves[i];
    const double len =
        m.arc ? (at.head<2>() - m.centre).norm() * std::abs(m.sweep) : (m.to - at).head<2>().norm();
    const bool up = std::max(at.z(), m.to.z()) > -1 + 1e-9;
    if (up) {
      raised += len;
      top = std::max(top, m.to.z());
      if (std::abs(at.z() - m.to.z()) < 1e-12) level += len;
      if (!was_up) ++rises;
    }
    was_up = up && m.to.z() > -1 + 1e-9;
    s_along += len;
    at = m.to;
  }
  EXPECT_EQ(rises, 3);
  EXPECT_NEAR(top, -1 + 0.15, 1e-12);              // the tab height above the final depth
  EXPECT_NEAR(level, 3 * 0.8, 1e-9);               // the level part: the tab size
  EXPECT_NEAR(raised, 3 * (0.8 + 2 * 0.4), 1e-9);  // with both leads
  EXPECT_NEAR(s_along, 4 * M_PI, 1e-9);            // the whole last pass
  // The first pass has none.
  for (const CutMove& m : path.moves)
    if (m.role == Role::Cut && m.to.z() > -0.5 + 1e-9) ADD_FAILURE() << m.to.z();
}

TEST(CutGeometry, TabProfileStartsAtFirstAndRepeatsStartToStart) {
  TabPlan t;
  t.on = true;
  t.sizes = {0.1, 4, 1, 0.5};
  t.first = 1;
  int n = 0;
  const Profile p = tab_profile(12, t, 0.1, &n);
  EXPECT_EQ(n, 3);  // at 1, 5 and 9 (9 + 2 <= 12)
  EXPECT_DOUBLE_EQ(p.at(1), 0);
  EXPECT_DOUBLE_EQ(p.at(1.25), 0.05);
  EXPECT_DOUBLE_EQ(p.at(2), 0.1);
  EXPECT_DOUBLE_EQ(p.at(3), 0);
  EXPECT_DOUBLE_EQ(p.at(5.5), 0.1);
  t.most = 2;
  tab_profile(12, t, 0.1, &n);
  EXPECT_EQ(n, 2);
}

// Plain moves get their tabs one move at a time: the window of the series over [2.5, 6)
// holds the end of the tab at 1 (down from 2.5 to 3) and the start of the one at 5.
TEST(CutGeometry, TabWindowIsThePartOfTheSeriesOnOneMove) {
  TabPlan t;
  t.on = true;
  t.sizes = {0.1, 4, 1, 0.5};
  t.first = 1;
  int ended = -1;
  const Profile w = tab_window(t, 0.1, 2.5, 6, &ended);
  EXPECT_EQ(ended, 1);                 // the tab at 1 ends at 3; the one at 5 is still on at 6
  EXPECT_DOUBLE_EQ(w.at(0), 0.1);      // 2.5: the end of the first tab's top
  EXPECT_DOUBLE_EQ(w.at(0.25), 0.05);  // 2.75: half way down
  EXPECT_DOUBLE_EQ(w.at(1.5), 0);      // 4: between tabs
  EXPECT_DOUBLE_EQ(w.at(2.75), 0.05);  // 5.25: half way up the next
  EXPECT_DOUBLE_EQ(w.at(3.5), 0.1);    // 6: on its top
  tab_window(t, 0.1, 2.5, 7, &ended);
  EXPECT_EQ(ended, 2);
  // Cut into any moves, the windows make the same profile as the whole path's (every tab
  // fits on 11: at 1, 5 and 9).
  const Profile whole = tab_profile(11, t, 0.1, nullptr);
  const double cuts[] = {0, 0.7, 1.2, 2.5, 2.6, 5.5, 8.9, 9.75, 11};
  for (size_t i = 0; i + 1 < std::size(cuts); ++i) {
    const Profile part = tab_window(t, 0.1, cuts[i], cuts[i + 1], nullptr);
    for (int k = 0; k <= 20; ++k) {
      const double s = cuts[i] + (cuts[i + 1] - cuts[i]) * k / 20;
      EXPECT_NEAR(part.at(s - cuts[i]), whole.at(s), 1e-12) << s;
    }
  }
  t.most = 2;  // a count: the third tab is left out
  EXPECT_DOUBLE_EQ(tab_window(t, 0.1, 8, 11, &ended).at(2), 0);
  EXPECT_EQ(ended, 2);
}

// One move through the tab profile: exact breakpoints, each part a straight line.
TEST(CutGeometry, TabStretchCutsAMoveAtTheTabBreakpoints) {
  TabPlan t;
  t.on = true;
  t.sizes = {0.1, 4, 1, 0.5};
  t.first = 4;
  Piece line;
  line.from = V2(0, 0);
  line.to = V2(10, 0);
  int ended = 0;
  const CutPath p = tab_stretch(V3(0, 0, -0.5), 0, line, -0.5, 0, t, 0.1, &ended);
  const double want[][2] = {{4, -0.5}, {4.5, -0.4}, {5.5, -0.4}, {6, -0.5},
                            {8, -0.5}, {8.5, -0.4}, {9.5, -0.4}, {10, -0.5}};
  ASSERT_EQ(p.moves.size(), std::size(want));
  for (size_t i = 0; i < p.moves.size(); ++i) {
    EXPECT_FALSE(p.moves[i].arc);
    EXPECT_NEAR(p.moves[i].to.x(), want[i][0], 1e-12) << i;
    EXPECT_EQ(p.moves[i].to.y(), 0) << i;
    EXPECT_NEAR(p.moves[i].to.z(), want[i][1], 1e-12) << i;
  }
  EXPECT_EQ(ended, 2);
  // Ending half way up a tab, the next move starts there, lifted, and carries on.
  const CutPath a = tab_stretch(V3(0, 0, -0.5), 0, line, -0.5, 0, t, 0.1, nullptr);
  Piece first = line, second = line;
  first.to = V2(4.25, 0);
  second.from = V2(4.25, 0);
  const CutPath b1 = tab_stretch(V3(0, 0, -0.5), 0, first, -0.5, 0, t, 0.1, nullptr);
  EXPECT_NEAR(b1.end().z(), -0.45, 1e-12);
  const CutPath b2 = tab_stretch(b1.end(), 0.05, second, -0.5, 4.25, t, 0.1, nullptr);
  EXPECT_NEAR(b2.moves.front().to.x(), 4.5, 1e-12);
  EXPECT_NEAR(b2.moves.front().to.z(), -0.4, 1e-12);
  EXPECT_NEAR(b2.end().z(), a.end().z(), 1e-12);
  EXPECT_EQ(b2.moves.size(), a.moves.size() - 1);  // the same moves, the first one split
  // On an arc, the parts are arcs about the same centre (helices where Z changes).
  Piece arc;
  arc.arc = true;
  arc.from = V2(2, 0);
  arc.to = V2(2, 0);
  arc.centre = V2(0, 0);
  arc.sweep = 2 * M_PI;  // 12.566 around: tabs at 4, 8 and 12, the last one still going up
  const CutPath c = tab_stretch(V3(2, 0, -0.5), 0, arc, -0.5, 0, t, 0.1, &ended);
  ASSERT_EQ(c.moves.size(), 11u);
  double swept = 0;
  for (const CutMove& m : c.moves) {
    EXPECT_TRUE(m.arc);
    EXPECT_EQ(m.centre, V2(0, 0));
    EXPECT_NEAR(m.to.head<2>().norm(), 2, 1e-12);
    swept += m.sweep;
  }
  EXPECT_NEAR(swept, 2 * M_PI, 1e-12);
  EXPECT_NEAR(c.moves[1].to.z(), -0.4, 1e-12);  // at 4.5 along
  EXPECT_NEAR(c.end().z(), -0.4, 1e-12);        // on the third tab's top: the path may go on
  EXPECT_EQ(ended, 2);
}

// Between passes an open path lifts clear of the work (Safe-Z, or the start if higher) to go
// back to its start: the start Z alone would not do, as a cut may start at depth (D8). At
// the end it returns to the start Z (D9), here 0, not Safe-Z as before issue 21.
TEST(CutGeometry, OpenArcsGoBackToTheStartAboveTheWorkBetweenPasses) {
  CircleParams p;
  p.diameter = 2;
  p.begin = 90;
  p.end = 180;
  p.pass.plunge = -0.2;
  p.pass.repetitions = 2;
  const CutPath path = cut_circle(setup_at(), p);
  std::vector<Role> roles;
  for (const CutMove& m : path.moves) roles.push_back(m.role);
  const std::vector<Role> want = {Role::Plunge, Role::Cut, Role::Retract, Role::Reposition,
                                  Role::Plunge, Role::Cut, Role::Retract};
  EXPECT_EQ(roles, want);
  EXPECT_NEAR(path.moves[2].to.z(), 1, 1e-12);  // Safe-Z
  EXPECT_NEAR(path.moves[3].to.head<2>().norm(), 0, 1e-12);
  EXPECT_NEAR(path.moves[4].to.z(), -0.4, 1e-12);
  EXPECT_NEAR(path.end().z(), 0, 1e-12);  // the start Z
  // Started at depth (below Safe-Z, in the work): still up to Safe-Z between passes.
  const CutPath deep = cut_circle(setup_at(0, 0, -0.3), p);
  EXPECT_NEAR(deep.moves.at(2).to.z(), 1, 1e-12);
  EXPECT_NEAR(deep.end().z(), -0.3, 1e-12);
  // Started above Safe-Z: never down to it.
  EXPECT_NEAR(cut_circle(setup_at(0, 0, 2.5), p).moves.at(2).to.z(), 2.5, 1e-12);
}

// D9, FabMo's rule (runtime/opensbp/commands/cut.js, end of CG and CR): unless "no pull up"
// is 1, Z ends where the command started, and moves only if the command changed it. Until
// issue 21 this test was PullUpGoesToSafeZOrStaysAboveIt: every cut ended at Safe-Z, which
// turned each CG of a CAM profile (cut at the depth the post's M3 set, no plunge) into a
// lift and a long ramp back down through the work.
TEST(CutGeometry, PullUpReturnsToTheStartZOnlyWhenTheCutChangedIt) {
  CircleParams p;
  p.diameter = 2;
  p.pass.plunge = -0.2;
  const CutPath from_top = cut_circle(setup_at(0, 0, 0), p);
  EXPECT_NEAR(from_top.end().z(), 0, 1e-12);             // back to the start, not to Safe-Z (1)
  EXPECT_EQ(from_top.moves.back().role, Role::Retract);  // out of the work: at jog speed
  EXPECT_NEAR(cut_circle(setup_at(0, 0, 2.5), p).end().z(), 2.5, 1e-12);
  p.pass.no_pull_up = true;
  EXPECT_NEAR(cut_circle(setup_at(0, 0, 0), p).end().z(), -0.2, 1e-12);  // stays at depth
  p.pass.no_pull_up = false;

  // No plunge, from depth (a post's M3 to -0.22, then CG ... T, 1): Z never moves.
  GcodeArcParams arc;
  arc.end = V2(2, 0);
  arc.center_offset = V2(1, 0);
  const CutPath flat = cut_gcode_arc(setup_at(0, 0, -0.22), arc);
  ASSERT_EQ(flat.moves.size(), 1u);
  EXPECT_TRUE(flat.moves[0].arc);
  EXPECT_NEAR(flat.moves[0].to.z(), -0.22, 1e-12);
  EXPECT_EQ(flat.moves[0].role, Role::Cut);

  // Plunge from Z 0 from below the surface: up to 0, the pass at -0.1, then down again to
  // the start, at move speed (into the work), as FabMo's CG returns to its start Z.
  p.pass.plunge = -0.1;
  p.pass.from_zero = true;
  const CutPath below = cut_circle(setup_at(0, 0, -0.5), p);
  EXPECT_NEAR(below.moves.front().to.z(), 0, 1e-12);
  EXPECT_NEAR(below.end().z(), -0.5, 1e-12);
  EXPECT_EQ(below.moves.back().role, Role::Plunge);
  p.pass.from_zero = false;

  CutSetup plus = setup_at(0, 0, 0);
  plus.plunge_negative = false;  // VC +: positive Z goes into the material
  p.pass.plunge = 0.2;
  p.pass.feature = 1;
  p.diameter = 6;
  const CutPath path = cut_circle(plus, p);
  EXPECT_NEAR(path.end().z(), 0, 1e-12);             // back to the start
  EXPECT_EQ(path.moves.back().role, Role::Retract);  // towards -Z is out of the work
  double lowest = kInf;
  for (const V3& q : cut_points(path)) lowest = std::min(lowest, q.z());
  EXPECT_NEAR(lowest, 0.2 - 0.1, 1e-12);  // the tabs lift towards -Z
}

TEST(CutGeometry, SweepsBeyondOneTurnAreOneTurn) {
  double b = 0, s = 0;
  angles(0.0, 720.0, 1, &b, &s);
  EXPECT_DOUBLE_EQ(s, 360);
  angles(90.0, 180.0, -1, &b, &s);
  EXPECT_DOUBLE_EQ(s, 270);
  angles(90.0, -180.0, -1, &b, &s);
  EXPECT_DOUBLE_EQ(s, 270);
  angles(0.0, 450.0, 1, &b, &s);
  EXPECT_DOUBLE_EQ(s, 90);
}

TEST(CutGeometry, ArcExtremesAreWhereTheArcCrossesTheAxes) {
  const std::vector<V2> e = arc_extremes(V2(1, 0), V2(0, 0), M_PI);  // counter-clockwise half
  ASSERT_EQ(e.size(), 1u);
  EXPECT_NEAR((e[0] - V2(0, 1)).norm(), 0, 1e-12);
  EXPECT_EQ(arc_extremes(V2(1, 0), V2(0, 0), -2 * M_PI).size(), 3u);  // 3 besides the ends
}

}  // namespace
}  // namespace gantry::cuts
