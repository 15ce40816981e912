// The XHC WHB04B pendant driver's loop: hot plug by polling, reports in, the display out.
#include "pendant/xhc_pendant.hpp"

#include <array>

#include <fmt/format.h>

namespace gantry::pendant {

std::string permission_message(const std::string& device) {
  return fmt::format(
      "the XHC pendant (USB {:04x}:{:04x}) is plugged in but this user may not open it ({}). "
      "Install the udev rule Gantry ships: sudo cp 70-gantry-pendant.rules /etc/udev/rules.d/ "
      "(from /usr/lib/udev/rules.d or the source's packaging/), then sudo udevadm control "
      "--reload-rules and plug the pendant in again (docs/hardware.md)",
      kXhcVendor, kXhcProduct, device);
}

void XhcPendant::lost(const std::string& why) {
  port_.close();
  connected_ = false;
  next_open_ = {};
  listener_.link(false, why);
}

void XhcPendant::poll(Clock::time_point now, int read_timeout_ms) {
  if (!connected_) {
    if (now < next_open_) return;
    next_open_ = now + kRetry;
    std::string why;
    const UsbPort::Status st = port_.open(kXhcVendor, kXhcProduct, &why);
    if (st == UsbPort::Status::Ok) {
      connected_ = true;
      told_.clear();
      next_display_ = now;
      listener_.link(true, "");
    } else if (st != UsbPort::Status::NoDevice) {
      const std::string text = st == UsbPort::Status::Denied
                                   ? permission_message(why)
                                   : fmt::format("the XHC pendant cannot be opened: {}", why);
      if (text != told_) listener_.link(false, text);
      told_ = text;
    }
    return;
  }
  if (now >= next_display_) {
    next_display_ = now + kRefresh;
    XhcDisplay d = listener_.display();
    d.seed = seed_;
    // A display block refused is only a stale display; the input reports decide whether the
    // pendant is still there (a wireless dongle without its pendant refuses them).
    for (const DisplayBlock& b : encode_display(d))
      if (port_.write(b) == UsbPort::Status::NoDevice) return lost("the pendant was unplugged");
  }
  std::array<std::uint8_t, 8> buf{};
  int got = 0;
  const UsbPort::Status st = port_.read(buf, &got, read_timeout_ms);
  if (st == UsbPort::Status::Ok) {
    std::string why;
    if (auto r = decode_report(std::span(buf.data(), static_cast<std::size_t>(got)), &why))
      listener_.report(*r);
  } else if (st != UsbPort::Status::Timeout) {
    lost(st == UsbPort::Status::NoDevice ? "the pendant was unplugged"
                                         : "the pendant's report stream was lost");
  }
}

}  // namespace gantry::pendant
