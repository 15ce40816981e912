// StepGenerator: planned segments to pulse words. The words are decoded here, independently
// of SimCard, from the pin map and the documented line conventions.
#include <gtest/gtest.h>

#include "segment_builders.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gantry/hal/card.hpp"
#include "gantry/hal/pin_map.hpp"
#include "gantry/motion/planned_segment.hpp"
#include "gantry/motion/trapezoid.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/step/step_generator.hpp"

namespace gantry {
namespace {

// A card that keeps every word it is given.
class RecordingCard : public Card {
 public:
  void start(double) override {}
  void write(std::span<const std::uint32_t> words) override {
    words_.insert(words_.end(), words.begin(), words.end());
    ++writes_;
  }
  void drain() override {}
  std::uint64_t ticks_played() const override { return words_.size(); }
  void stop(std::uint32_t) override {}
  std::uint32_t inputs() const override { return 0; }
  CardFault fault() const override { return CardFault::None; }

  const std::vector<std::uint32_t>& words() const { return words_; }
  int writes() const { return writes_; }

 private:
  std::vector<std::uint32_t> words_;
  int writes_ = 0;
};

// ---------------------------------------------------------------------------------------
// Decoding. Conventions (docs/settings.md): the step line is active high unless
// step_active_low; the direction line is low for positive travel (high with invert_dir).

bool step_active(std::uint32_t word, const AxisPins& p) {
  return ((word & p.step_mask) != 0) != p.step_active_low;
}
bool dir_positive(std::uint32_t word, const AxisPins& p) {
  const bool high = (word & p.dir_mask) != 0;
  return p.invert_dir ? high : !high;
}

constexpr std::int64_t kNoEnd = -1;

struct Pulse {
  std::int64_t start = 0;
  std::int64_t end = kNoEnd;  // first tick with the line idle again
  bool positive = true;       // direction level at the active edge
};

struct DirChange {
  std::int64_t tick = 0;
  bool positive = true;
};

struct AxisTrace {
  std::vector<Pulse> pulses;
  std::vector<DirChange> dir_changes;
  std::int64_t net = 0;  // signed step count
};

struct Trace {
  std::array<AxisTrace, kAxisCount> axes;
  std::uint32_t stray_bits = 0;  // bits outside every step and dir line that were ever set
};

// The lines rest idle and pointing positive before the first word.
Trace decode(const std::vector<std::uint32_t>& words, const PinMap& pins) {
  Trace tr;
  std::uint32_t used = 0;
  for (const AxisPins& p : pins.axes) used |= p.step_mask | p.dir_mask;
  for (std::uint32_t w : words) tr.stray_bits |= w & ~used;
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisPins& p = pins.axes[i];
    AxisTrace& a = tr.axes[i];
    bool active = false, positive = true;
    for (std::size_t t = 0; t < words.size(); ++t) {
      const std::uint32_t w = words[t];
      const auto tick = static_cast<std::int64_t>(t);
      const bool pos = dir_positive(w, p);
      if (pos != positive) a.dir_changes.push_back({tick, pos});
      positive = pos;
      const bool act = step_active(w, p);
      if (act && !active) {
        a.pulses.push_back({tick, kNoEnd, positive});
        a.net += positive ? 1 : -1;
      } else if (!act && active) {
        a.pulses.back().end = tick;
      }
      active = act;
    }
  }
  return tr;
}

// The first timing problem of one axis, or "" when every rule holds.
std::string timing_problem(const AxisTrace& a, const StepTiming& tm) {
  std::ostringstream out;
  for (std::size_t j = 0; j < a.pulses.size(); ++j) {
    const Pulse& p = a.pulses[j];
    if (p.end == kNoEnd) {
      out << "pulse at " << p.start << " never ends";
      return out.str();
    }
    if (p.end - p.start != tm.pulse_ticks) {
      out << "pulse at " << p.start << " is " << p.end - p.start << " ticks wide";
      return out.str();
    }
    if (j > 0 && p.start - a.pulses[j - 1].start < tm.min_period_ticks) {
      out << "steps at " << a.pulses[j - 1].start << " and " << p.start << " too close";
      return out.str();
    }
  }
  std::size_t next = 0;  // first pulse starting at or after the direction change
  for (const DirChange& d : a.dir_changes) {
    while (next < a.pulses.size() && a.pulses[next].start < d.tick) ++next;
    if (next > 0 && a.pulses[next - 1].end > d.tick) {
      out << "direction changed at " << d.tick << " during the pulse at "
          << a.pulses[next - 1].start;
      return out.str();
    }
    if (next < a.pulses.size() && a.pulses[next].start - d.tick < tm.dir_setup_ticks) {
      out << "direction changed at " << d.tick << ", only " << a.pulses[next].start - d.tick
          << " ticks before the step";
      return out.str();
    }
  }
  return "";
}

// Run-length encoding of an axis's step directions: (positive, count) per run.
using Runs = std::vector<std::pair<bool, std::int64_t>>;

void append_run(Runs& runs, bool positive, std::int64_t n) {
  if (n == 0) return;
  if (!runs.empty() && runs.back().first == positive)
    runs.back().second += n;
  else
    runs.emplace_back(positive, n);
}

Runs decoded_runs(const AxisTrace& a) {
  Runs r;
  for (const Pulse& p : a.pulses) append_run(r, p.positive, 1);
  return r;
}

// ---------------------------------------------------------------------------------------
// Segments.

using test::segment;
using test::vec;

PlannedSegment rest_to_rest(const Vec6& from, const Vec6& to, double v_max, double accel = 14) {
  return segment(from, to, 0, v_max, 0, accel);
}

std::int64_t target_steps(double units, double spu) {
  return std::llround(units * spu);
}

// Random 6-axis sequences, each block of ten kinds holding every kind once in random order:
// ordinary moves, reversals, moves of one to three steps, very slow moves (tens of steps per
// second), single-axis moves, and a fast there-and-back pair at constant speed (50 000 to
// 125 000 steps/s: an abrupt reversal, and above the card's 100 000 steps/s so that steps
// must be delayed). About a third of the others get non-zero entry and exit speeds.
// Durations are kept to tens of milliseconds to stay fast.
std::vector<PlannedSegment> random_segments(std::uint32_t seed, int count, const Settings& s) {
  std::mt19937 rng(seed);
  auto uni = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  auto chance = [&](double p) { return uni(0, 1) < p; };
  std::vector<PlannedSegment> out;
  std::array<int, 10> kinds{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  Vec6 pos = Vec6::Zero();
  Vec6 last_delta = vec(0.1);
  auto push = [&](const Vec6& delta, double ve, double v_max, double vx, double accel) {
    out.push_back(segment(pos, pos + delta, ve, v_max, vx, accel));
    pos += delta;
    last_delta = delta;
  };
  for (int k = 0; static_cast<int>(out.size()) < count; ++k) {
    if (k % 10 == 0) std::shuffle(kinds.begin(), kinds.end(), rng);
    const int kind = kinds[k % 10];
    if (kind == 8) {  // fast there and back at constant speed: an abrupt reversal
      const int i = pick(0, 2);
      const double spu = s.axes[i].steps_per_unit;
      const int there = pick(20, 200) * (chance(0.5) ? 1 : -1), back = -pick(10, 200);
      const double v1 = uni(50e3, 125e3) / spu, v2 = uni(50e3, 125e3) / spu;
      Vec6 d = Vec6::Zero();
      d[i] = there / spu;
      push(d, v1, v1, v1, 1);
      d[i] = (there > 0 ? back : -back) / spu;
      push(d, v2, v2, v2, 1);
      continue;
    }
    Vec6 delta = Vec6::Zero();
    double duration = uni(0.01, 0.08);  // target, seconds
    if (kind <= 3) {                    // ordinary
      for (int i = 0; i < kAxisCount; ++i)
        if (chance(0.6)) delta[i] = i < 3 ? uni(-0.25, 0.25) : uni(-1.5, 1.5);
    } else if (kind <= 5) {  // reversal of part of the previous move
      delta = -last_delta * uni(0.2, 1.0);
    } else if (kind == 6) {  // one to three steps on one or two axes
      for (int m = 0; m < 2; ++m) {
        const int i = pick(0, kAxisCount - 1);
        delta[i] = pick(1, 3) * (chance(0.5) ? 1 : -1) / s.axes[i].steps_per_unit;
      }
    } else if (kind == 7) {  // very slow: a few tens of steps per second
      const int i = pick(0, kAxisCount - 1);
      const int steps = pick(2, 8) * (chance(0.5) ? 1 : -1);
      delta[i] = steps / s.axes[i].steps_per_unit;
      if (chance(0.5)) delta[(i + 1) % kAxisCount] = -delta[i] / 2;
      duration = std::abs(steps) / uni(20, 60);
    } else {  // one linear axis, longer
      delta[pick(0, 2)] = uni(-0.6, 0.6);
    }
    if (delta.norm() == 0) delta[0] = 1 / s.axes[0].steps_per_unit;
    const double L = delta.norm();
    const double v_max = L / duration;
    const double accel = v_max / (duration * uni(0.1, 0.5));  // ramps take 10-50 %
    double ve = 0, vx = 0;
    if (kind != 7 && chance(0.35)) {  // a reachable pair of end speeds within v_max
      ve = uni(0, v_max);
      const double lo = std::sqrt(std::max(0.0, ve * ve - 2 * accel * L));
      const double hi = std::min(v_max, std::sqrt(ve * ve + 2 * accel * L));
      vx = uni(lo, hi);
    }
    push(delta, ve, v_max, vx, accel);
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// The checker itself must reject what it is meant to reject.

TEST(TimingChecker, RejectsEachKindOfBadTrace) {
  StepTiming tm;  // 1-tick pulse, 1-tick setup, 2-tick period
  AxisTrace wide;
  wide.pulses = {{0, 2, true}};
  EXPECT_NE(timing_problem(wide, tm), "");
  AxisTrace open;
  open.pulses = {{0, kNoEnd, true}};
  EXPECT_NE(timing_problem(open, tm), "");
  AxisTrace close;
  close.pulses = {{0, 1, true}, {1, 2, true}};
  EXPECT_NE(timing_problem(close, tm), "");
  AxisTrace during;
  tm.pulse_ticks = 2;
  during.pulses = {{0, 2, true}, {5, 7, false}};
  during.dir_changes = {{1, false}};
  EXPECT_NE(timing_problem(during, tm), "");
  AxisTrace setup;
  tm.pulse_ticks = 1;
  setup.pulses = {{0, 1, true}, {3, 4, false}};
  setup.dir_changes = {{3, false}};
  EXPECT_NE(timing_problem(setup, tm), "");
  setup.dir_changes = {{2, false}};
  EXPECT_EQ(timing_problem(setup, tm), "");
  setup.dir_changes = {{1, false}};  // as the first pulse ends: allowed
  EXPECT_EQ(timing_problem(setup, tm), "");
}

// ---------------------------------------------------------------------------------------
// StepTiming.

TEST(StepTiming, DefaultProfileIsOneTickPulseAndSetup) {
  const StepTiming t = StepTiming::from(default_settings().card);
  EXPECT_DOUBLE_EQ(t.tick_s, 5e-6);
  EXPECT_EQ(t.pulse_ticks, 1);
  EXPECT_EQ(t.dir_setup_ticks, 1);
  EXPECT_EQ(t.min_period_ticks, 2);
}

TEST(StepTiming, RoundsMicrosecondsUpToWholeTicks) {
  CardSettings c = default_settings().card;  // 5 us tick
  c.step_pulse_us = 7;
  c.dir_setup_us = 11;
  StepTiming t = StepTiming::from(c);
  EXPECT_EQ(t.pulse_ticks, 2);
  EXPECT_EQ(t.dir_setup_ticks, 3);
  EXPECT_EQ(t.min_period_ticks, 3);
  c.step_pulse_us = 10;  // exactly two ticks: no rounding up
  c.dir_setup_us = 15;
  t = StepTiming::from(c);
  EXPECT_EQ(t.pulse_ticks, 2);
  EXPECT_EQ(t.dir_setup_ticks, 3);
  c.step_pulse_us = 10.5;
  t = StepTiming::from(c);
  EXPECT_EQ(t.pulse_ticks, 3);
  EXPECT_EQ(t.min_period_ticks, 4);
}

TEST(StepTiming, PulseIsAtLeastOneTickAndSetupMayBeZero) {
  CardSettings c = default_settings().card;
  c.step_pulse_us = 0.1;
  c.dir_setup_us = 0;
  const StepTiming t = StepTiming::from(c);
  EXPECT_EQ(t.pulse_ticks, 1);
  EXPECT_EQ(t.dir_setup_ticks, 0);
  EXPECT_EQ(t.min_period_ticks, 2);
}

TEST(StepTiming, FollowsThePacerRate) {
  CardSettings c = default_settings().card;
  c.pacer_divisor = 40;  // 100 kHz, 10 us tick
  c.step_pulse_us = 7;
  c.dir_setup_us = 15;
  const StepTiming t = StepTiming::from(c);
  EXPECT_DOUBLE_EQ(t.tick_s, 1e-5);
  EXPECT_EQ(t.pulse_ticks, 1);
  EXPECT_EQ(t.dir_setup_ticks, 2);
}

// ---------------------------------------------------------------------------------------
// Single segments.

// Step and direction lines only; the other outputs have their own tests below.
Settings steps_only() {
  Settings s = default_settings();
  s.outputs.charge_pump_bit = -1;
  return s;
}

class StepGeneratorTest : public ::testing::Test {
 protected:
  Settings settings_ = steps_only();
  RecordingCard card_;

  double spu(int axis) const { return settings_.axes[axis].steps_per_unit; }
  Trace trace() const { return decode(card_.words(), PinMap::from(settings_.pins)); }
};

TEST_F(StepGeneratorTest, SingleAxisMoveEmitsExactlyTheRoundedStepCount) {
  StepGenerator gen(settings_, card_);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.5), 2.0));
  gen.flush();
  const std::int64_t n = target_steps(0.5, spu(0));  // 458.3662 -> 458
  EXPECT_EQ(n, 458);
  EXPECT_EQ(gen.position()[0], n);
  const Trace tr = trace();
  EXPECT_EQ(tr.axes[0].net, n);
  EXPECT_EQ(static_cast<std::int64_t>(tr.axes[0].pulses.size()), n);
  for (int i = 1; i < kAxisCount; ++i) EXPECT_TRUE(tr.axes[i].pulses.empty()) << "axis " << i;
  EXPECT_EQ(tr.stray_bits, 0u);
  EXPECT_EQ(timing_problem(tr.axes[0], gen.timing()), "");
}

TEST_F(StepGeneratorTest, NegativeMoveSetsTheDirectionLineHighBeforeTheFirstStep) {
  StepGenerator gen(settings_, card_);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0, -0.1), 1.0));
  gen.flush();
  const std::int64_t n = target_steps(-0.1, spu(1));
  EXPECT_EQ(gen.position()[1], n);
  const Trace tr = trace();
  const AxisTrace& y = tr.axes[1];
  EXPECT_EQ(y.net, n);
  ASSERT_EQ(y.dir_changes.size(), 1u);
  ASSERT_FALSE(y.pulses.empty());
  EXPECT_LE(y.dir_changes[0].tick + gen.timing().dir_setup_ticks, y.pulses[0].start);
  // Default pins: direction low = positive, so the Y dir bit (9) is high during the move.
  EXPECT_NE(card_.words()[y.pulses[0].start] & (1u << 9), 0u);
  EXPECT_EQ(timing_problem(y, gen.timing()), "");
}

