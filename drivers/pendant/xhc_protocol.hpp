// The XHC WHB04B-4/-6 pendant's USB reports: the 8-byte input report decoded, the display
// report encoded (facts from LinuxCNC's xhc-whb04b-6 documentation; docs/hardware.md).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace gantry::pendant {

inline constexpr std::uint16_t kXhcVendor = 0x10ce;
inline constexpr std::uint16_t kXhcProduct = 0xeb93;  // wired and wireless dongle alike
inline constexpr std::uint8_t kInputReportId = 0x04;
inline constexpr std::uint8_t kDisplayReportId = 0x06;

// The key codes of the two key bytes.
enum class XhcKey : std::uint8_t {
  None = 0x00,
  Reset = 0x01,
  Stop = 0x02,
  StartPause = 0x03,
  FeedPlus = 0x04,
  FeedMinus = 0x05,
  SpindlePlus = 0x06,
  SpindleMinus = 0x07,
  MachineHome = 0x08,
  SafeZ = 0x09,
  WorkHome = 0x0a,
  SpindleOnOff = 0x0b,
  Fn = 0x0c,
  ProbeZ = 0x0d,
  Continuous = 0x0e,  // printed "MPG" or "Continuous": the wheel jogs continuously
  Step = 0x0f,        // the wheel jogs a step a detent
  Macro10 = 0x10,
};

// One input report as it came: two keys held, the two knobs, the wheel's detents since the
// last report.
struct XhcReport {
  std::uint8_t seed = 0;
  XhcKey key1 = XhcKey::None, key2 = XhcKey::None;
  std::uint8_t feed_knob = 0;  // 0x0d-0x10 step sizes / 2-30 %, 0x1a 60 %, 0x1b 100 %, 0x1c (0x9b) Lead
  std::uint8_t axis_knob = 0;  // 0x06 off, 0x11-0x16 X-C
  std::int8_t delta = 0;
  // The report a wireless pendant sends as it goes to sleep (both knobs read 0): it sends
  // nothing more until it wakes, so a jog must not wait for it.
  bool asleep() const { return feed_knob == 0 && axis_knob == 0; }
};

// The report, or nothing with the reason (not 8 bytes, not report 0x04, a key code unknown).
std::optional<XhcReport> decode_report(std::span<const std::uint8_t> bytes, std::string* why);

// The axis the axis knob selects: 0-5 (X, Y, Z, A, B, C), -1 when off or unknown.
int knob_axis(std::uint8_t code);

// What the feed knob's position means: in step mode a step length (0 at 60 %, 100 %, Lead:
// no step), in continuous mode a share of the jog speed in percent (0 at Lead).
struct FeedKnob {
  double step = 0;
  double percent = 0;
  bool lead = false;
};
FeedKnob feed_knob(std::uint8_t code);

// What the display shows. The mode's two bits pick the text beside the knob: "CONT xx%",
// "STP x.xxx", "MPG xx%", "xxx%".
struct XhcDisplay {
  enum class Mode : std::uint8_t { Continuous = 0, Step = 1, Mpg = 2, Percent = 3 };
  Mode mode = Mode::Continuous;
  bool reset = false;               // the RESET indicator (an E-stop waits for acknowledgement)
  bool work_coordinates = true;     // false: machine coordinates (the -6 shows X, not X1)
  std::array<double, 3> coordinates{};  // the three lines: X Y Z, or A B C on the -6
  std::uint16_t feed = 0;           // the feed override in percent
  std::uint16_t spindle = 0;        // the spindle speed (RPM)
  std::uint8_t seed = 0xfe;
};

// One coordinate as the display takes it: the whole part (16 bits, little-endian), then the
// fraction in ten-thousandths (15 bits) with the sign in the top bit. Beyond 65535.9999 the
// display shows its limit.
std::array<std::uint8_t, 4> encode_coordinate(double v);

// The display report: 21 bytes of data (header 0xfdfe, seed, flags, three coordinates, feed,
// spindle, a pad byte) sent as three 8-byte blocks, each led by the report id 0x06.
using DisplayBlock = std::array<std::uint8_t, 8>;
std::array<DisplayBlock, 3> encode_display(const XhcDisplay& d);

}  // namespace gantry::pendant
