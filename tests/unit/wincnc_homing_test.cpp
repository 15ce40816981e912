// Homing as WinCNC's g28move describes it, per axis: its own approach speeds, the back-off
// between the approaches, how far off the switch it ends, and the longest search; on the
// simulated card with the switch at a known place, asserted to the step on the pin trace.
#include <gtest/gtest.h>
#include <unistd.h>

#include "pin_trace.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/settings/settings.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::channel_pulses;
using test::direction_runs;
using test::read_trace;
namespace fs = std::filesystem;

// X's proximity switch closes at or below -1.5 in (the card's own coordinates).
constexpr double kSwitch = -1.5;

struct HomingMachine {
  explicit HomingMachine(Settings s, const SimWorld& w = world())
      : settings(std::move(s)),
        path((fs::temp_directory_path() /
              ("gantry_wincnc_homing_" + std::to_string(getpid()) + ".trace"))
                 .string()),
        card(settings, false, w, path) {}
  static SimWorld world() {
    SimWorld w;
    w.home_switch[0] = kSwitch;
    return w;
  }
  Settings settings;
  std::string path;
  SimCard card;
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  double spu() const { return settings.axes[0].steps_per_unit; }
  std::int64_t steps(double in) const { return std::llround(in * spu()); }
  // X's step where its switch closes (the first whole step at or past it).
  std::int64_t at_switch() const { return static_cast<std::int64_t>(std::floor(kSwitch * spu())); }
  // G28 X, run to its end when it starts.
  Outcome home_x() {
    const Outcome o = c.run(Script::from_text("G28 X\n", "part.nc"));
    if (o) c.wait();
    return o;
  }
};

Settings profile() {
  Settings s = default_settings();
  s.outputs.charge_pump_bit = -1;
  s.gcode_dialect = GcodeDialect::WinCNC;
  s.homing.order = "zxy";
  s.homing.fast[0] = 2.0;     // g28move F
  s.homing.slow[0] = 0.05;    // g28move T
  s.homing.retract[0] = 0.1;  // g28move R
  s.homing.offset[0] = 0.5;   // g28move X
  return s;
}

// G28 X: fast to the switch, back 0.1, slowly to it again, 0.5 off it; the table base is 0
// where the switch closed (homing.x.at), so X reads 0.5 there.
TEST(WinCncHoming, EachAxisUsesItsOwnSpeedsBackOffAndFinalOffset) {
  auto m = std::make_unique<HomingMachine>(profile());
  const Outcome o = m->c.run(Script::from_text("G28 X\n", "part.nc"));
  ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : " " + o.errors[0].message);
  m->c.wait();
  const ControllerStatus st = m->c.status();
  ASSERT_EQ(st.state, MachineState::Idle) << st.message;
  // The first step at or below the switch, then 0.5 in off it.
  const double spu = m->spu();
  auto steps = [&](double in) { return std::llround(in * spu); };
  const auto at_switch = static_cast<std::int64_t>(std::floor(kSwitch * spu));
  EXPECT_EQ(m->card.steps()[0], at_switch + steps(0.5));
  const ModalState ms = m->c.modal();
  EXPECT_NEAR(ms.position[0] + ms.zero[0], 0.5, 1e-12);
  EXPECT_EQ(m->card.timing_violations(), 0u);
  const Settings settings = m->settings;
  const std::string path = m->path;
  m.reset();  // the trace is whole once the card is gone
  const auto pulses =
      channel_pulses(read_trace(path), settings.pins[0].step_bit, settings.pins[0].dir_bit);
  fs::remove(path);
  const auto runs = direction_runs(pulses);
  ASSERT_EQ(runs.size(), 4u);
  // The search and the measured approach each ramp down past the switch and come back to
  // where it closed (the probe's latch), so each pair of runs nets out exactly: R off it,
  // then the final offset.
  EXPECT_FALSE(runs[0].first);
  EXPECT_TRUE(runs[1].first);
  EXPECT_FALSE(runs[2].first);
  EXPECT_TRUE(runs[3].first);
  EXPECT_EQ(runs[1].second - runs[0].second, at_switch + steps(0.1));  // R = 0.1 off it
  EXPECT_EQ(runs[3].second - runs[2].second, steps(0.5) - steps(0.1));
  // The measured approach at T = 0.05 in/s: its steady steps 1 / (0.05 x spu) s apart.
  const auto from = static_cast<std::size_t>(runs[0].second + runs[1].second);
  std::vector<std::int64_t> intervals;
  for (std::size_t k = from + 1; k < from + static_cast<std::size_t>(runs[2].second); ++k)
    intervals.push_back(pulses[k].tick - pulses[k - 1].tick);
  ASSERT_GT(intervals.size(), 10u);
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  EXPECT_NEAR(static_cast<double>(intervals[intervals.size() / 2]),
              settings.card.pacer_hz() / (0.05 * spu), 1.0);
  // The search at F = 2 in/s: its fastest steps 1 / (2 x spu) s apart.
  std::int64_t fastest = INT64_MAX;
  for (std::size_t k = 1; k < static_cast<std::size_t>(runs[0].second); ++k)
    fastest = std::min(fastest, pulses[k].tick - pulses[k - 1].tick);
  EXPECT_NEAR(static_cast<double>(fastest), settings.card.pacer_hz() / (2.0 * spu), 1.0);
}