TEST_F(StepGeneratorTest, EveryPulseIsExactlyPulseTicksWide) {
  settings_.card.step_pulse_us = 12;  // 3 ticks
  StepGenerator gen(settings_, card_);
  ASSERT_EQ(gen.timing().pulse_ticks, 3);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.2, 0.1, -0.05), 3.0, 40));
  gen.flush();
  const Trace tr = trace();
  for (int i = 0; i < 3; ++i) {
    ASSERT_FALSE(tr.axes[i].pulses.empty());
    for (const Pulse& p : tr.axes[i].pulses) ASSERT_EQ(p.end - p.start, 3) << "axis " << i;
  }
}

TEST_F(StepGeneratorTest, ConstantSpeedStepsAreWithinHalfATickOfTheIdealTimes) {
  // 400 X steps at a constant 3 in/s: step k is due when the axis reaches k - 1/2 steps.
  const double v = 3.0, L = 400 / spu(0);
  StepGenerator gen(settings_, card_);
  gen.segment(segment(Vec6::Zero(), vec(L), v, v, v, 14));
  gen.flush();
  const Trace tr = trace();
  const auto& pulses = tr.axes[0].pulses;
  ASSERT_EQ(pulses.size(), 400u);
  const double tick = gen.timing().tick_s;
  for (int k = 1; k <= 400; ++k) {
    const double ideal = (k - 0.5) / spu(0) / v / tick;  // in ticks
    ASSERT_LE(std::abs(static_cast<double>(pulses[k - 1].start) - ideal), 0.5 + 1e-6)
        << "step " << k << " ideal " << ideal;
  }
}

