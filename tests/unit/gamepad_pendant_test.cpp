// A gamepad as a pendant: the bindings from the profile's texts, and the pendant events its
// sticks and buttons make (a held stick repeats, a let-go stick releases at once).
#include <gtest/gtest.h>
#include <linux/input-event-codes.h>

#include "gantry/session/gamepad_pendant.hpp"

namespace gantry::session {
namespace {

using Kind = PendantEvent::Kind;

GamepadEvent stick(int code, double v) { return {GamepadEvent::Kind::Axis, code, v}; }
GamepadEvent press(int code, bool down = true) {
  return {GamepadEvent::Kind::Button, code, down ? 1.0 : 0.0};
}

std::vector<PendantEvent> feed(GamepadPendant& g, const GamepadEvent& e) {
  std::vector<PendantEvent> out;
  g.event(e, out);
  return out;
}

TEST(GamepadPendant, AStickPushedJogsItsAxisAtOnceAtItsDeflectionAndRepeatsWhileHeld) {
  GamepadPendant g(GamepadBindings::usual());
  auto out = feed(g, stick(ABS_Y, -0.5));  // the left stick pushed half way up: Y+
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, Kind::Wheel);
  EXPECT_EQ(out[0].axis, 1);
  EXPECT_EQ(out[0].delta, 1);
  EXPECT_EQ(out[0].step, 0);  // continuous
  EXPECT_EQ(out[0].percent, 50);
  EXPECT_TRUE(feed(g, stick(ABS_Y, -0.6)).empty());  // further: the same jog
  std::vector<PendantEvent> held;
  g.tick(held);
  ASSERT_EQ(held.size(), 1u);
  EXPECT_EQ(held[0].kind, Kind::Wheel);
  EXPECT_EQ(held[0].percent, 60);
  out = feed(g, stick(ABS_Y, 0));  // let go
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, Kind::Release);
  held.clear();
  g.tick(held);
  EXPECT_TRUE(held.empty());  // nothing keeps a jog alive now
}

TEST(GamepadPendant, TheMostPushedStickWinsAndAChangeOfAxisOrWayReleasesFirst) {
  GamepadPendant g(GamepadBindings::usual());
  feed(g, stick(ABS_X, 0.3));
  auto out = feed(g, stick(ABS_RY, -0.9));  // the right stick up, further: Z+
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].kind, Kind::Release);
  EXPECT_EQ(out[1].axis, 2);
  EXPECT_EQ(out[1].delta, 1);
  out = feed(g, stick(ABS_RY, 0.95));  // pulled down: Z-, the other way
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].kind, Kind::Release);
  EXPECT_EQ(out[1].delta, -1);
  out = feed(g, stick(ABS_HAT0X, -1));  // the hat left, full: X- beats Z's 0.95
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].axis, 0);
  EXPECT_EQ(out[1].delta, -1);
  EXPECT_EQ(out[1].percent, 100);
  EXPECT_TRUE(feed(g, stick(ABS_Z, 1)).empty());  // a trigger bound to nothing
}

TEST(GamepadPendant, ButtonsPressOnPressOnlyAndLostEndsEverything) {
  GamepadPendant g(GamepadBindings::usual());
  auto out = feed(g, press(BTN_EAST));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, Kind::Button);
  EXPECT_EQ(out[0].button, PendantButton::Stop);
  EXPECT_TRUE(feed(g, press(BTN_EAST, false)).empty());
  EXPECT_TRUE(feed(g, press(BTN_NORTH)).empty());  // not bound in the usual layout
  feed(g, stick(ABS_X, 1));
  out = feed(g, {GamepadEvent::Kind::Lost, 0, 0});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, Kind::Lost);
  std::vector<PendantEvent> held;
  g.tick(held);
  EXPECT_TRUE(held.empty());
}

TEST(GamepadBindingsText, TheProfilesTextsBindSticksAndButtons) {
  std::string error;
  auto b = GamepadBindings::parse({"abs_rx", "-ABS_RY, ABS_HAT0Y", "none", "", "", ""},
                                  "BTN_START = start/pause, BTN_NORTH=macro 3, btn_west = safe Z",
                                  &error);
  ASSERT_TRUE(b) << error;
  ASSERT_EQ(b->jog[0].size(), 1u);
  EXPECT_EQ(b->jog[0][0].code, ABS_RX);
  ASSERT_EQ(b->jog[1].size(), 2u);
  EXPECT_TRUE(b->jog[1][0].invert);
  EXPECT_FALSE(b->jog[1][1].invert);
  EXPECT_TRUE(b->jog[2].empty());  // none: Z is not jogged from the gamepad
  EXPECT_EQ(b->buttons.size(), 3u);
  EXPECT_EQ(b->buttons.at(BTN_NORTH).button, PendantButton::Macro);
  EXPECT_EQ(b->buttons.at(BTN_NORTH).macro, 3);
  EXPECT_EQ(b->buttons.at(BTN_WEST).button, PendantButton::SafeZ);
  EXPECT_FALSE(b->buttons.contains(BTN_EAST));  // a button list replaces the usual one
}

TEST(GamepadBindingsText, ABadNameOrActionSaysWhichAndWhatIsAllowed) {
  std::string error;
  EXPECT_FALSE(GamepadBindings::parse({"ABS_Q", "", "", "", "", ""}, "", &error));
  EXPECT_NE(error.find("pendant.gamepad_x: \"ABS_Q\" is not a stick axis"), std::string::npos)
      << error;
  EXPECT_FALSE(GamepadBindings::parse({}, "BTN_SOUTH = fly", &error));
  EXPECT_NE(error.find("\"BTN_SOUTH = fly\" needs an action"), std::string::npos) << error;
  EXPECT_NE(error.find("\"macro 1\" to \"macro 10\""), std::string::npos) << error;
  EXPECT_FALSE(GamepadBindings::parse({}, "BTN_SOUTH = macro 11", &error));
  EXPECT_FALSE(GamepadBindings::parse({}, "BTN_SOUTH", &error));
  EXPECT_FALSE(GamepadBindings::parse({}, "KEY_A = stop", &error));
  EXPECT_NE(error.find("\"KEY_A\" is not a button"), std::string::npos) << error;
}

}  // namespace
}  // namespace gantry::session
