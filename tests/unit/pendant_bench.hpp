// Test support for the pendant tests: a controller on the simulated card with a pendant input
// on a fake clock (what it was told kept), and an XHC input report built field by field.
#pragma once

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gantry/interp/operator_io.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/session/pendant_input.hpp"
#include "gantry/settings/settings.hpp"
#include "pendant/xhc_protocol.hpp"
#include "sim/sim_card.hpp"

namespace gantry::session {

using namespace std::chrono_literals;

struct FakeClock {
  std::atomic<std::int64_t> ms{0};
  PendantInput::Clock::time_point now() const {
    return PendantInput::Clock::time_point{} + std::chrono::milliseconds(ms.load());
  }
};

struct Bench {
  explicit Bench(bool realtime = false, Settings s = default_settings())
      : settings(std::move(s)), card(settings, realtime) {}
  Settings settings;
  SimCard card;
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  FakeClock clock;
  std::vector<std::string> told;
  std::mutex told_m;
  PendantBindings bindings;
  std::unique_ptr<PendantInput> input;

  PendantInput& in() {
    if (!input)
      input = std::make_unique<PendantInput>(
          c, settings, bindings, [this] { return clock.now(); },
          [this](const std::string& t) {
            std::lock_guard lock(told_m);
            told.push_back(t);
          });
    return *input;
  }
  void send(const std::vector<PendantEvent>& out) {
    for (const PendantEvent& e : out) in().handle(e);
  }
  std::int64_t steps(double units, int axis = 0) const {
    return std::llround(units * settings.axes[axis].steps_per_unit);
  }
  // Ticks until every queued step jog has played and the machine is at rest.
  void settle() {
    for (int k = 0; k < 2000; ++k) {
      in().tick();
      const bool rest = c.wait_for(1ms);
      if (rest && !in().jogging()) {
        in().tick();
        if (!in().jogging()) return;
      }
    }
    const ControllerStatus st = c.status();
    FAIL() << "the pendant's jogs never came to rest: " << state_name(st.state) << " settled "
           << st.settled << " jogging " << in().jogging() << " " << st.message << " / "
           << last_told();
  }
  std::string last_told() {
    std::lock_guard lock(told_m);
    return told.empty() ? "" : told.back();
  }
};

inline pendant::XhcReport report(pendant::XhcKey k1, pendant::XhcKey k2, std::uint8_t feed,
                                 std::uint8_t axis, std::int8_t delta) {
  pendant::XhcReport r;
  r.key1 = k1;
  r.key2 = k2;
  r.feed_knob = feed;
  r.axis_knob = axis;
  r.delta = delta;
  return r;
}

}  // namespace gantry::session
