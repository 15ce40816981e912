// The look-ahead planner's passes run only when the front is sent and stop at the first block
// at its corner speed: the plan equals re-planning every block at once (the planner before
// issue 27, kept as set_eager), with far fewer bounds computed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "gantry/motion/lookahead_planner.hpp"
#include "segment_builders.hpp"

namespace gantry {
namespace {

using test::Collect;
using test::vec;

CanonMove line(const Vec6& from, const Vec6& to, const Settings& s) {
  CanonMove m;
  m.from = from;
  m.to = to;
  m.speeds = s.speeds.move;
  return m;
}

// Segments of 0.002-0.05 in whose heading wanders a few degrees at a time (adaptive
// clearing, as bench/plan_bench.cpp), with a sharp turn now and then.
std::vector<Vec6> adaptive_path(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> len(0.002, 0.05), u(0, 1);
  std::normal_distribution<double> turn(0, 3 * M_PI / 180);
  std::vector<Vec6> p = {vec(2, 2)};
  double heading = 0.3, x = 2, y = 2;
  for (int i = 0; i < n; ++i) {
    heading += u(rng) < 0.01 ? M_PI / 2 : turn(rng);
    const double l = len(rng);
    if (x + l * std::cos(heading) < 1 || x + l * std::cos(heading) > 21) heading = M_PI - heading;
    if (y + l * std::sin(heading) < 1 || y + l * std::sin(heading) > 15) heading = -heading;
    x += l * std::cos(heading);
    y += l * std::sin(heading);
    p.push_back(vec(x, y, u(rng) < 0.05 ? -0.1 : 0));
  }
  return p;
}

// What the planner is given besides moves, at given points of the path.
enum class Event { None, Override, Hold, Resume, Dwell, Stop };

struct Planned {
  std::vector<PlannedSegment> segs;
  size_t replanned = 0;
};

Planned plan(const Settings& s, const std::vector<Vec6>& pts, bool eager,
             const std::vector<Event>& events = {}) {
  Collect out;
  LookAheadPlanner p(s, out);
  p.set_eager(eager);
  for (size_t i = 1; i < pts.size(); ++i) {
    switch (i < events.size() ? events[i] : Event::None) {
      case Event::Override:
        p.feed_override(0.3 + static_cast<double>(i % 7) * 0.25);
        break;
      case Event::Hold:
        p.feedhold();
        break;
      case Event::Resume:
        p.resume();
        break;
      case Event::Dwell: {
        CanonMove d;
        d.kind = MoveKind::Dwell;
        d.dwell_s = 0.01;
        d.from = d.to = pts[i - 1];
        p.move(d);
        break;
      }
      case Event::Stop: {
        CanonMove m;
        m.kind = MoveKind::Stop;
        p.move(m);
        break;
      }
      case Event::None:
        break;
    }
    p.move(line(pts[i - 1], pts[i], s));
  }
  p.resume();
  p.flush();
  return {out.segs, p.replanned()};
}

// Bit for bit: the same recursions over the same values, in another order.
void expect_same_plan(const Planned& lazy, const Planned& eager) {
  ASSERT_EQ(lazy.segs.size(), eager.segs.size());
  for (size_t k = 0; k < lazy.segs.size(); ++k) {
    const Trapezoid &a = lazy.segs[k].profile, &b = eager.segs[k].profile;
    ASSERT_EQ(lazy.segs[k].to, eager.segs[k].to) << k;
    ASSERT_EQ(a.length, b.length) << k;
    ASSERT_EQ(a.v_entry, b.v_entry) << k;
    ASSERT_EQ(a.v_cruise, b.v_cruise) << k;
    ASSERT_EQ(a.v_exit, b.v_exit) << k;
    ASSERT_EQ(a.duration(), b.duration()) << k;
    ASSERT_EQ(lazy.segs[k].dwell_s, eager.segs[k].dwell_s) << k;
  }
}

struct Mode {
  PlannerMode mode;
  double jerk;
  int lookahead;
};

class LookaheadReplan : public ::testing::TestWithParam<Mode> {
 protected:
  Settings settings() const {
    Settings s = default_settings();
    s.planner.mode = GetParam().mode;
    s.planner.jerk = GetParam().jerk;
    s.planner.lookahead = GetParam().lookahead;
    return s;
  }
};

TEST_P(LookaheadReplan, SendingFromTheSettledFrontGivesTheEagerPlan) {
  const Settings s = settings();
  const std::vector<Vec6> pts = adaptive_path(6000, 11);
  const Planned lazy = plan(s, pts, false), eager = plan(s, pts, true);
  expect_same_plan(lazy, eager);
  // The ramp down at the tail is re-planned once per block sent, not once per block added.
  const double blocks = static_cast<double>(pts.size() - 1);
  const double per_block = static_cast<double>(lazy.replanned) / blocks,
               eager_per_block = static_cast<double>(eager.replanned) / blocks;
  std::printf("bounds computed per block: %.2f, eagerly %.2f\n", per_block, eager_per_block);
  EXPECT_LE(per_block, eager_per_block);
  if (GetParam().lookahead > 100) {
    EXPECT_LE(per_block, 1.1);
    // stop mode: every bound is its corner speed, 0, and the eager pass stops at once too
    if (GetParam().mode != PlannerMode::Stop) {
      EXPECT_GE(eager_per_block, 3);
    }
    if (GetParam().jerk > 0) {
      EXPECT_GE(eager_per_block, 5);
    }
  }
}

// Feed override, holds, dwells and MS/JS stops mid-stream: each re-plans what is held.
TEST_P(LookaheadReplan, OverridesHoldsAndStopsGiveTheEagerPlan) {
  const Settings s = settings();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    const std::vector<Vec6> pts = adaptive_path(3000, 20 + static_cast<unsigned>(trial));
    std::vector<Event> events(pts.size(), Event::None);
    std::uniform_int_distribution<size_t> at(1, pts.size() - 1);
    std::uniform_int_distribution<int> kind(1, 5);
    for (int e = 0; e < 12; ++e) {
      const size_t i = at(rng);
      events[i] = static_cast<Event>(kind(rng));
      if (events[i] == Event::Hold && i + 40 < events.size()) events[i + 40] = Event::Resume;
    }
    SCOPED_TRACE(trial);
    expect_same_plan(plan(s, pts, false, events), plan(s, pts, true, events));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Modes, LookaheadReplan,
    ::testing::Values(Mode{PlannerMode::SB3, 0, 1024}, Mode{PlannerMode::Junction, 0, 1024},
                      Mode{PlannerMode::Stop, 0, 1024}, Mode{PlannerMode::Junction, 200, 1024},
                      Mode{PlannerMode::SB3, 500, 1024}, Mode{PlannerMode::Junction, 200, 8},
                      Mode{PlannerMode::SB3, 0, 2}),
    [](const auto& info) {
      return std::string(planner_mode_name(info.param.mode)) +
             (info.param.jerk > 0 ? "_jerk" : "") + "_lookahead" +
             std::to_string(info.param.lookahead);
    });

}  // namespace
}  // namespace gantry
