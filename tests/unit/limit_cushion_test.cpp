// WinCNC's limit handling beyond lim_mode: the cushioned stop after a limit switch (lim_step)
// and after the operator's E-stop (esc_step), counted to the step on the pin trace; the
// soft-limit clamp (softlim B1, V1); the limit rule on the real cards' input path
// (LimitFilter, shared); and homing.require's flags.
#include <gtest/gtest.h>
#include <unistd.h>

#include "pin_trace.hpp"
#include "segment_builders.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "gantry/hal/limit_filter.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/step/motion_feeder.hpp"
#include "gantry/step/step_generator.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::channel_pulses;
using test::read_trace;
using test::segment;
using test::TracePulse;
using test::vec;
namespace fs = std::filesystem;

std::string trace_path(const char* name) {
  return (fs::temp_directory_path() /
          (std::string("gantry_cushion_") + name + "_" + std::to_string(getpid()) + ".trace"))
      .string();
}

Settings quiet() {
  Settings s = default_settings();
  s.outputs.charge_pump_bit = -1;  // the trace holds the step and direction lines only
  return s;
}

struct LimitRun {
  Steps6 card{};      // the simulated card's own decoded count
  Steps6 reported{};  // the step generator's played position: what the controller reports
  CardFault fault = CardFault::None;
  std::string message;
  std::vector<TracePulse> x, y;  // X's and Y's pulses on the trace
};

