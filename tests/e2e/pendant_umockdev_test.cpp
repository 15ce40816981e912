// The XHC pendant end to end under umockdev (run by ctest through umockdev-run with
// tests/data/pendant): libusb finds the emulated device in sysfs, opens its usbfs node and
// reads the recorded interrupt reports; the driver, the session's pendant input and the
// controller on the simulated card jog to the step, run a button's line, and see the cable
// pulled.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "gantry/interp/operator_io.hpp"
#include "gantry/session/pendant_input.hpp"
#include "gantry/session/pendant_xhc.hpp"
#include "pendant/usb_port.hpp"
#include "pendant/xhc_pendant.hpp"
#include "sim/sim_card.hpp"

namespace gantry::session {
namespace {

using namespace std::chrono_literals;

struct Rig final : pendant::XhcPendant::Listener {
  Settings settings = default_settings();
  SimCard card{settings};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  std::vector<std::string> told;
  PendantInput input{c, settings, {}, PendantInput::Clock::now,
                     [this](const std::string& t) { told.push_back(t); }};
  XhcTranslator translator;
  std::vector<std::pair<bool, std::string>> links;
  int reports = 0;

  void report(const pendant::XhcReport& r) override {
    ++reports;
    for (const PendantEvent& e : translator.events(r)) input.handle(e);
  }
  void link(bool connected, const std::string& why) override {
    links.emplace_back(connected, why);
    if (!connected) input.handle({.kind = PendantEvent::Kind::Lost});
  }
  pendant::XhcDisplay display() override {
    return xhc_display(c.status(), c.status().machine, translator.step_mode(), translator.axis());
  }
  // Each report's jogs and lines played out before the next is read (the simulated card plays
  // in virtual time), as an operator's hand is slower than the machine.
  void settle() {
    for (int k = 0; k < 5000; ++k) {
      input.tick();
      if (c.wait_for(1ms) && !input.jogging()) return;
    }
    FAIL() << "never at rest";
  }
  std::int64_t steps(double units, int axis) const {
    return std::llround(units * settings.axes[axis].steps_per_unit);
  }
};

TEST(PendantUmockdev, JogAButtonAndAnUnplugThroughLibusb) {
  ASSERT_NE(std::getenv("UMOCKDEV_DIR"), nullptr) << "run under umockdev-run (ctest does)";
  std::string why;
  std::unique_ptr<pendant::UsbPort> port = pendant::open_libusb_port(&why);
  ASSERT_TRUE(port) << why;
  Rig rig;
  pendant::XhcPendant driver(*port, rig);
  const auto t0 = pendant::XhcPendant::Clock::now();
  for (int k = 0; k < 2000; ++k) {
    driver.poll(pendant::XhcPendant::Clock::now(), 20);
    rig.settle();
    if (rig.links.size() >= 2) break;  // plugged in, then pulled out: the recording's end
  }
  ASSERT_EQ(rig.links.size(), 2u);
  EXPECT_TRUE(rig.links[0].first);
  EXPECT_FALSE(rig.links[1].first);
  EXPECT_EQ(rig.links[1].second, "the pendant was unplugged");
  EXPECT_EQ(rig.reports, 5);
  const ControllerStatus s = rig.c.status();
  EXPECT_EQ(s.steps[0], rig.steps(0.03, 0));  // 3 detents of 0.01 on X
  EXPECT_EQ(s.steps[1], rig.steps(0.2, 1));   // 2 detents of 0.1 on Y
  EXPECT_EQ(s.steps[2], 0);
  EXPECT_EQ(s.outputs & 1u, 1u);  // S-ON/OFF: SO, 1, 1
  EXPECT_EQ(s.state, MachineState::Idle);
  EXPECT_TRUE(rig.told.empty()) << rig.told.front();
  EXPECT_LT(pendant::XhcPendant::Clock::now() - t0, 30s);
}

}  // namespace
}  // namespace gantry::session