// L: the search gives up after its length, with an error naming the key; X stopped there.
TEST(WinCncHoming, TheSearchStopsAtItsLongestTravelWithAnError) {
  Settings s = profile();
  s.homing.search[0] = 1.0;  // the switch is 1.5 in away
  HomingMachine m(s);
  const Outcome o = m.home_x();
  ASSERT_TRUE(o) << o.reason;
  const ControllerStatus st = m.c.status();
  EXPECT_NE(st.state, MachineState::Idle);
  EXPECT_NE(st.message.find("never closed within 1"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("homing.x.search"), std::string::npos) << st.message;
  EXPECT_EQ(m.card.steps()[0], -m.steps(1.0));
  fs::remove(m.path);
}

// Left out, each axis takes the [homing] values: the back-off is also the final offset.
TEST(WinCncHoming, PerAxisKeysAreOptionalAndDefaultToTheHomingTable) {
  const SettingsLoad plain = parse_settings(default_profile_text(), "p.toml");
  ASSERT_TRUE(plain.ok());
  for (int i = 0; i < kAxisCount; ++i) {
    EXPECT_FALSE(plain.settings.homing.fast[i]);
    EXPECT_FALSE(plain.settings.homing.offset[i]);
    EXPECT_FALSE(plain.settings.homing.search[i]);
  }
  std::string text = default_profile_text();
  const std::string key = "[homing.x]\n";
  ASSERT_NE(text.find(key), std::string::npos);
  text.insert(text.find(key) + key.size(),
              "fast_speed = 2\nslow_speed = 0.05\nback_off = 0.1\noffset = 0.5\nsearch = 30\n");
  const SettingsLoad with = parse_settings(text, "p.toml");
  ASSERT_TRUE(with.ok()) << with.errors[0].message;
  EXPECT_EQ(with.settings.homing.fast[0], 2.0);
  EXPECT_EQ(with.settings.homing.slow[0], 0.05);
  EXPECT_EQ(with.settings.homing.retract[0], 0.1);
  EXPECT_EQ(with.settings.homing.offset[0], 0.5);
  EXPECT_EQ(with.settings.homing.search[0], 30.0);
}

// The home input spikes for two words while X searches, far from the switch (a wire picking
// up noise); the switch itself closes at kSwitch.
SimWorld spiked_world(const Settings& s) {
  SimWorld w = HomingMachine::world();
  const int bit = s.inputs.switch_bits[static_cast<std::size_t>(s.homing.input - 1)];
  const double tick = 1.0 / s.card.pacer_hz();
  w.input_events = {{0.3, bit, true}, {0.3 + 2 * tick, bit, false}};
  return w;
}

// g28_lim_cnt: with homing.debounce = 4 the spike is forgotten and X homes exactly where the
// switch closes, as without it; with 1 (the first closing) the spike stops the search there,
// and the measured approach finds no switch.
TEST(WinCncHoming, TheHomingDebounceIgnoresASpikeAndKeepsTheSwitchsPlace) {
  for (const int debounce : {4, 1}) {
    Settings s = profile();
    s.homing.debounce = debounce;
    HomingMachine m(s, spiked_world(s));
    const Outcome o = m.home_x();
    ASSERT_TRUE(o) << o.reason;
    const ControllerStatus st = m.c.status();
    if (debounce == 4) {
      ASSERT_EQ(st.state, MachineState::Idle) << st.message;
      EXPECT_EQ(m.card.steps()[0], m.at_switch() + m.steps(0.5));
      const ModalState ms = m.c.modal();
      EXPECT_NEAR(ms.position[0] + ms.zero[0], 0.5, 1e-12);
    } else {
      EXPECT_NE(st.state, MachineState::Idle);
      EXPECT_NE(st.message.find("did not close again"), std::string::npos) << st.message;
      EXPECT_GT(m.card.steps()[0], m.at_switch() + m.steps(0.5));  // stopped short
    }
    fs::remove(m.path);
  }
}

// The debounced switch's place does not depend on the count: G28 X with homing.debounce 30
// ends on the same step as with 1, on a switch that does not bounce.
TEST(WinCncHoming, TheDebouncedEdgeIsWhereTheSwitchClosed) {
  Settings s = profile();
  s.homing.debounce = 30;
  HomingMachine m(s);
  const Outcome o = m.home_x();
  ASSERT_TRUE(o) << o.reason;
  ASSERT_EQ(m.c.status().state, MachineState::Idle) << m.c.status().message;
  EXPECT_EQ(m.card.steps()[0], m.at_switch() + m.steps(0.5));
  fs::remove(m.path);
}

// The watch's count, sample by sample, as every card feeds it: a run shorter than the count
// is forgotten; the edge given is the first sample of the run that reached it; a run of
// samples alike counts as many.
TEST(WinCncHoming, TheEdgeDetectorCountsSamplesAtTheLevel) {
  EdgeDetector d;
  d.arm({.mask = 1u << 3, .levels = 1u << 3, .stop = 0, .debounce = 3}, 0);
  EXPECT_FALSE(d.sample(1u << 3, 10));  // 1
  EXPECT_FALSE(d.sample(0, 11));        // released: forgotten
  EXPECT_FALSE(d.sample(1u << 3, 12));  // 1
  EXPECT_FALSE(d.sample(1u << 3, 13));  // 2
  EXPECT_EQ(d.samples_left(), 1u);
  const std::optional<InputEdge> e = d.sample(1u << 3, 14);  // 3
  ASSERT_TRUE(e);
  EXPECT_EQ(e->tick, 12u);
  EXPECT_EQ(e->bit, 3);
  EXPECT_FALSE(d.sample(1u << 3, 15));  // once until armed again
  d.arm({.mask = 1u << 3, .levels = 1u << 3, .stop = 0, .debounce = 5}, 0);
  EXPECT_FALSE(d.sample(1u << 3, 20, 4));
  const std::optional<InputEdge> run = d.sample(1u << 3, 24, 1);
  ASSERT_TRUE(run);
  EXPECT_EQ(run->tick, 20u);
  // Armed at its level already: it must leave it first, whatever the count.
  d.arm({.mask = 1u << 3, .levels = 1u << 3, .stop = 0, .debounce = 1}, 1u << 3);
  EXPECT_FALSE(d.sample(1u << 3, 30, 100));
  EXPECT_FALSE(d.sample(0, 31));
  EXPECT_TRUE(d.sample(1u << 3, 32));
}

// g28coord: after G28 X, X goes to its park position (table base 3) at jog speed; Z, not
// homed, has a park too and stays. A park outside the soft limits is refused at load.
TEST(WinCncHoming, TheParkPositionFollowsHoming) {
  Settings s = profile();
  s.homing.park[0] = 3.0;
  s.homing.park[2] = -0.5;
  HomingMachine m(s);
  const Outcome o = m.home_x();
  ASSERT_TRUE(o) << o.reason;
  ASSERT_EQ(m.c.status().state, MachineState::Idle) << m.c.status().message;
  EXPECT_EQ(m.card.steps()[0], m.at_switch() + m.steps(3.0));
  EXPECT_EQ(m.card.steps()[2], 0);
  const ModalState ms = m.c.modal();
  EXPECT_NEAR(ms.position[0] + ms.zero[0], 3.0, 1e-12);
  fs::remove(m.path);

  std::string text = default_profile_text();
  const std::string key = "[homing.x]\n";
  ASSERT_NE(text.find(key), std::string::npos);
  text.insert(text.find(key) + key.size(), "park = 30\n");
  const SettingsLoad bad = parse_settings(text, "p.toml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.errors[0].message.find("homing.x.park 30 is outside X's soft limits"),
            std::string::npos)
      << bad.errors[0].message;
}

// g28move A: X homes on a switch of its own, input 5 (bit 9), while the others share input 3;
// without homing.x.input it watches input 3, which X's switch never closes.
TEST(WinCncHoming, AnAxisHomesOnItsOwnInput) {
  for (const bool own : {true, false}) {
    Settings s = profile();
    s.inputs.switch_bits[4] = 9;
    s.inputs.home_bit[0] = 9;
    if (own) s.homing.axis_input[0] = 5;
    s.homing.search[0] = 3.0;
    HomingMachine m(s);
    const Outcome o = m.home_x();
    ASSERT_TRUE(o) << o.reason;
    const ControllerStatus st = m.c.status();
    if (own) {
      ASSERT_EQ(st.state, MachineState::Idle) << st.message;
      EXPECT_EQ(m.card.steps()[0], m.at_switch() + m.steps(0.5));
    } else {
      EXPECT_NE(st.message.find("input 3 never closed"), std::string::npos) << st.message;
    }
    fs::remove(m.path);
  }
}

// WinCNC homes on the limit switch of the homing side (the import makes it an input switch,
// homing.x.input): X homes down onto its min limit switch (bit 2, input 5) and stops there
// without a limit fault, as the card does not trip on a bit homing watches.
TEST(WinCncHoming, AnAxisHomesOnItsLimitSwitch) {
  Settings s = profile();
  s.inputs.switch_bits[4] = s.inputs.min_bit[0];
  s.homing.axis_input[0] = 5;
  s.homing.search[0] = 3.0;
  SimWorld w;
  w.min_switch[0] = kSwitch;
  HomingMachine m(s, w);
  const Outcome o = m.home_x();
  ASSERT_TRUE(o) << o.reason;
  ASSERT_EQ(m.c.status().state, MachineState::Idle) << m.c.status().message;
  EXPECT_EQ(m.card.steps()[0], m.at_switch() + m.steps(0.5));
  fs::remove(m.path);
}

}  // namespace
}  // namespace gantry
