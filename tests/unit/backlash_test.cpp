// Backlash compensation on the simulated card: the extra steps at each reversal counted on
// the pin trace, the position reported without them, their timing within the axis's limits.
#include <gtest/gtest.h>
#include <unistd.h>

#include "pin_trace.hpp"
#include "segment_builders.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "gantry/settings/settings.hpp"
#include "gantry/step/step_generator.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::channel_pulses;
using test::direction_runs;
using test::read_trace;
using test::segment;
using test::vec;
namespace fs = std::filesystem;

// X with 0.01 in of backlash: 916.7324 steps/in, 9 steps of slack.
Settings backlash_x() {
  Settings s = default_settings();
  s.outputs.charge_pump_bit = -1;
  s.axes[0].backlash = 0.01;
  return s;
}

std::string trace_path(const char* name) {
  return (fs::temp_directory_path() / (std::string("gantry_backlash_") + name + "_" +
                                       std::to_string(getpid()) + ".trace"))
      .string();
}

std::int64_t steps(double units, const Settings& s, int axis = 0) {
  return std::llround(units * s.axes[axis].steps_per_unit);
}

// X out to 0.5, back to 0.2, out to 0.6: two reversals, each taking up 9 steps of slack
// first; the first move sets the slack's side and takes none.
TEST(Backlash, EachReversalAddsTheSlackOnThePinTraceAndTheReportedPositionIgnoresIt) {
  const Settings s = backlash_x();
  const std::string path = trace_path("reversals");
  Steps6 reported{}, played{};
  std::uint64_t violations = 0;
  Steps6 card_steps{};
  {
    SimCard card(s, false, {}, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    gen.segment(segment(vec(0), vec(0.5), 0, 2, 0, 14));
    gen.segment(segment(vec(0.5), vec(0.2), 0, 2, 0, 14));
    gen.segment(segment(vec(0.2), vec(0.6), 0, 2, 0, 14));
    gen.flush();
    reported = gen.position();
    played = gen.played_position();
    violations = card.timing_violations();
    card_steps = card.steps();
    EXPECT_EQ(gen.timing().min_period_ticks, 2);
  }
  const auto trace = read_trace(path);
  fs::remove(path);
  const std::int64_t slack = steps(0.01, s);
  ASSERT_EQ(slack, 9);
  const std::int64_t a = steps(0.5, s), b = steps(0.2, s), c = steps(0.6, s);
  const auto runs = direction_runs(channel_pulses(trace, 0, 8));
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0], std::make_pair(true, static_cast<int>(a)));              // no takeup yet
  EXPECT_EQ(runs[1], std::make_pair(false, static_cast<int>(a - b + slack)));  // + the slack
  EXPECT_EQ(runs[2], std::make_pair(true, static_cast<int>(c - b + slack)));
  // The position reported counts the load's steps only; the card's decoded count is the
  // motor's, which ends where the load does (both last moved towards plus).
  EXPECT_EQ(reported[0], c);
  EXPECT_EQ(played[0], c);
  EXPECT_EQ(card_steps[0], c);
  EXPECT_EQ(violations, 0u);
}

