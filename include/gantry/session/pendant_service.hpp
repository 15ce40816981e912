// The pendants of a live machine: the XHC USB pendant's driver on its own thread (found
// whenever it is plugged in), and the dead-man clock on another, so that a stalled USB read
// never keeps a jog going.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "gantry/machine/controller.hpp"         // Controller
#include "gantry/session/live_position.hpp"     // LivePosition
#include "gantry/session/pendant_input.hpp"     // PendantInput, PendantBindings
#include "gantry/session/pendant_xhc.hpp"       // XhcTranslator
#include "pendant/usb_port.hpp"                 // UsbPort
#include "pendant/xhc_pendant.hpp"              // XhcPendant

namespace gantry::session {

class PendantService : private pendant::XhcPendant::Listener {
 public:
  // `usb`: the USB port the XHC pendant is looked for on (null: none). `settings`: the values
  // in force (the display's units and frame). `tell`: notes for the operator (plugged in,
  // unplugged, a refusal, a missing permission).
  PendantService(Controller& c, std::function<Settings()> settings, PendantBindings bindings,
                 std::function<void(const std::string&)> tell,
                 std::unique_ptr<pendant::UsbPort> usb);
  ~PendantService() override;
  PendantService(const PendantService&) = delete;
  PendantService& operator=(const PendantService&) = delete;

  PendantInput& input() { return input_; }
  bool connected() const { return connected_; }

 private:
  void report(const pendant::XhcReport& r) override;
  void link(bool connected, const std::string& why) override;
  pendant::XhcDisplay display() override;

  Controller& c_;
  std::function<Settings()> settings_;
  std::function<void(const std::string&)> tell_;
  PendantInput input_;
  std::unique_ptr<pendant::UsbPort> usb_;
  std::unique_ptr<pendant::XhcPendant> xhc_;
  XhcTranslator translator_;  // the USB thread's
  LivePosition position_;     // the USB thread's
  std::atomic<bool> quit_{false}, connected_{false};
  std::thread usb_thread_, tick_thread_;
};

}  // namespace gantry::session
