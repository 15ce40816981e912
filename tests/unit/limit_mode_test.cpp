// Limit modes on the simulated card: any limit switch that closes stops the card, or with
// limits.travel_only only one whose axis travels towards it (WinCNC's lim_mode 1).
#include <gtest/gtest.h>

#include "segment_builders.hpp"

#include <string>

#include "gantry/settings/settings.hpp"
#include "gantry/step/step_generator.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::segment;
using test::vec;

// X runs 1 in at 1 in/s; Y's min switch (input bit 4) closes 0.3 s in, Y at rest (a switch
// knocked, a wire picking up noise). Returns the card's fault.
CardFault y_switch_closes_while_x_runs(bool travel_only, SimWorld w = {}) {
  Settings s = default_settings();
  s.limits.travel_only = travel_only;
  w.input_events.push_back({0.3, s.inputs.min_bit[1], true});
  SimCard card(s, false, w);
  card.start(s.card.pacer_hz());
  StepGenerator gen(s, card);
  try {
    gen.segment(segment(vec(0), vec(1.0), 0, 1, 0, 10));
    gen.flush();
  } catch (const GantryError&) {
  }
  return card.fault();
}

TEST(LimitMode, AnyLimitSwitchThatClosesStopsTheCardByDefault) {
  EXPECT_EQ(y_switch_closes_while_x_runs(false), CardFault::Limit);
}

TEST(LimitMode, TravelOnlyIgnoresTheSwitchOfAnAxisNotTravellingTowardsIt) {
  EXPECT_EQ(y_switch_closes_while_x_runs(true), CardFault::None);
}

TEST(LimitMode, TravelOnlyStillStopsOnTheSwitchTheAxisRunsInto) {
  SimWorld w;
  w.max_switch[0] = 0.5;  // X's own max switch, on its way
  EXPECT_EQ(y_switch_closes_while_x_runs(true, w), CardFault::Limit);
}

TEST(LimitMode, TravelOnlyIsAnOptionalProfileKey) {
  const SettingsLoad plain = parse_settings(default_profile_text(), "p.toml");
  ASSERT_TRUE(plain.ok());
  EXPECT_FALSE(plain.settings.limits.travel_only);
  const SettingsLoad with =
      parse_settings(default_profile_text() + "\n[limits]\ntravel_only = true\n", "p.toml");
  ASSERT_TRUE(with.ok()) << with.errors[0].message;
  EXPECT_TRUE(with.settings.limits.travel_only);
}

}  // namespace
}  // namespace gantry