TEST_F(StepGeneratorTest, EveryAxisFollowsTheProfileOnADiagonalTrapezoid) {
  const Vec6 to = vec(0.3, -0.2, 0.05, 2.0, 0, -1.0);
  const PlannedSegment seg = rest_to_rest(Vec6::Zero(), to, 2.5, 20);
  StepGenerator gen(settings_, card_);
  gen.segment(seg);
  gen.flush();
  const Trace tr = trace();
  const double tick = gen.timing().tick_s;
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t n = std::abs(target_steps(to[i], spu(i)));
    const auto& pulses = tr.axes[i].pulses;
    ASSERT_EQ(static_cast<std::int64_t>(pulses.size()), n) << "axis " << i;
    for (std::int64_t k = 1; k <= n; ++k) {
      // The k-th step is due when the exact position crosses k - 1/2 steps.
      const double s =
          (static_cast<double>(k) - 0.5) / std::abs(to[i] * spu(i)) * seg.profile.length;
      const double ideal = seg.profile.time_at(s) / tick;
      // Negative axes wait one tick for the direction setup only on their first step.
      const double slack = (k == 1 && to[i] < 0) ? 1.0 : 0.0;
      ASSERT_LE(std::abs(static_cast<double>(pulses[k - 1].start) - ideal), 0.5 + slack + 1e-6)
          << "axis " << i << " step " << k;
    }
  }
}

TEST_F(StepGeneratorTest, WordsEmittedEqualTheSegmentDurationsInTicks) {
  const std::vector<PlannedSegment> segs = {
      rest_to_rest(Vec6::Zero(), vec(0.4, 0.3), 2.0),
      rest_to_rest(vec(0.4, 0.3), vec(0.4, 0.3, -0.2), 0.5),
      rest_to_rest(vec(0.4, 0.3, -0.2), vec(0.1, 0.3, -0.2, 5), 3.0, 30)};
  StepGenerator gen(settings_, card_);
  std::int64_t expected = 0;
  for (const PlannedSegment& s : segs) {
    gen.segment(s);
    expected += std::llround(s.profile.duration() / gen.timing().tick_s);
    EXPECT_EQ(gen.tick(), expected);
  }
  gen.flush();
  EXPECT_EQ(static_cast<std::int64_t>(card_.words().size()), expected);
  EXPECT_EQ(gen.tick(), expected);
  EXPECT_EQ(card_.ticks_played(), static_cast<std::uint64_t>(expected));
}

TEST_F(StepGeneratorTest, StepsNeverCloserThanMinPeriodWhenTheSegmentIsTooFast) {
  // 100 X steps in 50 ticks would need two steps per tick: they are delayed, not dropped.
  const double L = 100 / spu(0);
  const double v = L / (50 * 5e-6);
  StepGenerator gen(settings_, card_);
  gen.segment(segment(Vec6::Zero(), vec(L), v, v, v, 1e6));
  gen.flush();
  const Trace tr = trace();
  const auto& pulses = tr.axes[0].pulses;
  ASSERT_EQ(pulses.size(), 100u);
  EXPECT_EQ(gen.position()[0], 100);
  for (std::size_t j = 1; j < pulses.size(); ++j)
    ASSERT_EQ(pulses[j].start - pulses[j - 1].start, gen.timing().min_period_ticks) << j;
}

