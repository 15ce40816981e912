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
  explicit HomingMachine(Settings s)
      : settings(std::move(s)),
        path((fs::temp_directory_path() /
              ("gantry_wincnc_homing_" + std::to_string(getpid()) + ".trace"))
                 .string()),
        card(settings, false, world(), path) {}
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
  const Outcome o = m.c.run(Script::from_text("G28 X\n", "part.nc"));
  ASSERT_TRUE(o) << o.reason;
  m.c.wait();
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

}  // namespace
}  // namespace gantry