// The takeup steps come first: while the motor turns through the slack the position the
// generator reports for those ticks stays where the load stopped.
TEST(Backlash, TheLoadMovesOnlyOnceTheSlackIsTaken) {
  const Settings s = backlash_x();
  const std::string path = trace_path("first");
  std::vector<std::int64_t> reported;  // X reported at each tick
  {
    SimCard card(s, false, {}, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    gen.segment(segment(vec(0), vec(0.1), 0, 2, 0, 14));
    gen.segment(segment(vec(0.1), vec(0.05), 0, 2, 0, 14));
    gen.flush();
    for (std::int64_t t = 0; t <= gen.tick(); ++t)
      reported.push_back((*gen.position_at(static_cast<std::uint64_t>(t)))[0]);
  }  // the trace is complete once the card is gone
  std::vector<std::int64_t> reported_after;  // X reported just after each reverse pulse
  for (const auto& p : channel_pulses(read_trace(path), 0, 8))
    if (!p.positive) reported_after.push_back(reported.at(static_cast<std::size_t>(p.tick) + 1));
  fs::remove(path);
  const std::int64_t out = steps(0.1, s), back = steps(0.05, s);
  ASSERT_EQ(reported_after.size(), static_cast<std::size_t>(out - back + 9));
  for (int k = 0; k < 9; ++k) EXPECT_EQ(reported_after[k], out) << "takeup step " << k;
  EXPECT_EQ(reported_after[9], out - 1);
  EXPECT_EQ(reported_after.back(), back);
}

// The slack is taken at the axis's corner jump speed on top of the load's, so the motor is
// never faster than the load plus that: the move back starts from rest at 14 in/s^2, so
// after t seconds the takeup's steps are 1 / (corner jump x max_speed + 14 t) / steps per
// unit apart at least (less a tick of rounding), and at most the takeup's own period; every
// pulse keeps the card's width, setup and period rules.
TEST(Backlash, TakeupStepsKeepTheAxisRateAndTheCardTiming) {
  Settings s = backlash_x();
  s.axes[0].backlash = 0.05;  // 46 steps
  const std::string path = trace_path("rate");
  std::uint64_t violations = 0;
  {
    SimCard card(s, false, {}, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    gen.segment(segment(vec(0), vec(0.2), 0, 2, 0, 14));
    gen.segment(segment(vec(0.2), vec(0), 0, 2, 0, 14));
    gen.flush();
    violations = card.timing_violations();
  }
  const auto pulses = channel_pulses(read_trace(path), 0, 8);
  fs::remove(path);
  const std::int64_t slack = steps(0.05, s);
  ASSERT_EQ(slack, 46);
  std::size_t first_back = 0;
  while (pulses[first_back].positive) ++first_back;
  ASSERT_EQ(pulses.size() - first_back, static_cast<std::size_t>(steps(0.2, s) + slack));
  const double step_rate = s.planner.corner_jump * s.axes[0].max_speed * s.axes[0].steps_per_unit;
  const double pacer = s.card.pacer_hz(), spu = s.axes[0].steps_per_unit;
  const double gap_ticks = pacer / step_rate;  // 248 ticks: 807 steps/s
  for (std::size_t k = first_back + 1; k < first_back + static_cast<std::size_t>(slack); ++k) {
    const double gap = static_cast<double>(pulses[k].tick - pulses[k - 1].tick);
    const double t = static_cast<double>(pulses[k].tick - pulses[first_back].tick) / pacer +
                     gap_ticks / pacer;  // at most this long since the move began
    EXPECT_GE(gap, pacer / (step_rate + 14 * t * spu) - 1) << "pulse " << k - first_back;
    EXPECT_LE(gap, gap_ticks + 1) << "pulse " << k - first_back;
  }
  EXPECT_EQ(violations, 0u);
}

// A hold that cuts the reversing move during its takeup: the steps of slack not played are
// taken when the move resumes, and none twice.
TEST(Backlash, AMoveCutDuringTheTakeupTakesTheRestWhenItResumes) {
  const Settings s = backlash_x();
  const std::string path = trace_path("cut");
  Steps6 reported{};
  {
    SimCard card(s, false, {}, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    gen.segment(segment(vec(0), vec(0.1), 0, 2, 0, 14));
    gen.flush();
    // Cut the move back 4 takeup steps in: stop at the tick after the 4th reverse pulse.
    const PlannedSegment back = segment(vec(0.1), vec(0), 0, 2, 0, 14);
    std::atomic<std::int64_t> stop{StepGenerator::kNever};
    // Find where the 4th takeup step falls by placing the same move on a second generator.
    std::int64_t cut = 0, t0 = 0;
    {
      SimCard probe(s, false, {}, path + ".probe");
      probe.start(s.card.pacer_hz());
      StepGenerator g2(s, probe);
      g2.segment(segment(vec(0), vec(0.1), 0, 2, 0, 14));
      g2.flush();
      t0 = g2.tick();
      g2.segment(back);
      g2.flush();
    }
    int seen = 0;
    for (const auto& p : channel_pulses(read_trace(path + ".probe"), 0, 8))
      if (!p.positive && ++seen == 4) cut = p.tick + 1 - t0;
    fs::remove(path + ".probe");
    ASSERT_GT(cut, 0);
    stop = gen.tick() + cut;
    const std::optional<double> at = gen.segment_until(back, {&stop, nullptr});
    ASSERT_TRUE(at.has_value());
    EXPECT_EQ(gen.position()[0], steps(0.1, s));  // the load has not moved
    // Resume the rest of the move from where it was cut (here: the same place).
    gen.segment(segment(vec(0.1), vec(0), 0, 2, 0, 14));
    gen.flush();
    reported = gen.position();
  }
  const auto runs = direction_runs(channel_pulses(read_trace(path), 0, 8));
  fs::remove(path);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1], std::make_pair(false, static_cast<int>(steps(0.1, s) + 9)));
  EXPECT_EQ(reported[0], 0);
}

// An axis's backlash is an optional profile key: a profile without it loads (none), one with
// it loads its value, and a negative one is refused.
TEST(Backlash, IsAnOptionalProfileKey) {
  const SettingsLoad plain = parse_settings(default_profile_text(), "p.toml");
  ASSERT_TRUE(plain.ok());
  for (const AxisSettings& a : plain.settings.axes) EXPECT_EQ(a.backlash, 0);
  std::string text = default_profile_text();
  const std::size_t at = text.find("[axes.y]");
  ASSERT_NE(at, std::string::npos);
  text.insert(text.find('\n', at) + 1, "backlash = 0.004\n");
  const SettingsLoad with = parse_settings(text, "p.toml");
  ASSERT_TRUE(with.ok()) << with.errors[0].message;
  EXPECT_EQ(with.settings.axes[1].backlash, 0.004);
  text.replace(text.find("backlash = 0.004"), 16, "backlash = -1.0");
  const SettingsLoad bad = parse_settings(text, "p.toml");
  ASSERT_EQ(bad.errors.size(), 1u);
  EXPECT_NE(bad.errors[0].message.find("axes.y.backlash"), std::string::npos)
      << bad.errors[0].message;
}

}  // namespace
}  // namespace gantry
