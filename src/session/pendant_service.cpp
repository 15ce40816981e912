// The live machine's pendants: the XHC pendant's thread and the dead-man clock's.
#include "gantry/session/pendant_service.hpp"

#include <chrono>

namespace gantry::session {

PendantService::PendantService(Controller& c, std::function<Settings()> settings,
                               PendantBindings bindings,
                               std::function<void(const std::string&)> tell,
                               std::unique_ptr<pendant::UsbPort> usb)
    : c_(c),
      settings_(std::move(settings)),
      tell_(std::move(tell)),
      input_(c, settings_(), std::move(bindings), PendantInput::Clock::now, tell_),
      usb_(std::move(usb)),
      translator_(settings_().pendant.xhc_coordinates == "machine") {
  tick_thread_ = std::thread([this] {
    while (!quit_) {
      input_.tick();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  if (!usb_) return;
  xhc_ = std::make_unique<pendant::XhcPendant>(*usb_, static_cast<Listener&>(*this));
  usb_thread_ = std::thread([this] {
    while (!quit_) {
      xhc_->poll(pendant::XhcPendant::Clock::now(), 10);
      if (!xhc_->connected()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
}

PendantService::~PendantService() {
  quit_ = true;
  if (usb_thread_.joinable()) usb_thread_.join();
  if (tick_thread_.joinable()) tick_thread_.join();
  xhc_.reset();
  input_.handle({.kind = PendantEvent::Kind::Lost});  // nothing of ours keeps moving
}

void PendantService::report(const pendant::XhcReport& r) {
  for (const PendantEvent& e : translator_.events(r)) input_.handle(e);
}

void PendantService::link(bool connected, const std::string& why) {
  connected_ = connected;
  if (!connected) {
    translator_.reset();
    input_.handle({.kind = PendantEvent::Kind::Lost});
  }
  if (tell_) tell_(connected ? std::string("the XHC pendant is connected") : why);
}

pendant::XhcDisplay PendantService::display() {
  const ControllerStatus s = c_.status();
  const bool machine = translator_.machine_coordinates();
  if (s.settled && !machine) position_.snapshot(c_.modal(), settings_());
  return xhc_display(s, machine ? s.machine : position_.at(s, s.settled), translator_.step_mode(),
                     translator_.axis(), machine);
}

}  // namespace gantry::session