TEST_F(StepGeneratorTest, FastReversalSetsTheDirectionAsThePulseEnds) {
  // 20 X steps at 100 000 steps/s, then straight back: the direction waits for the last
  // pulse to end (tick 40) and the reverse step waits dir_setup after it.
  const double v = 100e3 / spu(0);
  const Vec6 p1 = vec(20 / spu(0)), p2 = vec(10 / spu(0));
  StepGenerator gen(settings_, card_);
  gen.segment(segment(Vec6::Zero(), p1, v, v, v, 1e6));
  gen.segment(segment(p1, p2, v, v, v, 1e6));
  gen.segment(rest_to_rest(p2, vec(8 / spu(0)), 0.5));  // ends at rest, lines idle
  gen.flush();
  const Trace tr = trace();
  const AxisTrace& x = tr.axes[0];
  ASSERT_EQ(x.pulses.size(), 32u);
  EXPECT_EQ(x.pulses[19].start, 39);
  EXPECT_EQ(x.pulses[19].end, 40);
  ASSERT_EQ(x.dir_changes.size(), 1u);
  EXPECT_EQ(x.dir_changes[0].tick, 40);
  EXPECT_EQ(x.pulses[20].start, 41);
  EXPECT_FALSE(x.pulses[20].positive);
  EXPECT_EQ(x.net, 8);
  EXPECT_EQ(timing_problem(x, gen.timing()), "");
}

TEST_F(StepGeneratorTest, DirectionSetupDelaysAnEarlyReverseStep) {
  // With a 4-tick setup, the reverse step due 1 tick after the segment start must wait.
  settings_.card.dir_setup_us = 20;
  const double v = 100e3 / spu(0);
  const Vec6 p1 = vec(20 / spu(0)), p2 = vec(10 / spu(0));
  StepGenerator gen(settings_, card_);
  ASSERT_EQ(gen.timing().dir_setup_ticks, 4);
  gen.segment(segment(Vec6::Zero(), p1, v, v, v, 1e6));
  gen.segment(segment(p1, p2, v, v, v, 1e6));
  gen.segment(rest_to_rest(p2, vec(8 / spu(0)), 0.5));  // ends at rest, lines idle
  gen.flush();
  const Trace tr = trace();
  const AxisTrace& x = tr.axes[0];
  ASSERT_EQ(x.pulses.size(), 32u);
  ASSERT_EQ(x.dir_changes.size(), 1u);
  EXPECT_EQ(x.dir_changes[0].tick, 40);
  EXPECT_EQ(x.pulses[20].start, 44);
  EXPECT_EQ(x.pulses[21].start, 46);  // then the min period: 2 ticks
  EXPECT_EQ(timing_problem(x, gen.timing()), "");
}

TEST_F(StepGeneratorTest, NextSegmentStartsWhereAnOverrunningSegmentEnded) {
  // X: 20 steps due within 10 ticks, delayed to ticks 0, 2, ..., 38. The following Y
  // segment (constant 100 000 steps/s) must start at tick 38, not at its planned tick 10.
  const double vx = (20 / spu(0)) / (10 * 5e-6), vy = 100e3 / spu(1);
  const Vec6 p1 = vec(20 / spu(0)), p2 = vec(20 / spu(0), 10 / spu(1));
  StepGenerator gen(settings_, card_);
  gen.segment(segment(Vec6::Zero(), p1, vx, vx, vx, 1e6));
  EXPECT_EQ(gen.tick(), 38);
  gen.segment(segment(p1, p2, vy, vy, vy, 1e6));
  EXPECT_EQ(gen.tick(), 38 + 20);
  gen.segment(rest_to_rest(p2, p2 + vec(0, 2 / spu(1)), 0.5));  // ends at rest, lines idle
  gen.flush();
  const Trace tr = trace();
  ASSERT_EQ(tr.axes[0].pulses.size(), 20u);
  ASSERT_EQ(tr.axes[1].pulses.size(), 12u);
  EXPECT_EQ(tr.axes[0].pulses.back().start, 38);
  EXPECT_EQ(tr.axes[1].pulses.front().start, 39);
  EXPECT_EQ(tr.axes[1].pulses[9].start, 57);
  EXPECT_EQ(timing_problem(tr.axes[0], gen.timing()), "");
  EXPECT_EQ(timing_problem(tr.axes[1], gen.timing()), "");
}

TEST_F(StepGeneratorTest, FlushPlaysTheLastPulse) {
  // Too fast a segment pushes its last step past the segment's end: only flush plays it.
  const double L = 20 / spu(0);
  const double v = L / (10 * 5e-6);
  StepGenerator gen(settings_, card_, 8);
  gen.segment(segment(Vec6::Zero(), vec(L), v, v, v, 1e6));
  const std::int64_t before = gen.tick();
  gen.flush();
  const Trace tr = trace();
  ASSERT_EQ(tr.axes[0].pulses.size(), 20u);
  const Pulse& last = tr.axes[0].pulses.back();
  EXPECT_EQ(last.start, 38);     // delayed to ticks 0, 2, ..., 38
  EXPECT_EQ(before, 38);         // the segment ends where its last step starts
  EXPECT_EQ(card_.writes(), 5);  // four full blocks of 8, then the rest at the flush
  EXPECT_EQ(gen.tick(), static_cast<std::int64_t>(card_.words().size()));
  // Every word the generator produced reached the card.
  EXPECT_GE(static_cast<std::int64_t>(card_.words().size()), last.start + gen.timing().pulse_ticks);
}

TEST_F(StepGeneratorTest, FlushEndsWithEveryStepLineIdle) {
  const double rate = 100e3;  // steps/s: one step every 2 ticks
  const double v = rate / spu(0);
  StepGenerator gen(settings_, card_);
  gen.segment(segment(Vec6::Zero(), vec(20 / spu(0)), v, v, v, 1e6));
  gen.flush();
  const Trace tr = trace();
  ASSERT_EQ(tr.axes[0].pulses.size(), 20u);
  EXPECT_EQ(tr.axes[0].pulses.back().start, 39);
  EXPECT_EQ(card_.words().size(), 41u);
  EXPECT_EQ(card_.words().back(), PinMap::from(settings_.pins).idle_word());
  EXPECT_EQ(timing_problem(tr.axes[0], gen.timing()), "");
}

TEST_F(StepGeneratorTest, FlushWithNothingPendingWritesNothingMore) {
  StepGenerator gen(settings_, card_);
  gen.flush();
  EXPECT_TRUE(card_.words().empty());
  EXPECT_EQ(card_.writes(), 0);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.05), 1.0));
  gen.flush();
  const std::size_t n = card_.words().size();
  const int writes = card_.writes();
  gen.flush();
  EXPECT_EQ(card_.words().size(), n);
  EXPECT_EQ(card_.writes(), writes);
}

TEST_F(StepGeneratorTest, WordsReachTheCardInBlocksAndOnlyWhenFull) {
  StepGenerator gen(settings_, card_, 1000);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.05), 1.0));
  const std::int64_t ticks = gen.tick();
  ASSERT_GT(ticks, 3000);
  EXPECT_EQ(static_cast<std::int64_t>(card_.words().size()), ticks / 1000 * 1000);
  EXPECT_EQ(card_.writes(), ticks / 1000);
  gen.flush();
  EXPECT_EQ(static_cast<std::int64_t>(card_.words().size()), ticks);
}

