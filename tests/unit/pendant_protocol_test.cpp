// The XHC WHB04B pendant without hardware: its reports decoded, its display encoded (golden
// bytes worked out by hand from the documented layout), and the driver's loop through a fake
// USB port playing recorded report sequences (hot plug, unplug, a missing permission).
#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "gantry/session/pendant_xhc.hpp"
#include "pendant/xhc_pendant.hpp"
#include "pendant/xhc_protocol.hpp"
#include "pendant_bench.hpp"  // report

namespace gantry::pendant {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(PendantProtocol, DecodesARecordedReport) {
  // Feed knob at 0.01 (0x0e), axis knob on Y (0x12), RESET held, the wheel 3 detents back.
  const Bytes b{0x04, 0x82, 0x01, 0x00, 0x0e, 0x12, 0xfd, 0x81};
  std::string why;
  const auto r = decode_report(b, &why);
  ASSERT_TRUE(r) << why;
  EXPECT_EQ(r->seed, 0x82);
  EXPECT_EQ(r->key1, XhcKey::Reset);
  EXPECT_EQ(r->key2, XhcKey::None);
  EXPECT_EQ(knob_axis(r->axis_knob), 1);
  EXPECT_DOUBLE_EQ(feed_knob(r->feed_knob).step, 0.01);
  EXPECT_DOUBLE_EQ(feed_knob(r->feed_knob).percent, 5);
  EXPECT_EQ(r->delta, -3);
  EXPECT_FALSE(r->asleep());
}

TEST(PendantProtocol, RefusesMalformedReportsSayingWhy) {
  std::string why;
  EXPECT_FALSE(decode_report(Bytes{0x04, 0, 0, 0}, &why));
  EXPECT_EQ(why, "a report of 4 bytes (8 expected)");
  EXPECT_FALSE(decode_report(Bytes{0x05, 0, 0, 0, 0x0e, 0x11, 0, 0}, &why));
  EXPECT_EQ(why, "report id 0x05 (0x04 expected)");
  EXPECT_FALSE(decode_report(Bytes{0x04, 0, 0x3f, 0, 0x0e, 0x11, 0, 0}, &why));
  EXPECT_EQ(why, "unknown key code 0x3f");
}

TEST(PendantProtocol, KnobsMeanWhatTheirPrintSays) {
  EXPECT_EQ(knob_axis(0x06), -1);  // OFF
  EXPECT_EQ(knob_axis(0x11), 0);
  EXPECT_EQ(knob_axis(0x16), 5);  // C
  EXPECT_DOUBLE_EQ(feed_knob(0x0d).step, 0.001);
  EXPECT_DOUBLE_EQ(feed_knob(0x10).step, 1.0);
  EXPECT_DOUBLE_EQ(feed_knob(0x1a).step, 0);  // 60 %: no step size
  EXPECT_DOUBLE_EQ(feed_knob(0x1a).percent, 60);
  EXPECT_DOUBLE_EQ(feed_knob(0x1b).percent, 100);
  EXPECT_TRUE(feed_knob(0x1c).lead);
}

// -12.3456: whole part 12 = 0x000c; fraction 3456 = 0x0d80, sign bit 0x8000 -> 0x8d80; each
// 16-bit field little-endian.
TEST(PendantProtocol, EncodesACoordinateAsTheDisplayReadsIt) {
  EXPECT_EQ(encode_coordinate(-12.3456), (std::array<std::uint8_t, 4>{0x0c, 0x00, 0x80, 0x8d}));
  EXPECT_EQ(encode_coordinate(0.5), (std::array<std::uint8_t, 4>{0x00, 0x00, 0x88, 0x13}));
  EXPECT_EQ(encode_coordinate(100.0001), (std::array<std::uint8_t, 4>{0x64, 0x00, 0x01, 0x00}));
  EXPECT_EQ(encode_coordinate(-0.00004), (std::array<std::uint8_t, 4>{0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(encode_coordinate(1e9), (std::array<std::uint8_t, 4>{0xff, 0xff, 0x0f, 0x27}));
}

// The 21 data bytes: fe fd (header 0xfdfe), seed, flags (step mode 1 | work coordinates 0x80),
// X -12.3456, Y 0.5, Z 100.0001, feed 100 % (0x0064), spindle 12000 (0x2ee0), a pad byte;
// cut in sevens, each block led by report id 0x06.
TEST(PendantProtocol, EncodesTheDisplayInThreeBlocks) {
  XhcDisplay d;
  d.mode = XhcDisplay::Mode::Step;
  d.work_coordinates = true;
  d.coordinates = {-12.3456, 0.5, 100.0001};
  d.feed = 100;
  d.spindle = 12000;
  d.seed = 0xfe;
  const auto blocks = encode_display(d);
  EXPECT_EQ(blocks[0], (DisplayBlock{0x06, 0xfe, 0xfd, 0xfe, 0x81, 0x0c, 0x00, 0x80}));
  EXPECT_EQ(blocks[1], (DisplayBlock{0x06, 0x8d, 0x00, 0x00, 0x88, 0x13, 0x64, 0x00}));
  EXPECT_EQ(blocks[2], (DisplayBlock{0x06, 0x01, 0x00, 0x64, 0x00, 0xe0, 0x2e, 0x00}));
  d.mode = XhcDisplay::Mode::Continuous;
  d.work_coordinates = false;
  d.reset = true;
  EXPECT_EQ(encode_display(d)[0][4], 0x40);
}

// A USB port playing a recording: each open() and read() takes the next answer.
class RecordedPort final : public UsbPort {
 public:
  struct Read {
    Status status = Status::Timeout;
    Bytes bytes;
  };
  std::deque<std::pair<Status, std::string>> opens;
  std::deque<Read> reads;
  std::vector<Bytes> written;
  int closes = 0;
  bool open_now = false;

  Status open(std::uint16_t vendor, std::uint16_t product, std::string* why) override {
    EXPECT_EQ(vendor, 0x10ce);
    EXPECT_EQ(product, 0xeb93);
    if (opens.empty()) return Status::NoDevice;
    auto [st, text] = opens.front();
    opens.pop_front();
    *why = text;
    open_now = st == Status::Ok;
    return st;
  }
  Status read(std::span<std::uint8_t> buf, int* got, int) override {
    if (reads.empty()) return Status::Timeout;
    Read r = reads.front();
    reads.pop_front();
    std::copy(r.bytes.begin(), r.bytes.end(), buf.begin());
    *got = static_cast<int>(r.bytes.size());
    return r.status;
  }
  Status write(std::span<const std::uint8_t> block) override {
    written.emplace_back(block.begin(), block.end());
    return open_now ? Status::Ok : Status::NoDevice;
  }
  void close() override {
    ++closes;
    open_now = false;
  }
};

struct Listener final : XhcPendant::Listener {
  std::vector<XhcReport> reports;
  std::vector<std::pair<bool, std::string>> links;
  int displays = 0;
  void report(const XhcReport& r) override { reports.push_back(r); }
  void link(bool c, const std::string& why) override { links.emplace_back(c, why); }
  XhcDisplay display() override {
    ++displays;
    return {};
  }
};

TEST(PendantDriver, FindsThePendantWhenPluggedInReadsItsReportsAndSeesItUnplugged) {
  RecordedPort port;
  Listener l;
  XhcPendant p(port, l);
  using namespace std::chrono_literals;
  XhcPendant::Clock::time_point t{};
  p.poll(t, 10);  // nothing plugged in: silence
  EXPECT_TRUE(l.links.empty());
  port.opens.push_back({UsbPort::Status::Ok, ""});
  p.poll(t + 100ms, 10);  // too soon to look again
  EXPECT_FALSE(p.connected());
  p.poll(t + 500ms, 10);
  ASSERT_TRUE(p.connected());
  ASSERT_EQ(l.links.size(), 1u);
  EXPECT_TRUE(l.links[0].first);
  port.reads.push_back({UsbPort::Status::Ok, {0x04, 0x10, 0x00, 0x00, 0x0e, 0x11, 0x02, 0x10}});
  port.reads.push_back({UsbPort::Status::Ok, {0x04, 0x11}});  // short: dropped
  port.reads.push_back({UsbPort::Status::NoDevice, {}});
  for (int k = 0; k < 3; ++k) p.poll(t + 510ms + k * 10ms, 10);
  ASSERT_EQ(l.reports.size(), 1u);
  EXPECT_EQ(l.reports[0].delta, 2);
  EXPECT_FALSE(p.connected());
  ASSERT_EQ(l.links.size(), 2u);
  EXPECT_EQ(l.links[1], std::make_pair(false, std::string("the pendant was unplugged")));
  EXPECT_GE(port.closes, 1);
}

TEST(PendantDriver, RefreshesTheDisplayAtLeastTenTimesASecond) {
  RecordedPort port;
  port.opens.push_back({UsbPort::Status::Ok, ""});
  Listener l;
  XhcPendant p(port, l);
  using namespace std::chrono_literals;
  XhcPendant::Clock::time_point t{};
  for (int ms = 0; ms < 1000; ms += 10) p.poll(t + std::chrono::milliseconds(ms), 10);
  EXPECT_GE(l.displays, 10);
  EXPECT_EQ(port.written.size(), 3u * static_cast<std::size_t>(l.displays));
  for (const Bytes& b : port.written) {
    ASSERT_EQ(b.size(), 8u);
    EXPECT_EQ(b[0], 0x06);
  }
}

TEST(PendantDriver, AMissingPermissionIsToldOnceNamingTheUdevRule) {
  RecordedPort port;
  for (int k = 0; k < 3; ++k)
    port.opens.push_back({UsbPort::Status::Denied, "/dev/bus/usb/001/004: Access denied"});
  Listener l;
  XhcPendant p(port, l);
  using namespace std::chrono_literals;
  XhcPendant::Clock::time_point t{};
  for (int k = 0; k < 3; ++k) p.poll(t + k * 600ms, 10);
  ASSERT_EQ(l.links.size(), 1u);
  const std::string& why = l.links[0].second;
  EXPECT_NE(why.find("/dev/bus/usb/001/004"), std::string::npos) << why;
  EXPECT_NE(why.find("/etc/udev/rules.d"), std::string::npos) << why;
  EXPECT_NE(why.find("70-gantry-pendant.rules"), std::string::npos) << why;
  EXPECT_NE(why.find("udevadm control --reload-rules"), std::string::npos) << why;
}

}  // namespace
}  // namespace gantry::pendant

namespace gantry::session {
namespace {

using pendant::XhcKey;
using pendant::XhcReport;

TEST(PendantXhc, AKeyActsOnceWhenPressedAndFnMakesItAMacro) {
  XhcTranslator t;
  auto e = t.events(report(XhcKey::Stop, XhcKey::None, 0x0e, 0x11, 0));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].kind, PendantEvent::Kind::Button);
  EXPECT_EQ(e[0].button, PendantButton::Stop);
  EXPECT_TRUE(t.events(report(XhcKey::Stop, XhcKey::None, 0x0e, 0x11, 0)).empty());  // held
  EXPECT_TRUE(t.events(report(XhcKey::None, XhcKey::None, 0x0e, 0x11, 0)).empty());  // let go
  EXPECT_TRUE(t.events(report(XhcKey::Fn, XhcKey::None, 0x0e, 0x11, 0)).empty());
  e = t.events(report(XhcKey::Fn, XhcKey::SafeZ, 0x0e, 0x11, 0));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].button, PendantButton::Macro);
  EXPECT_EQ(e[0].macro, 6);
  e = t.events(report(XhcKey::Fn, XhcKey::Stop, 0x0e, 0x11, 0));  // a stop stays a stop
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].button, PendantButton::Stop);
  // Macro-10 alone switches the display between work and machine coordinates (as the
  // pendant's documentation reserves it); with Fn it is macro 10.
  EXPECT_TRUE(t.events(report(XhcKey::Macro10, XhcKey::None, 0x0e, 0x11, 0)).empty());
  EXPECT_TRUE(t.machine_coordinates());
  EXPECT_TRUE(t.events(report(XhcKey::Fn, XhcKey::None, 0x0e, 0x11, 0)).empty());
  e = t.events(report(XhcKey::Fn, XhcKey::Macro10, 0x0e, 0x11, 0));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].macro, 10);
}

