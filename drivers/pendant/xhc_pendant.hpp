// The XHC WHB04B pendant driver: finds the pendant (polling, so it may be plugged in and out at
// any time), reads its reports and refreshes its display, through the USB seam.
#pragma once

#include <chrono>
#include <string>

#include "pendant/usb_port.hpp"     // UsbPort
#include "pendant/xhc_protocol.hpp"  // XhcReport, XhcDisplay

namespace gantry::pendant {

class XhcPendant {
 public:
  using Clock = std::chrono::steady_clock;
  // Told on the caller's thread of poll().
  class Listener {
   public:
    virtual ~Listener() = default;
    virtual void report(const XhcReport& r) = 0;
    // Plugged in (connected) or gone: unplugged, the stream lost, or it cannot be opened
    // (`why` says which; an open refused for permission is told once, with the fix).
    virtual void link(bool connected, const std::string& why) = 0;
    virtual XhcDisplay display() = 0;  // what the display shows now
  };

  static constexpr auto kRetry = std::chrono::milliseconds(500);   // looking for a pendant
  static constexpr auto kRefresh = std::chrono::milliseconds(80);  // the display: 12.5 a second

  XhcPendant(UsbPort& port, Listener& listener) : port_(port), listener_(listener) {}
  ~XhcPendant() { port_.close(); }

  // One turn at time `now`: unplugged, look for the pendant (every kRetry); plugged in,
  // refresh the display when due, then wait up to `read_timeout_ms` for a report.
  void poll(Clock::time_point now, int read_timeout_ms);
  bool connected() const { return connected_; }

 private:
  void lost(const std::string& why);

  UsbPort& port_;
  Listener& listener_;
  bool connected_ = false;
  Clock::time_point next_open_{}, next_display_{};
  std::string told_;  // the last refusal told (each once)
  std::uint8_t seed_ = 0xfe;
};

// The message for a pendant found but not opened for permission: names the udev rule.
std::string permission_message(const std::string& device);

}  // namespace gantry::pendant