TEST_F(StepGeneratorTest, BlockSizeDoesNotChangeTheWords) {
  const std::vector<PlannedSegment> segs = random_segments(7, 8, settings_);
  auto run = [&](std::size_t block) {
    RecordingCard card;
    StepGenerator gen(settings_, card, block);
    for (const PlannedSegment& s : segs) gen.segment(s);
    gen.flush();
    return card.words();
  };
  const std::vector<std::uint32_t> reference = run(4096);
  EXPECT_TRUE(run(1) == reference);
  EXPECT_TRUE(run(7) == reference);
  EXPECT_TRUE(run(100000) == reference);
}

TEST_F(StepGeneratorTest, ZeroLengthSegmentEmitsNothing) {
  StepGenerator gen(settings_, card_);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.02), 1.0));
  const std::int64_t ticks = gen.tick();
  gen.segment(rest_to_rest(vec(0.02), vec(0.02), 1.0));
  EXPECT_EQ(gen.tick(), ticks);
  gen.flush();
  EXPECT_EQ(static_cast<std::int64_t>(card_.words().size()), ticks);
  EXPECT_EQ(gen.position()[0], target_steps(0.02, spu(0)));
  EXPECT_EQ(trace().axes[0].net, target_steps(0.02, spu(0)));
}

TEST_F(StepGeneratorTest, SubStepMoveEmitsNothing) {
  StepGenerator gen(settings_, card_);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.4 / spu(0)), 1.0));  // rounds to 0 steps
  gen.flush();
  EXPECT_EQ(gen.position()[0], 0);
  const Trace tr = trace();
  EXPECT_TRUE(tr.axes[0].pulses.empty());
  EXPECT_TRUE(tr.axes[0].dir_changes.empty());
}

// ---------------------------------------------------------------------------------------
// Extreme durations and distances (issue 22: `PAUSE 1e20` overflowed std::llround and the
// card played garbled steps with status "done").

PlannedSegment dwell_at(const Vec6& at, double seconds) {
  PlannedSegment d;
  d.from = d.to = at;
  d.dwell_s = seconds;
  d.loc = SourceLoc{std::make_shared<const std::string>("part.sbp"), 2, 1};
  return d;
}

std::string fault_of(StepGenerator& gen, const PlannedSegment& s) {
  try {
    gen.segment(s);
  } catch (const GantryError& e) {
    return format(e.diagnostic());
  }
  return "";
}

TEST_F(StepGeneratorTest, ADwellBeyondTheTickRangeIsALocatedFaultAndNothingGarbledIsSent) {
  for (const double seconds : {1e20, 1e14 * 1e3, std::nan(""), HUGE_VAL}) {
    RecordingCard card;
    StepGenerator gen(settings_, card);
    gen.segment(rest_to_rest(Vec6::Zero(), vec(0.5), 2.0));
    const std::int64_t before = gen.tick();
    const std::string fault = fault_of(gen, dwell_at(vec(0.5), seconds));
    EXPECT_NE(fault.find("part.sbp:2:1: error: this segment needs"), std::string::npos)
        << seconds << ": " << fault;
    EXPECT_NE(fault.find("nothing of it was sent"), std::string::npos) << fault;
    EXPECT_EQ(gen.tick(), before) << seconds;  // the clock did not wrap
    // What was sent before it is whole and exact: the next move goes on from there.
    gen.segment(rest_to_rest(vec(0.5), vec(1.0), 2.0));
    gen.flush();
    const Trace tr = decode(card.words(), PinMap::from(settings_.pins));
    EXPECT_EQ(tr.axes[0].net, target_steps(1.0, spu(0))) << seconds;
    EXPECT_EQ(timing_problem(tr.axes[0], gen.timing()), "") << seconds;
  }
}

TEST_F(StepGeneratorTest, ATargetBeyondTheStepRangeIsALocatedFault) {
  StepGenerator gen(settings_, card_);
  PlannedSegment s = rest_to_rest(Vec6::Zero(), vec(0.5), 2.0);
  s.to[1] = 1e300;  // a Y the profile's length does not know about
  s.loc = SourceLoc{std::make_shared<const std::string>("part.sbp"), 2, 1};
  EXPECT_NE(fault_of(gen, s).find("steps, beyond what the step generator can place"),
            std::string::npos);
  EXPECT_EQ(gen.tick(), 0);
  EXPECT_EQ(gen.position()[1], 0);
}

// The longest dwell a profile allows (30 days) and far beyond it are placed on the tick clock
// without overflow: a stop cuts them at the tick asked for, and the remaining time is exact.
TEST_F(StepGeneratorTest, AnExtremelyLongDwellIsCutByAStopAtTheTickAskedFor) {
  for (const double seconds : {30 * 86400.0, 1e9}) {
    RecordingCard card;
    StepGenerator gen(settings_, card, 64);
    gen.segment(rest_to_rest(Vec6::Zero(), vec(0.5), 2.0));
    const std::int64_t t0 = gen.tick();
    std::atomic<std::int64_t> stop{t0 + 1000};
    const std::optional<double> cut = gen.segment_until(dwell_at(vec(0.5), seconds), {&stop});
    ASSERT_TRUE(cut.has_value()) << seconds;
    EXPECT_DOUBLE_EQ(*cut, 1000 * gen.timing().tick_s);
    EXPECT_EQ(gen.tick(), t0 + 1000);
    gen.flush();
    EXPECT_EQ(static_cast<std::int64_t>(card.words().size()), t0 + 1000);
  }
}

// ---------------------------------------------------------------------------------------
// Pin options.

TEST_F(StepGeneratorTest, InvertDirDrivesTheDirectionLineTheOtherWay) {
  settings_.pins[0].invert_dir = true;
  StepGenerator gen(settings_, card_);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.02), 1.0));  // positive: dir bit 8 high
  gen.segment(rest_to_rest(vec(0.02), vec(-0.01), 1.0));    // negative: dir bit 8 low
  gen.flush();
  const std::vector<std::uint32_t>& w = card_.words();
  EXPECT_NE(w.front() & (1u << 8), 0u);  // rests high: positive
  const Trace tr = trace();
  const AxisTrace& x = tr.axes[0];
  EXPECT_EQ(x.net, target_steps(-0.01, spu(0)));
  const std::int64_t up = target_steps(0.02, spu(0));
  ASSERT_EQ(static_cast<std::int64_t>(x.pulses.size()), up + up - target_steps(-0.01, spu(0)));
  for (std::int64_t j = 0; j < static_cast<std::int64_t>(x.pulses.size()); ++j) {
    const bool high = (w[x.pulses[j].start] & (1u << 8)) != 0;
    ASSERT_EQ(high, j < up) << "step " << j;
  }
  ASSERT_EQ(x.dir_changes.size(), 1u);
  EXPECT_EQ(timing_problem(x, gen.timing()), "");
}