TEST(PendantXhc, TheWheelStepsOrJogsContinuouslyByTheMode) {
  XhcTranslator t;
  EXPECT_TRUE(t.step_mode());
  auto e = t.events(report(XhcKey::None, XhcKey::None, 0x0f, 0x13, 4));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].kind, PendantEvent::Kind::Wheel);
  EXPECT_EQ(e[0].axis, 2);
  EXPECT_EQ(e[0].delta, 4);
  EXPECT_DOUBLE_EQ(e[0].step, 0.1);
  EXPECT_TRUE(t.events(report(XhcKey::None, XhcKey::None, 0x1b, 0x13, 4)).empty());  // 100 %
  EXPECT_TRUE(t.events(report(XhcKey::Continuous, XhcKey::None, 0x1a, 0x11, 0)).empty());
  EXPECT_FALSE(t.step_mode());
  e = t.events(report(XhcKey::None, XhcKey::None, 0x1a, 0x11, -1));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_DOUBLE_EQ(e[0].step, 0);
  EXPECT_DOUBLE_EQ(e[0].percent, 60);
  EXPECT_EQ(e[0].delta, -1);
  EXPECT_TRUE(t.events(report(XhcKey::None, XhcKey::None, 0x1a, 0x06, 3)).empty());  // OFF
  e = t.events(report(XhcKey::None, XhcKey::None, 0, 0, 0));  // the wireless one sleeps
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].kind, PendantEvent::Kind::Lost);
}

TEST(PendantXhc, TheDisplayShowsTheSelectedGroupTheOverrideAndTheSpindle) {
  ControllerStatus s;
  s.feed_override = 1.2;
  s.spindle_rpm = 18000;
  Vec6 work;
  work << 1, 2, 3, 4, 5, 6;
  pendant::XhcDisplay d = xhc_display(s, work, true, 0);
  EXPECT_EQ(d.coordinates, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(d.feed, 120);
  EXPECT_EQ(d.spindle, 18000);
  EXPECT_EQ(d.mode, pendant::XhcDisplay::Mode::Step);
  EXPECT_FALSE(d.reset);
  s.state = MachineState::EStop;
  d = xhc_display(s, work, false, 4);
  EXPECT_EQ(d.coordinates, (std::array<double, 3>{4, 5, 6}));
  EXPECT_TRUE(d.reset);
  EXPECT_EQ(d.mode, pendant::XhcDisplay::Mode::Continuous);
}

}  // namespace
}  // namespace gantry::session
