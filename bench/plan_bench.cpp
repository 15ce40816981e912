// Planner throughput (blocks per second on one core) and the cycle time each planner mode
// gives an adaptive-clearing-like path, against stopping at every move.
#include <benchmark/benchmark.h>  // the harness

#include <cmath>   // cos, sin
#include <random>  // path generation
#include <vector>

#include "gantry/motion/lookahead_planner.hpp"  // LookAheadPlanner

namespace {

using namespace gantry;

Vec6 xy(double x, double y) {
  Vec6 v = Vec6::Zero();
  v[0] = x;
  v[1] = y;
  return v;
}

// Segments of 0.002-0.05 in whose heading wanders a few degrees at a time, bouncing off the
// edges of a 20 x 14 in area: what adaptive clearing toolpaths look like.
const std::vector<Vec6>& adaptive_path() {
  static const std::vector<Vec6> pts = [] {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> len(0.002, 0.05);
    std::normal_distribution<double> turn(0, 3 * M_PI / 180);
    std::vector<Vec6> p = {xy(2, 2)};
    double heading = 0.3, x = 2, y = 2;
    for (int i = 0; i < 1'000'000; ++i) {
      heading += turn(rng);
      const double l = len(rng);
      double nx = x + l * std::cos(heading), ny = y + l * std::sin(heading);
      if (nx < 1 || nx > 21) heading = M_PI - heading;
      if (ny < 1 || ny > 15) heading = -heading;
      nx = x + l * std::cos(heading);
      ny = y + l * std::sin(heading);
      x = nx;
      y = ny;
      p.push_back(xy(x, y));
    }
    return p;
  }();
  return pts;
}

// Back and forth across 10 in at 0.02 in step-over: long moves and 90 deg corners.
const std::vector<Vec6>& zigzag_path() {
  static const std::vector<Vec6> pts = [] {
    std::vector<Vec6> p = {xy(2, 1)};
    for (int i = 0; i < 500'000; ++i) {
      const double x = (i / 2) % 2 ? 2 : 12;
      p.push_back(xy(i % 2 ? p.back()[0] : x, 1 + 0.02 * ((i + 1) / 2 % 700)));
    }
    return p;
  }();
  return pts;
}

class NullSegments : public SegmentSink {
 public:
  void segment(const PlannedSegment&) override { ++count; }
  void flush() override {}
  std::size_t count = 0;
};

// Plans `pts` in `mode` (with S-curve ramps of `jerk`, if above 0); returns the machine time.
// `eager`: re-plan every held block a new one changes as it arrives (before issue 27).
double plan(const std::vector<Vec6>& pts, PlannerMode mode, std::size_t* held = nullptr,
            double jerk = 0, bool eager = false) {
  static const Settings base = default_settings();
  Settings s = base;
  s.planner.mode = mode;
  s.planner.jerk = jerk;
  NullSegments out;
  LookAheadPlanner planner(s, out);
  planner.set_eager(eager);
  CanonMove m;
  m.speeds = s.speeds.move;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    m.from = pts[i - 1];
    m.to = pts[i];
    planner.move(m);
  }
  planner.flush();
  if (held) *held = planner.most_held();
  return planner.planned_time();
}

void blocks_per_second(benchmark::State& state, const std::vector<Vec6>& pts, PlannerMode mode,
                       double jerk = 0, bool eager = false) {
  std::size_t held = 0;
  for (auto _ : state) benchmark::DoNotOptimize(plan(pts, mode, &held, jerk, eager));
  state.counters["blocks/s"] = benchmark::Counter(
      static_cast<double>(pts.size() - 1) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
  state.counters["most_held"] = static_cast<double>(held);  // memory: constant in length
}

void BM_PlanAdaptiveSb3(benchmark::State& st) {
  blocks_per_second(st, adaptive_path(), PlannerMode::SB3);
}
void BM_PlanAdaptiveJunction(benchmark::State& st) {
  blocks_per_second(st, adaptive_path(), PlannerMode::Junction);
}
void BM_PlanZigzagSb3(benchmark::State& st) {
  blocks_per_second(st, zigzag_path(), PlannerMode::SB3);
}
void BM_PlanZigzagJunction(benchmark::State& st) {
  blocks_per_second(st, zigzag_path(), PlannerMode::Junction);
}
void BM_PlanAdaptiveJunctionJerk200(benchmark::State& st) {
  blocks_per_second(st, adaptive_path(), PlannerMode::Junction, 200);
}
// The same, re-planning eagerly as before issue 27: old and new in one run.
void BM_PlanAdaptiveJunctionJerk200Eager(benchmark::State& st) {
  blocks_per_second(st, adaptive_path(), PlannerMode::Junction, 200, true);
}
void BM_PlanAdaptiveSb3Jerk200(benchmark::State& st) {
  blocks_per_second(st, adaptive_path(), PlannerMode::SB3, 200);
}
void BM_PlanZigzagJunctionJerk200(benchmark::State& st) {
  blocks_per_second(st, zigzag_path(), PlannerMode::Junction, 200);
}
BENCHMARK(BM_PlanAdaptiveSb3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanAdaptiveJunctionJerk200Eager)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanAdaptiveSb3Jerk200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanZigzagJunctionJerk200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanAdaptiveJunctionJerk200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanAdaptiveJunction)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanZigzagSb3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanZigzagJunction)->Unit(benchmark::kMillisecond);

// Cycle time of the adaptive path: how many times faster than stopping at every move.
void BM_CycleTimeVsStopping(benchmark::State& state) {
  double stop = 0, sb3 = 0, junction = 0, jerk = 0;
  for (auto _ : state) {
    stop = plan(adaptive_path(), PlannerMode::Stop);
    sb3 = plan(adaptive_path(), PlannerMode::SB3);
    junction = plan(adaptive_path(), PlannerMode::Junction);
    jerk = plan(adaptive_path(), PlannerMode::Junction, nullptr, 200);
  }
  state.counters["stop_s"] = stop;
  state.counters["sb3_s"] = sb3;
  state.counters["junction_s"] = junction;
  state.counters["sb3_x_faster"] = stop / sb3;
  state.counters["junction_x_faster"] = stop / junction;
  state.counters["junction_jerk200_x_faster"] = stop / jerk;
}
BENCHMARK(BM_CycleTimeVsStopping)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