TEST_F(StepGeneratorTest, ActiveLowStepsIdleHighAndPulseLow) {
  settings_.pins[2].step_active_low = true;
  StepGenerator gen(settings_, card_);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0, 0, 0.01), 0.5));
  gen.flush();
  const std::vector<std::uint32_t>& w = card_.words();
  const std::uint32_t z_step = 1u << 2;
  const std::int64_t n = target_steps(0.01, spu(2));
  ASSERT_GT(n, 0);
  EXPECT_NE(w.front() & z_step, 0u);  // idle high
  EXPECT_NE(w.back() & z_step, 0u);
  std::int64_t low_words = 0;
  for (std::uint32_t word : w) low_words += (word & z_step) == 0;
  EXPECT_EQ(low_words, n * gen.timing().pulse_ticks);
  const Trace tr = trace();
  EXPECT_EQ(tr.axes[2].net, n);
  EXPECT_EQ(timing_problem(tr.axes[2], gen.timing()), "");
}

TEST_F(StepGeneratorTest, RemappedPinsUseOnlyTheirBits) {
  settings_.pins[0].step_bit = 20;
  settings_.pins[0].dir_bit = 31;
  StepGenerator gen(settings_, card_);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(-0.01), 1.0));
  gen.flush();
  std::uint32_t seen = 0;
  for (std::uint32_t w : card_.words()) seen |= w;
  EXPECT_EQ(seen, (1u << 20) | (1u << 31));
  EXPECT_EQ(trace().axes[0].net, target_steps(-0.01, spu(0)));
}

// ---------------------------------------------------------------------------------------
// An axis moving on its own (MI) beside the path.

PlannedSegment independent(int axis, double speed, double accel, double frequency = 0,
                           double travel = 0) {
  PlannedSegment s;
  s.independent = IndependentMotion{axis, speed, accel, frequency, travel};
  return s;
}

PlannedSegment wait_for(double seconds) {
  PlannedSegment s;
  s.dwell_s = seconds;
  return s;
}

TEST_F(StepGeneratorTest, AnOscillationFollowsItsCosineAndEndsBackWhereItStarted) {
  // Z out 0.1 in and back at 2.5 Hz: a 1 s dwell is 2.5 cycles, and the flush finishes the
  // third. Crossing k - 1/2 of D steps: out at (2 pi c + th_k) / w, back at
  // (2 pi (c + 1) - th_k) / w, th_k = acos(1 - (2k - 1) / D).
  StepGenerator gen(settings_, card_);
  gen.segment(independent(2, 0, 0, 2.5, 0.1));
  gen.segment(wait_for(1.0));
  gen.flush();
  const Trace tr = trace();
  const AxisTrace& z = tr.axes[2];
  const double d = 0.1 * spu(2);
  const int n = 102;  // the half steps below D = 101.86
  ASSERT_EQ(z.pulses.size(), 6u * n);
  EXPECT_EQ(z.net, 0);
  EXPECT_EQ(gen.position()[2], 0);
  EXPECT_EQ(timing_problem(z, gen.timing()), "");
  const double w = 2 * M_PI * 2.5 * gen.timing().tick_s;
  for (int c = 0; c < 3; ++c)
    for (int k = 1; k <= n; ++k) {
      const double th = std::acos(1 - (2.0 * k - 1) / d);
      const Pulse& out = z.pulses[static_cast<std::size_t>(c * 2 * n + k - 1)];
      const Pulse& back = z.pulses[static_cast<std::size_t>(c * 2 * n + 2 * n - k)];
      ASSERT_TRUE(out.positive && !back.positive) << "cycle " << c << " step " << k;
      ASSERT_LE(std::abs(static_cast<double>(out.start) - (2 * M_PI * c + th) / w), 0.5 + 1e-6)
          << "cycle " << c << " step " << k;
      ASSERT_LE(std::abs(static_cast<double>(back.start) - (2 * M_PI * (c + 1) - th) / w),
                0.5 + 1e-6)
          << "cycle " << c << " step " << k;
    }
  // The words go on past the dwell (1 s) to the third cycle's last step (before 1.2 s).
  EXPECT_EQ(static_cast<std::int64_t>(card_.words().size()), z.pulses.back().end + 1);
}

TEST_F(StepGeneratorTest, ATurningAxisRampsUpAndDownAtItsAccelerationAndStopsWhereThatLeavesIt) {
  // B at 45 deg/s and 360 deg/s^2: up in 0.125 s; told to stop at 1 s, it slows for another
  // 0.125 s, having turned 2.8125 + 39.375 + 2.8125 = 45 degrees.
  StepGenerator gen(settings_, card_);
  gen.segment(independent(4, 45, 360));
  gen.segment(wait_for(1.0));
  gen.flush();
  const double tick = gen.timing().tick_s;
  const double v = 45 * spu(4) * tick, a = 360 * spu(4) * tick * tick;  // steps, ticks
  const double t1 = v / a, u1 = v * v / (2 * a), ts = 1.0 / tick, us = u1 + v * (ts - t1);
  const double ue = us + u1;
  const auto n = static_cast<std::int64_t>(std::floor(ue + 0.5));
  EXPECT_EQ(n, std::llround(45 * spu(4)));
  const Trace tr = trace();
  const AxisTrace& b = tr.axes[4];
  ASSERT_EQ(b.net, n);
  EXPECT_EQ(gen.position()[4], n);
  EXPECT_EQ(timing_problem(b, gen.timing()), "");
  for (std::int64_t k = 1; k <= n; ++k) {
    const double u = static_cast<double>(k) - 0.5;
    const double ideal = u <= u1   ? std::sqrt(2 * u / a)
                         : u <= us ? t1 + (u - u1) / v
                                   : ts + (v - std::sqrt(v * v - 2 * a * (u - us))) / a;
    ASSERT_LE(
        std::abs(static_cast<double>(b.pulses[static_cast<std::size_t>(k - 1)].start) - ideal),
        0.5 + 1e-6)
        << "step " << k;
  }
}

TEST_F(StepGeneratorTest, ThePathPlaysTheSameStepsWithAnAxisTurningBesideIt) {
  // The second segment asks B for 7 degrees: while B turns on its own the path leaves it be.
  const std::vector<PlannedSegment> path = {
      rest_to_rest(Vec6::Zero(), vec(0.4, 0.3), 2.0),
      rest_to_rest(vec(0.4, 0.3), vec(0.1, 0.3, -0.2, 0, 7), 1.5)};
  StepGenerator alone_gen(settings_, card_);
  for (const PlannedSegment& s : path) alone_gen.segment(s);
  alone_gen.flush();
  const Trace alone = trace();
  RecordingCard card;
  StepGenerator gen(settings_, card);
  gen.segment(independent(4, -30, 360));
  for (const PlannedSegment& s : path) gen.segment(s);
  gen.flush();
  const Trace beside = decode(card.words(), PinMap::from(settings_.pins));
  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(beside.axes[i].pulses.size(), alone.axes[i].pulses.size()) << "axis " << i;
    for (std::size_t j = 0; j < alone.axes[i].pulses.size(); ++j)
      ASSERT_EQ(beside.axes[i].pulses[j].start, alone.axes[i].pulses[j].start) << "axis " << i;
    EXPECT_EQ(timing_problem(beside.axes[i], gen.timing()), "") << "axis " << i;
  }
  EXPECT_EQ(alone.axes[4].net, target_steps(7, spu(4)));
  EXPECT_LT(beside.axes[4].net, -target_steps(7, spu(4)));  // turning backwards all along
  EXPECT_EQ(beside.axes[4].net, gen.position()[4]);
  EXPECT_EQ(timing_problem(beside.axes[4], gen.timing()), "");
}