// X (and Y, at half X's speed, when `diagonal`) runs at 4 in/s onto X's max limit switch
// at 0.5 in, with `cushion` steps of limits.cushion_steps.
LimitRun run_into_limit(int cushion, bool diagonal = false) {
  Settings s = quiet();
  s.limits.cushion_steps = cushion;
  SimWorld w;
  w.max_switch[0] = 0.5;
  const std::string path = trace_path(diagonal ? "diag" : "x");
  LimitRun r;
  {
    SimCard card(s, false, w, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    try {
      gen.segment(segment(vec(0), diagonal ? vec(1.0, 0.5) : vec(1.0), 4, 4, 4, 20));
      gen.flush();
    } catch (const GantryError& e) {
      r.message = e.diagnostic().message;
    }
    r.card = card.steps();
    r.reported = gen.played_position();
    r.fault = card.fault();
  }
  const auto trace = read_trace(path);
  fs::remove(path);
  r.x = channel_pulses(trace, s.pins[0].step_bit, s.pins[0].dir_bit);
  r.y = channel_pulses(trace, s.pins[1].step_bit, s.pins[1].dir_bit);
  return r;
}

// The step at which X reaches its switch: the first at or beyond 0.5 in.
std::int64_t hit_step() {
  return static_cast<std::int64_t>(std::ceil(0.5 * default_settings().axes[0].steps_per_unit));
}

TEST(CushionedStop, WithoutACushionTheCardStopsAtTheStepThatClosesTheSwitch) {
  const LimitRun r = run_into_limit(0);
  EXPECT_EQ(r.fault, CardFault::Limit);
  EXPECT_EQ(r.card[0], hit_step());
  EXPECT_EQ(r.reported[0], hit_step());
  EXPECT_EQ(r.message.find("cushioned"), std::string::npos);
}

// lim_step = 100: X makes exactly 100 more steps after the one that closed the switch, each
// interval at least as long as the one before (a deceleration, not a dead stop), the last
// several times the cruise's; the position reported is the card's own count.
TEST(CushionedStop, ALimitHitDeceleratesForTheCushionsStepsAndTheyAreCounted) {
  const LimitRun r = run_into_limit(100);
  EXPECT_EQ(r.fault, CardFault::Limit);
  EXPECT_EQ(r.card[0], hit_step() + 100);
  EXPECT_EQ(r.reported, r.card);  // every step counted
  ASSERT_EQ(static_cast<std::int64_t>(r.x.size()), hit_step() + 100);
  for (const TracePulse& p : r.x) EXPECT_TRUE(p.positive);
  const auto at = static_cast<std::size_t>(hit_step()) - 1;  // the pulse that closed it
  const std::int64_t cruise = r.x[at].tick - r.x[at - 1].tick;
  std::int64_t before = cruise;
  for (std::size_t k = at + 1; k < r.x.size(); ++k) {
    const std::int64_t interval = r.x[k].tick - r.x[k - 1].tick;
    EXPECT_GE(interval, before - 1) << "cushion step " << k - at;  // rounding to ticks only
    before = interval;
  }
  EXPECT_GT(before, 5 * cruise);  // the last steps come slowly: it came to rest
  std::cout << "cushion: 100 steps in " << r.x.back().tick - r.x[at].tick
            << " ticks after the hit; step interval " << cruise << " ticks at the hit, " << before
            << " at the end\n";
  // The run still ends on the limit, and says the cushion moved it.
  EXPECT_NE(r.message.find("limit switch"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("cushioned: 100 more steps"), std::string::npos) << r.message;
}

// Two axes: the fastest (X) makes the cushion's steps, Y its share (half), along the same line.
TEST(CushionedStop, EachMovingAxisDeceleratesInProportionTheFastestMakingTheCushion) {
  const LimitRun r = run_into_limit(100, /*diagonal=*/true);
  ASSERT_EQ(r.fault, CardFault::Limit);
  EXPECT_EQ(r.card[0], hit_step() + 100);
  const std::int64_t y_at_hit =
      std::llround(0.5 * hit_step() / default_settings().axes[0].steps_per_unit *
                   default_settings().axes[1].steps_per_unit);
  EXPECT_NEAR(static_cast<double>(r.card[1] - y_at_hit), 50, 2);
  EXPECT_EQ(r.reported, r.card);
  EXPECT_EQ(static_cast<std::int64_t>(r.y.size()), r.card[1]);
}

// esc_step: the operator's E-stop request, cut at the same tick with and without a cushion:
// the cushioned one makes exactly esc_steps more of X's steps, and they are counted.
TEST(CushionedStop, TheOperatorsEStopDeceleratesForEscSteps) {
  auto halted_at = [](int esc) {
    Settings s = quiet();
    SimCard card(s);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    MotionFeeder feeder(gen);
    feeder.request_halt(std::llround(0.1 * s.card.pacer_hz()), esc);  // 0.1 s in
    feeder.segment(segment(vec(0), vec(1.0), 4, 4, 4, 20));
    EXPECT_EQ(feeder.phase(), FeedPhase::Halted);
    EXPECT_EQ(gen.played_position(), card.steps());
    EXPECT_EQ(card.fault(), CardFault::None);  // a stop, not a fault
    return card.steps()[0];
  };
  const std::int64_t dead = halted_at(0), cushioned = halted_at(200);
  EXPECT_GT(dead, 300);  // 0.1 s at 4 in/s
  EXPECT_EQ(cushioned, dead + 200);
}

// The cushion and the steps before it agree with the live machine's report: a run into the
// limit ends stopped with the switch named, never done, and the position is the card's.
TEST(CushionedStop, TheControllerReportsTheLimitAndThePositionAfterTheCushion) {
  Settings s = default_settings();
  s.limits.cushion_steps = 50;
  SimWorld w;
  w.max_switch[0] = 0.5;
  SimCard card(s, false, w);
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{s, card, io, store};
  const Outcome o = c.run(Script::from_text("MX, 1\n", "part.sbp"));
  ASSERT_TRUE(o) << o.reason;
  c.wait();
  const ControllerStatus st = c.status();
  EXPECT_NE(st.state, MachineState::Idle);
  EXPECT_NE(st.message.find("X high limit switch"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("cushioned"), std::string::npos) << st.message;
  EXPECT_EQ(st.steps[0], card.steps()[0]);
  EXPECT_EQ(card.steps()[0], hit_step() + 50);
}

TEST(CushionedStop, CushionAndEscStepsAreOptionalProfileKeys) {
  const SettingsLoad plain = parse_settings(default_profile_text(), "p.toml");
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain.settings.limits.cushion_steps, 0);
  EXPECT_EQ(plain.settings.limits.esc_steps, 0);
  const SettingsLoad with = parse_settings(
      default_profile_text() + "\n[limits]\ncushion_steps = 100\nesc_steps = 200\n", "p.toml");
  ASSERT_TRUE(with.ok()) << with.errors[0].message;
  EXPECT_EQ(with.settings.limits.cushion_steps, 100);
  EXPECT_EQ(with.settings.limits.esc_steps, 200);
  const SettingsLoad bad =
      parse_settings(default_profile_text() + "\n[limits]\ncushion_steps = -1\n", "p.toml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.errors[0].message.find("limits.cushion_steps"), std::string::npos)
      << bad.errors[0].message;
}

// ---- the soft-limit clamp ---------------------------------------------------------------

struct ClampRun {
  std::vector<CanonMove> moves;
  std::vector<std::string> errors, warnings;
};

ClampRun clamp_run(SoftClamp mode, const std::string& text) {
  Settings s = default_settings();  // X 0..24, Z -5.5..5.5 (in)
  s.limits.soft_clamp = mode;
  ClampRun r;
  struct Sink : MotionSink {
    std::vector<CanonMove>* out;
    void move(const CanonMove& m) override {
      if (m.kind == MoveKind::Line) out->push_back(m);
    }
    void flush() override {}
  } sink;
  sink.out = &r.moves;
  ScriptedIO io{true, {}};
  PersistentStore store;
  Interpreter in(s, sink, io, store);
  try {
    in.run(Script::from_text(text, "part.sbp"));
  } catch (const GantryError& e) {
    r.errors.push_back(e.diagnostic().message);
  }
  for (const Diagnostic& d : io.warnings()) r.warnings.push_back(d.message);
  return r;
}

TEST(SoftClamp, RefusalStaysTheDefault) {
  const ClampRun r = clamp_run(SoftClamp::Off, "MX, 30\n");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors[0].find("outside the soft limits"), std::string::npos);
  EXPECT_TRUE(r.moves.empty());
}

// softlim B1: the target is moved to the boundary; the run is told once; the moves after it
// go on from the clamped point.
TEST(SoftClamp, AllClampsEveryAxisToItsLimitAndWarnsOnce) {
  const ClampRun r = clamp_run(SoftClamp::All, "MX, 30\nMY, 2\nMY, -4\nMX, 10\n");
  ASSERT_TRUE(r.errors.empty()) << r.errors[0];
  ASSERT_EQ(r.moves.size(), 4u);
  EXPECT_DOUBLE_EQ(r.moves[0].to[0], 24.0);
  EXPECT_DOUBLE_EQ(r.moves[2].to[1], 0.0);
  EXPECT_DOUBLE_EQ(r.moves[3].from[0], 24.0);
  EXPECT_DOUBLE_EQ(r.moves[3].to[0], 10.0);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("clamped to the soft limits (X=30.0000 to 24.0000"),
            std::string::npos)
      << r.warnings[0];
}

// softlim V1: vertical axes clamped silently; the others still refused.
TEST(SoftClamp, VerticalClampsZSilentlyAndRefusesTheOthers) {
  const ClampRun z = clamp_run(SoftClamp::Vertical, "MZ, 9\n");
  ASSERT_TRUE(z.errors.empty()) << z.errors[0];
  ASSERT_EQ(z.moves.size(), 1u);
  EXPECT_DOUBLE_EQ(z.moves[0].to[2], default_settings().axes[2].max);
  EXPECT_TRUE(z.warnings.empty());
  const ClampRun x = clamp_run(SoftClamp::Vertical, "MX, 30\n");
  ASSERT_EQ(x.errors.size(), 1u);
  EXPECT_NE(x.errors[0].find("outside the soft limits"), std::string::npos);
}

TEST(SoftClamp, IsAnOptionalProfileKeyWithThreeValues) {
  EXPECT_EQ(parse_settings(default_profile_text(), "p.toml").settings.limits.soft_clamp,
            SoftClamp::Off);
  const SettingsLoad v =
      parse_settings(default_profile_text() + "\n[limits]\nsoft_clamp = \"vertical\"\n", "p.toml");
  ASSERT_TRUE(v.ok()) << v.errors[0].message;
  EXPECT_EQ(v.settings.limits.soft_clamp, SoftClamp::Vertical);
  EXPECT_FALSE(
      parse_settings(default_profile_text() + "\n[limits]\nsoft_clamp = \"some\"\n", "p.toml")
          .ok());
}

// ---- the limit rule the real cards share -------------------------------------------------

// The rule as a card's input path applies it, the steps read from the words themselves (as
// the PCI-7200 and GPIO cards see them): X's min switch (input bit 2) counts while X steps
// towards minus, not while it steps towards plus.
TEST(LimitFilter, TravelOnlyReadsTheDirectionFromTheWordsPlayed) {
  Settings s = default_settings();
  s.limits.travel_only = true;
  const double pacer = s.card.pacer_hz();
  const InputTrip limits{1u << 2, 1u << 2};
  const std::uint32_t step = 1u << s.pins[0].step_bit, minus = 1u << s.pins[0].dir_bit;
  for (const bool towards_minus : {true, false}) {
    LimitFilter f(s, pacer);
    const std::uint32_t dir = towards_minus ? minus : 0;
    std::uint32_t before = dir;
    for (std::uint64_t t = 0; t < 100; ++t) {  // a step every 10 ticks
      const std::uint32_t w = dir | (t % 10 == 0 ? step : 0);
      f.note_word(t, before, w);
      before = w;
    }
    EXPECT_EQ(f.sample(limits, 100, 0, 1u << 2), towards_minus) << towards_minus;
  }
}

// lim_cnt: consecutive samples. A card that samples the inputs every N ticks counts samples.
TEST(LimitFilter, DebounceCountsConsecutiveSamplesAndForgetsARelease) {
  Settings s = default_settings();
  s.limits.debounce = 3;
  LimitFilter f(s, s.card.pacer_hz());
  const InputTrip limits{1u << 2, 1u << 2};
  const std::uint32_t on = 1u << 2;
  EXPECT_FALSE(f.sample(limits, 10, 0, on));   // 1
  EXPECT_FALSE(f.sample(limits, 20, on, on));  // 2
  EXPECT_FALSE(f.sample(limits, 30, on, 0));   // released: forgotten
  EXPECT_FALSE(f.sample(limits, 40, 0, on));   // 1 again
  EXPECT_FALSE(f.sample(limits, 50, on, on));  // 2
  EXPECT_TRUE(f.sample(limits, 60, on, on));   // 3: trips
  LimitFilter g(s, s.card.pacer_hz());
  EXPECT_FALSE(g.sample(limits, 10, 0, on));
  EXPECT_EQ(g.samples_to_trip(), 2u);
  EXPECT_TRUE(g.sample(limits, 12, on, on, 2));  // a run of two samples alike
}

// ---- homing.require --------------------------------------------------------------------

// An E-stop mid-motion flags the axes homing.require names: a run that moves one is refused
// at its line until it is homed (G28 here, the built-in homing on the simulated switches) or
// the operator confirms the position; an axis not named moves.
TEST(RequireHome, AnEStopMidMotionRefusesTheNamedAxesUntilTheyAreHomed) {
  Settings s = default_settings();
  s.gcode_dialect = GcodeDialect::WinCNC;  // G28: the built-in homing
  s.homing.require = 0b011;                // X and Y
  SimCard card(s, false, simulated_world(s));
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{s, card, io, store};
  c.schedule(Request::EStop, 0.2);
  ASSERT_TRUE(c.run(Script::from_text("MX, 5\n", "part.sbp")));
  c.wait();
  ASSERT_EQ(c.status().state, MachineState::EStop);
  ASSERT_TRUE(c.acknowledge());
  EXPECT_EQ(c.axes_to_home(), 0b011u);
  const Outcome z = c.run(Script::from_text("MZ, 0.5\n", "part.sbp"));  // Z is not named
  ASSERT_TRUE(z) << z.reason;
  c.wait();
  EXPECT_EQ(c.status().state, MachineState::Idle) << c.status().message;
  const Outcome x = c.run(Script::from_text("MY, 1\n", "part.sbp"));
  if (x) c.wait();
  const std::string why =
      x ? c.status().message : x.reason + (x.errors.empty() ? "" : x.errors[0].message);
  EXPECT_NE(why.find("Y must be homed"), std::string::npos) << why;
  const Outcome home = c.run(Script::from_text("G28\n", "part.nc"));
  ASSERT_TRUE(home) << home.reason;
  c.wait();
  ASSERT_EQ(c.status().state, MachineState::Idle) << c.status().message;
  EXPECT_EQ(c.axes_to_home(), 0u);
  const Outcome after = c.run(Script::from_text("MY, 1\n", "part.sbp"));
  ASSERT_TRUE(after) << after.reason;
  c.wait();
  EXPECT_EQ(c.status().state, MachineState::Idle) << c.status().message;
}

TEST(RequireHome, ConfirmClearsTheFlags) {
  Settings s = default_settings();
  s.homing.require = 0b100;
  SimCard card(s);
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{s, card, io, store};
  c.schedule(Request::EStop, 0.2);
  ASSERT_TRUE(c.run(Script::from_text("MZ, 2\n", "part.sbp")));
  c.wait();
  ASSERT_TRUE(c.acknowledge());
  EXPECT_EQ(c.axes_to_home(), 0b100u);
  c.clear_home_flags();
  EXPECT_EQ(c.axes_to_home(), 0u);
}

TEST(RequireHome, IsAnOptionalProfileKeyOfAxisLetters) {
  EXPECT_EQ(parse_settings(default_profile_text(), "p.toml").settings.homing.require, 0u);
  std::string text = default_profile_text();
  const std::string key = "back_off = 0.25";
  ASSERT_NE(text.find(key), std::string::npos);
  text.replace(text.find(key), key.size(), key + "\nrequire = \"xZ\"");
  const SettingsLoad xz = parse_settings(text, "p.toml");
  ASSERT_TRUE(xz.ok()) << xz.errors[0].message;
  EXPECT_EQ(xz.settings.homing.require, 0b101u);
  text.replace(text.find("require = \"xZ\""), 13, "require = \"xq\"");
  EXPECT_FALSE(parse_settings(text, "p.toml").ok());
}

}  // namespace
}  // namespace gantry
