// The XHC WHB04B pendant's reports: decoding the input report, encoding the display.
#include "pendant/xhc_protocol.hpp"

#include <cmath>

#include <fmt/format.h>

namespace gantry::pendant {
namespace {

bool known_key(std::uint8_t k) {
  return k <= static_cast<std::uint8_t>(XhcKey::Macro10);
}

void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v & 0xff);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}

}  // namespace

std::optional<XhcReport> decode_report(std::span<const std::uint8_t> b, std::string* why) {
  auto refuse = [&](std::string text) -> std::optional<XhcReport> {
    if (why) *why = std::move(text);
    return std::nullopt;
  };
  if (b.size() != 8) return refuse(fmt::format("a report of {} bytes (8 expected)", b.size()));
  if (b[0] != kInputReportId)
    return refuse(fmt::format("report id 0x{:02x} (0x{:02x} expected)", b[0], kInputReportId));
  if (!known_key(b[2]) || !known_key(b[3]))
    return refuse(fmt::format("unknown key code 0x{:02x}", known_key(b[2]) ? b[3] : b[2]));
  XhcReport r;
  r.seed = b[1];
  r.key1 = static_cast<XhcKey>(b[2]);
  r.key2 = static_cast<XhcKey>(b[3]);
  r.feed_knob = b[4];
  r.axis_knob = b[5];
  r.delta = static_cast<std::int8_t>(b[6]);
  // b[7], the checksum, is not checked: its rule is not known for key presses (the
  // documentation's finding); a report's other bytes are checked above.
  return r;
}

int knob_axis(std::uint8_t code) {
  return code >= 0x11 && code <= 0x16 ? code - 0x11 : -1;
}

FeedKnob feed_knob(std::uint8_t code) {
  switch (code) {
    case 0x0d: return {0.001, 2, false};
    case 0x0e: return {0.01, 5, false};
    case 0x0f: return {0.1, 10, false};
    case 0x10: return {1.0, 30, false};
    case 0x1a: return {0, 60, false};
    case 0x1b: return {0, 100, false};
    case 0x1c:
    case 0x9b: return {0, 0, true};  // some -4 and -6 units send 0x9b for Lead
    default: return {};
  }
}

std::array<std::uint8_t, 4> encode_coordinate(double v) {
  const bool negative = v < 0;
  double a = std::fabs(v);
  if (!std::isfinite(a) || a > 65535.9999) a = 65535.9999;
  const auto scaled = static_cast<std::uint32_t>(std::llround(a * 10000.0));
  const auto whole = static_cast<std::uint16_t>(scaled / 10000);
  // No "-0.0000": the sign only on what shows.
  const auto fraction =
      static_cast<std::uint16_t>(scaled % 10000 | (negative && scaled != 0 ? 0x8000 : 0));
  std::array<std::uint8_t, 4> out{};
  put16(&out[0], whole);
  put16(&out[2], fraction);
  return out;
}

std::array<DisplayBlock, 3> encode_display(const XhcDisplay& d) {
  std::array<std::uint8_t, 21> data{};
  put16(&data[0], 0xfdfe);
  data[2] = d.seed;
  data[3] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(d.mode) & 0x03) |
            (d.reset ? 0x40 : 0) | (d.work_coordinates ? 0x80 : 0);
  for (int i = 0; i < 3; ++i) {
    const auto c = encode_coordinate(d.coordinates[static_cast<std::size_t>(i)]);
    for (int k = 0; k < 4; ++k) data[static_cast<std::size_t>(4 + 4 * i + k)] = c[static_cast<std::size_t>(k)];
  }
  put16(&data[16], d.feed);
  put16(&data[18], d.spindle);
  std::array<DisplayBlock, 3> blocks{};
  for (std::size_t b = 0; b < 3; ++b) {
    blocks[b][0] = kDisplayReportId;
    for (std::size_t k = 0; k < 7; ++k) blocks[b][1 + k] = data[7 * b + k];
  }
  return blocks;
}

}  // namespace gantry::pendant