// ---------------------------------------------------------------------------------------
// Random sequences: exact counts and every timing rule.

struct SequenceCase {
  std::uint32_t seed;
  double pulse_us, dir_setup_us;
  bool invert_dir, active_low;
};

void PrintTo(const SequenceCase& c, std::ostream* os) {
  *os << "seed " << c.seed << " pulse " << c.pulse_us << " us setup " << c.dir_setup_us << " us"
      << (c.invert_dir ? " invert_dir" : "") << (c.active_low ? " active_low" : "");
}

// One run of a random sequence through the generator, decoded.
struct SequenceRun {
  Settings settings = default_settings();
  std::vector<PlannedSegment> segments;
  std::vector<Steps6> position_after;  // generator position after each segment
  std::int64_t duration_ticks = 0;     // sum of the rounded segment durations
  StepTiming timing;
  Steps6 final{};
  std::int64_t final_tick = 0;
  std::size_t words = 0;
  Trace trace;
};

SequenceRun run_sequence(const SequenceCase& c) {
  SequenceRun r;
  r.settings.outputs.charge_pump_bit = -1;  // step and direction lines only
  r.settings.card.step_pulse_us = c.pulse_us;
  r.settings.card.dir_setup_us = c.dir_setup_us;
  for (int i = 0; i < kAxisCount; i += 2) r.settings.pins[i].invert_dir = c.invert_dir;
  for (int i = 1; i < kAxisCount; i += 2) r.settings.pins[i].step_active_low = c.active_low;
  r.segments = random_segments(c.seed, 40, r.settings);
  RecordingCard card;
  StepGenerator gen(r.settings, card);
  for (const PlannedSegment& s : r.segments) {
    gen.segment(s);
    r.position_after.push_back(gen.position());
    r.duration_ticks += std::llround(s.profile.duration() / gen.timing().tick_s);
  }
  gen.flush();
  r.timing = gen.timing();
  r.final = gen.position();
  r.final_tick = gen.tick();
  r.words = card.words().size();
  r.trace = decode(card.words(), PinMap::from(r.settings.pins));
  return r;
}

class RandomSequence : public ::testing::TestWithParam<SequenceCase> {
 protected:
  // Each case runs once; its tests share the result.
  const SequenceRun& run() const {
    static std::map<std::uint32_t, SequenceRun> cache;
    const SequenceCase& c = GetParam();
    auto it = cache.find(c.seed);
    if (it == cache.end()) it = cache.emplace(c.seed, run_sequence(c)).first;
    return it->second;
  }
  double spu(int axis) const { return run().settings.axes[axis].steps_per_unit; }
};

TEST_P(RandomSequence, PositionAfterEverySegmentIsTheRoundedTarget) {
  const SequenceRun& r = run();
  for (std::size_t n = 0; n < r.segments.size(); ++n)
    for (int i = 0; i < kAxisCount; ++i)
      ASSERT_EQ(r.position_after[n][i], target_steps(r.segments[n].to[i], spu(i)))
          << "segment " << n << " axis " << i;
}

TEST_P(RandomSequence, DecodedNetStepsReachTheFinalTarget) {
  const SequenceRun& r = run();
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t target = target_steps(r.segments.back().to[i], spu(i));
    EXPECT_EQ(r.trace.axes[i].net, target) << "axis " << i;
    EXPECT_EQ(r.final[i], target) << "axis " << i;
  }
}

TEST_P(RandomSequence, EveryStepHasTheDirectionOfItsSegment) {
  // Exact per-segment counts: the decoded steps, grouped by direction, are the segments'
  // step deltas in order (consecutive segments in one direction merge).
  const SequenceRun& r = run();
  for (int i = 0; i < kAxisCount; ++i) {
    Runs expected;
    std::int64_t prev = 0;
    for (const PlannedSegment& s : r.segments) {
      const std::int64_t t = target_steps(s.to[i], spu(i));
      append_run(expected, t > prev, std::abs(t - prev));
      prev = t;
    }
    EXPECT_EQ(decoded_runs(r.trace.axes[i]), expected) << "axis " << i;
  }
}

TEST_P(RandomSequence, EveryAxisObeysPulseWidthDirSetupAndMinPeriod) {
  const SequenceRun& r = run();
  for (int i = 0; i < kAxisCount; ++i)
    EXPECT_EQ(timing_problem(r.trace.axes[i], r.timing), "") << "axis " << i;
}

TEST_P(RandomSequence, OnlyStepAndDirBitsAreUsed) {
  EXPECT_EQ(run().trace.stray_bits, 0u);
}

TEST_P(RandomSequence, WordCountTracksTheSegmentDurations) {
  const SequenceRun& r = run();
  EXPECT_EQ(r.final_tick, static_cast<std::int64_t>(r.words));
  // Delays for setup and step rate may stretch a segment, never shrink it: at most to its
  // busiest axis's steps at the minimum period, plus a direction setup.
  std::int64_t bound = 0;
  Steps6 prev{};
  for (std::size_t n = 0; n < r.segments.size(); ++n) {
    std::int64_t most = 0;
    for (int i = 0; i < kAxisCount; ++i)
      most = std::max(most, std::abs(r.position_after[n][i] - prev[i]));
    prev = r.position_after[n];
    const std::int64_t ticks = std::llround(r.segments[n].profile.duration() / r.timing.tick_s);
    bound += std::max(ticks, most * r.timing.min_period_ticks) + r.timing.dir_setup_ticks +
             r.timing.min_period_ticks;
  }
  EXPECT_GE(r.final_tick, r.duration_ticks);
  EXPECT_LE(r.final_tick, bound);
}

