// The evdev gamepad: normalised sticks, the decoder's events (a lost report ends everything),
// the profile's code names, and the messages when a device cannot be used.
#include <gtest/gtest.h>

#include "gamepad/evdev_gamepad.hpp"

namespace gantry {
namespace {

input_event ev(int type, int code, int value) {
  input_event e{};
  e.type = static_cast<__u16>(type);
  e.code = static_cast<__u16>(code);
  e.value = value;
  return e;
}

TEST(GamepadAxis, CentreIsRestAndTheEndsAreFull) {
  const AxisRange r{-32768, 32767, 0};
  EXPECT_EQ(normalised_axis(0, r), 0);
  EXPECT_DOUBLE_EQ(normalised_axis(32767, r), 1);
  EXPECT_DOUBLE_EQ(normalised_axis(-32768, r), -1);
  EXPECT_DOUBLE_EQ(normalised_axis(99999, r), 1);  // a reading past the range is clamped
}

TEST(GamepadAxis, TheDeadZoneIsTheWiderOfFlatAndSixPercentAndMotionRisesFromZero) {
  const AxisRange byte{0, 255, 0};                     // centre 127.5, half 127.5
  EXPECT_EQ(normalised_axis(128, byte), 0);            // 0.4 % off centre
  EXPECT_EQ(normalised_axis(135, byte), 0);            // 5.9 %
  EXPECT_GT(normalised_axis(136, byte), 0);            // 6.7 %: just past the band
  EXPECT_LT(normalised_axis(136, byte), 0.01);         // and barely moving
  const AxisRange flat{-100, 100, 20};                 // the device says 20 % is rest
  EXPECT_EQ(normalised_axis(-20, flat), 0);
  EXPECT_DOUBLE_EQ(normalised_axis(60, flat), 0.5);    // (0.6 - 0.2) / 0.8
  EXPECT_DOUBLE_EQ(normalised_axis(-60, flat), -0.5);
  const AxisRange hat{-1, 1, 0};
  EXPECT_EQ(normalised_axis(1, hat), 1);
  EXPECT_EQ(normalised_axis(-1, hat), -1);
  EXPECT_EQ(normalised_axis(0, hat), 0);
  EXPECT_EQ(normalised_axis(5, AxisRange{3, 3, 0}), 0);  // no range: nothing moves
}

TEST(GamepadDecoder, ButtonsPressAndReleaseAndAutoRepeatSaysNothing) {
  EvdevDecoder d;
  auto press = d.decode(ev(EV_KEY, BTN_SOUTH, 1));
  ASSERT_TRUE(press);
  EXPECT_EQ(press->kind, GamepadEvent::Kind::Button);
  EXPECT_EQ(press->code, BTN_SOUTH);
  EXPECT_EQ(press->value, 1);
  EXPECT_FALSE(d.decode(ev(EV_KEY, BTN_SOUTH, 2)));
  EXPECT_FALSE(d.decode(ev(EV_SYN, SYN_REPORT, 0)));
  auto release = d.decode(ev(EV_KEY, BTN_SOUTH, 0));
  ASSERT_TRUE(release);
  EXPECT_EQ(release->value, 0);
  EXPECT_FALSE(d.decode(ev(EV_REL, REL_X, 3)));  // a mouse's motion is not ours
}

TEST(GamepadDecoder, AStickUsesItsRangeAndJitterInsideTheDeadZoneSaysNothing) {
  EvdevDecoder d;
  d.set_range(ABS_X, {0, 255, 0});
  auto full = d.decode(ev(EV_ABS, ABS_X, 255));
  ASSERT_TRUE(full);
  EXPECT_EQ(full->kind, GamepadEvent::Kind::Axis);
  EXPECT_EQ(full->code, ABS_X);
  EXPECT_DOUBLE_EQ(full->value, 1);
  EXPECT_FALSE(d.decode(ev(EV_ABS, ABS_X, 255)));  // unchanged
  auto rest = d.decode(ev(EV_ABS, ABS_X, 128));
  ASSERT_TRUE(rest);
  EXPECT_EQ(rest->value, 0);
  EXPECT_FALSE(d.decode(ev(EV_ABS, ABS_X, 126)));  // jitter at rest
  EXPECT_FALSE(d.decode(ev(EV_ABS, ABS_X, 130)));
  // An axis with no range read from the device takes the common signed 16-bit one.
  auto y = d.decode(ev(EV_ABS, ABS_Y, -32768));
  ASSERT_TRUE(y);
  EXPECT_DOUBLE_EQ(y->value, -1);
}

TEST(GamepadDecoder, DroppedEventsReadAsLostAndTheBrokenReportIsIgnored) {
  EvdevDecoder d;
  d.set_range(ABS_X, {-100, 100, 0});
  ASSERT_TRUE(d.decode(ev(EV_ABS, ABS_X, 100)));
  auto lost = d.decode(ev(EV_SYN, SYN_DROPPED, 0));
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->kind, GamepadEvent::Kind::Lost);
  // Until the next SYN_REPORT the kernel's report is incomplete: nothing of it counts.
  EXPECT_FALSE(d.decode(ev(EV_KEY, BTN_EAST, 1)));
  EXPECT_FALSE(d.decode(ev(EV_ABS, ABS_X, 50)));
  EXPECT_FALSE(d.decode(ev(EV_SYN, SYN_REPORT, 0)));
  // Then a stick still held where it was is sent again: the Lost ended its jog.
  auto again = d.decode(ev(EV_ABS, ABS_X, 100));
  ASSERT_TRUE(again);
  EXPECT_DOUBLE_EQ(again->value, 1);
}

TEST(GamepadCodes, TheKernelsNamesBothWaysWithNumbersForTheRest) {
  EXPECT_EQ(button_code("BTN_SOUTH"), BTN_SOUTH);
  EXPECT_EQ(button_code("BTN_A"), BTN_SOUTH);  // the same code, the older name
  EXPECT_EQ(button_code("BTN_START"), BTN_START);
  EXPECT_EQ(axis_code("ABS_HAT0X"), ABS_HAT0X);
  EXPECT_EQ(axis_code("ABS_RX"), ABS_RX);
  EXPECT_EQ(code_name(GamepadEvent::Kind::Button, BTN_SOUTH), "BTN_SOUTH");
  EXPECT_EQ(code_name(GamepadEvent::Kind::Axis, ABS_HAT0Y), "ABS_HAT0Y");
  EXPECT_EQ(code_name(GamepadEvent::Kind::Button, 0x2c0), "BTN_704");  // BTN_TRIGGER_HAPPY1
  EXPECT_EQ(button_code("BTN_704"), 0x2c0);
  EXPECT_FALSE(button_code("ABS_X"));
  EXPECT_FALSE(button_code("BTN_"));
  EXPECT_FALSE(button_code("BTN_12x"));
  EXPECT_FALSE(axis_code("ABS_999"));  // past ABS_MAX
  EXPECT_FALSE(axis_code("x"));
}

TEST(GamepadDevice, AMissingDeviceAndANonInputFileSayWhatIsWrong) {
  std::string error;
  EXPECT_FALSE(EvdevGamepad::open("/nonexistent/event9", &error));
  EXPECT_NE(error.find("/nonexistent/event9"), std::string::npos) << error;
  EXPECT_NE(error.find("plugged in"), std::string::npos) << error;
  EXPECT_FALSE(EvdevGamepad::open("/dev/null", &error));
  EXPECT_NE(error.find("/dev/null is not a gamepad"), std::string::npos) << error;
  EXPECT_TRUE(EvdevGamepad::find("/nonexistent").empty());
}

}  // namespace
}  // namespace gantry
