// Limit modes on the simulated card: any limit switch that closes stops the card, or with
// limits.travel_only only one whose axis travels towards it (WinCNC's lim_mode 1).
#include <gtest/gtest.h>

#include "segment_builders.hpp"

#include <cmath>
#include <cstdint>
#include <string>

#include "gantry/settings/settings.hpp"
#include "gantry/step/step_generator.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using test::segment;
using test::vec;

// X runs 1 in at 1 in/s on a card in that world, until it ends or the card faults.
void run_x_one_inch(const Settings& s, SimCard& card) {
  card.start(s.card.pacer_hz());
  StepGenerator gen(s, card);
  try {
    gen.segment(segment(vec(0), vec(1.0), 0, 1, 0, 10));
    gen.flush();
  } catch (const GantryError&) {
  }
}

// X runs 1 in at 1 in/s; Y's min switch (input bit 4) closes 0.3 s in, Y at rest (a switch
// knocked, a wire picking up noise). Returns the card's fault.
CardFault y_switch_closes_while_x_runs(bool travel_only, SimWorld w = {}) {
  Settings s = default_settings();
  s.limits.travel_only = travel_only;
  w.input_events.push_back({0.3, s.inputs.min_bit[1], true});
  SimCard card(s, false, w);
  run_x_one_inch(s, card);
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

// Y's min switch reads active from 0.3 s for `words` pacer ticks (forever: 0), X running.
struct Spike {
  CardFault fault;
  std::uint64_t played;  // ticks the card played
  std::uint64_t at;      // the tick the input went active
};
Spike y_spike(int debounce, std::uint64_t words) {
  Settings s = default_settings();
  s.limits.debounce = debounce;
  const double tick = 1 / s.card.pacer_hz();
  SimWorld w;
  w.input_events.push_back({0.3, s.inputs.min_bit[1], true});
  if (words > 0)
    w.input_events.push_back({0.3 + static_cast<double>(words) * tick, s.inputs.min_bit[1], false});
  SimCard card(s, false, w);
  run_x_one_inch(s, card);
  return {card.fault(), card.ticks_played(), static_cast<std::uint64_t>(std::llround(0.3 / tick))};
}

TEST(LimitMode, ADebouncedLimitIgnoresASpikeShorterThanItsCount) {
  EXPECT_EQ(y_spike(1, 2).fault, CardFault::Limit);  // no debounce: any spike stops it
  EXPECT_EQ(y_spike(3, 2).fault, CardFault::None);   // 2 words < 3
  EXPECT_EQ(y_spike(3, 3).fault, CardFault::Limit);  // 3 words: it counts
}

TEST(LimitMode, ADebouncedLimitStopsTheCardOnceItsCountOfWordsHasPlayed) {
  const Spike none = y_spike(1, 0), five = y_spike(5, 0);
  EXPECT_EQ(none.fault, CardFault::Limit);
  EXPECT_EQ(five.fault, CardFault::Limit);
  EXPECT_EQ(none.played, none.at);      // at once: the word at the edge does not play
  EXPECT_EQ(five.played, five.at + 5);  // the five words it read active played
}

TEST(LimitMode, DebounceIsAnOptionalProfileKeyOfAtMost30) {
  EXPECT_EQ(parse_settings(default_profile_text(), "p.toml").settings.limits.debounce, 1);
  const SettingsLoad with =
      parse_settings(default_profile_text() + "\n[limits]\ndebounce = 30\n", "p.toml");
  ASSERT_TRUE(with.ok()) << with.errors[0].message;
  EXPECT_EQ(with.settings.limits.debounce, 30);
  EXPECT_FALSE(
      parse_settings(default_profile_text() + "\n[limits]\ndebounce = 31\n", "p.toml").ok());
}

}  // namespace
}  // namespace gantry