TEST_P(RandomSequence, SequenceHasReversalsShortAndSlowSegments) {
  // Guards the test data: the properties above must be checked on the hard cases.
  const SequenceRun& r = run();
  int reversals = 0, short_segments = 0, slow_segments = 0, abrupt = 0;
  Steps6 prev{};
  Vec6 prev_delta = Vec6::Zero();
  for (std::size_t n = 0; n < r.segments.size(); ++n) {
    const PlannedSegment& s = r.segments[n];
    const Vec6 d = s.to - s.from;
    std::int64_t most = 0;
    for (int i = 0; i < kAxisCount; ++i) {
      reversals += d[i] * prev_delta[i] < 0;
      most = std::max(most, std::abs(r.position_after[n][i] - prev[i]));
    }
    short_segments += most > 0 && most <= 3;
    slow_segments += static_cast<double>(most) / s.profile.duration() < 100;  // steps/s
    abrupt += s.profile.v_entry > 0;
    prev = r.position_after[n];
    prev_delta = d;
  }
  EXPECT_GE(reversals, 20);
  EXPECT_GE(short_segments, 3);
  EXPECT_GE(slow_segments, 3);
  EXPECT_GE(abrupt, 5);
}

INSTANTIATE_TEST_SUITE_P(
    Seeds, RandomSequence,
    ::testing::Values(SequenceCase{1, 5, 5, false, false}, SequenceCase{2, 5, 5, false, false},
                      SequenceCase{3, 5, 0, false, false}, SequenceCase{4, 10, 15, false, false},
                      SequenceCase{5, 7, 11, true, true}, SequenceCase{6, 5, 5, true, false}));

// ---------------------------------------------------------------------------------------
// The other outputs, and faults.

TEST(ChargePump, SquareWaveAtItsRateUnbrokenAcrossBlocksWhilePulsesFlow) {
  Settings s = default_settings();  // bit 16 at 10 kHz on the 200 kHz pacer: 10 ticks each
  RecordingCard card;
  StepGenerator gen(s, card, /*block_words=*/7);  // runs and blocks cut across the wave
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.05), 1.0));
  gen.flush();
  const auto& w = card.words();
  ASSERT_GT(w.size(), 1000u);
  for (std::size_t t = 0; t < w.size(); ++t)
    ASSERT_EQ((w[t] >> 16) & 1u, (t / 10) & 1u) << "tick " << t;
  EXPECT_EQ(decode(w, PinMap::from(s.pins)).axes[0].net,
            target_steps(0.05, s.axes[0].steps_per_unit));
}

// The spindle speed's square wave beside the pump's, each by the tick's own number, across
// runs cut by pulses and by small blocks: the writer steps from flip to flip (issue 27).
TEST(ChargePump, SpindleSpeedWaveUnbrokenBesideThePumpAcrossBlocks) {
  Settings s = default_settings();
  s.spindle.pwm_bit = 30;  // 1 kHz on the 200 kHz pacer: a 200-tick period
  RecordingCard card;
  StepGenerator gen(s, card, /*block_words=*/37);
  gen.set_spindle_speed(0.3 * s.spindle.max_rpm);  // high for the first 60 ticks of each
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.05), 1.0));
  gen.flush();
  const auto& w = card.words();
  ASSERT_GT(w.size(), 1000u);
  for (std::size_t t = 0; t < w.size(); ++t) {
    ASSERT_EQ((w[t] >> 16) & 1u, (t / 10) & 1u) << "tick " << t;
    ASSERT_EQ((w[t] >> 30) & 1u, t % 200 < 60 ? 1u : 0u) << "tick " << t;
  }
}

TEST(SpindleOutput, FollowsSetSpindleFromTheNextWord) {
  Settings s = steps_only();
  RecordingCard card;
  StepGenerator gen(s, card);
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.01), 1.0));
  gen.set_spindle(true);
  gen.segment(rest_to_rest(vec(0.01), vec(0.02), 1.0));
  gen.set_spindle(false);
  gen.segment(rest_to_rest(vec(0.02), vec(0.03), 1.0));
  gen.flush();
  std::vector<int> changes;  // ticks where bit 17 changes
  for (std::size_t t = 1; t < card.words().size(); ++t)
    if (((card.words()[t] ^ card.words()[t - 1]) >> 17) & 1u)
      changes.push_back(static_cast<int>(t));
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_EQ((card.words()[0] >> 17) & 1u, 0u);
}

TEST(AuxOutputs, OutputSwitchesSetTheirBitsAndUnwiredOnesSaySo) {
  Settings s = steps_only();  // outputs 1-12 on bits 18-29
  RecordingCard card;
  StepGenerator gen(s, card);
  EXPECT_TRUE(gen.set_output(3, true));  // bit 20
  EXPECT_FALSE(gen.set_output(13, true));
  EXPECT_FALSE(gen.set_output(0, true));
  gen.segment(rest_to_rest(Vec6::Zero(), vec(0.01), 1.0));
  EXPECT_TRUE(gen.set_output(3, false));
  gen.segment(rest_to_rest(vec(0.01), vec(0.02), 1.0));
  gen.flush();
  const auto& w = card.words();
  EXPECT_EQ(w.front() & (0xFFFu << 18), 1u << 20);
  EXPECT_EQ(w.back() & (0xFFFu << 18), 0u);
}

// A card that plays words until a given tick, then reports a fault and plays no more.
class FaultAtCard : public RecordingCard {
 public:
  explicit FaultAtCard(std::uint64_t at) : at_(at) {}
  void write(std::span<const std::uint32_t> words) override {
    if (fault_ != CardFault::None) return;
    const std::uint64_t room = at_ - played();
    RecordingCard::write(words.first(std::min<std::uint64_t>(room, words.size())));
    if (played() >= at_) fault_ = CardFault::EStop;
  }
  std::uint64_t ticks_played() const override { return played(); }
  CardFault fault() const override { return fault_; }

 private:
  std::uint64_t played() const { return RecordingCard::ticks_played(); }
  std::uint64_t at_;
  CardFault fault_ = CardFault::None;
};

TEST(CardFaults, AFaultStopsGenerationAndThePositionIsThePulsesPlayed) {
  Settings s = steps_only();
  for (std::uint64_t at : {1000u, 4096u, 4097u, 33333u}) {
    SCOPED_TRACE(at);
    FaultAtCard card(at);
    StepGenerator gen(s, card, 512);
    PlannedSegment seg = rest_to_rest(Vec6::Zero(), vec(0.5, -0.25, 0.1), 2.0);
    seg.loc = SourceLoc{std::make_shared<const std::string>("part.sbp"), 7, 1};
    std::string message;
    try {
      gen.segment(seg);
      gen.flush();
    } catch (const GantryError& e) {
      message = format(e.diagnostic());
    }
    EXPECT_NE(message.find("part.sbp:7:1: error: E-stop: the card stopped at"), std::string::npos)
        << message;
    EXPECT_TRUE(gen.faulted());
    EXPECT_EQ(card.words().size(), at);
    const Trace tr = decode(card.words(), PinMap::from(s.pins));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(gen.played_position()[i], tr.axes[i].net) << i;
    EXPECT_LT(std::abs(gen.played_position()[0]), target_steps(0.5, s.axes[0].steps_per_unit));
    gen.segment(seg);  // nothing more reaches the card, and no second error
    gen.flush();
    EXPECT_EQ(card.words().size(), at);
  }
}

}  // namespace
}  // namespace gantry
