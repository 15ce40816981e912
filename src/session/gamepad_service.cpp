// The gamepad's thread: find, open, poll, translate; an unplugged gamepad ends its jog.
#include "gantry/session/gamepad_service.hpp"

#include <poll.h>

#include <chrono>

#include "gamepad/evdev_gamepad.hpp"  // EvdevGamepad

namespace gantry::session {

GamepadService::GamepadService(std::string device, GamepadBindings bindings,
                               std::function<void(const PendantEvent&)> send,
                               std::function<void(const std::string&)> tell, std::string dir)
    : device_(std::move(device)),
      dir_(std::move(dir)),
      pendant_(std::move(bindings)),
      send_(std::move(send)),
      tell_(std::move(tell)) {
  thread_ = std::thread([this] { run(); });
}

GamepadService::~GamepadService() {
  quit_ = true;
  thread_.join();
}

void GamepadService::run() {
  using Clock = std::chrono::steady_clock;
  constexpr auto kRepeat = std::chrono::milliseconds(GamepadPendant::kRepeatMs);
  constexpr auto kLookAgain = std::chrono::seconds(1);
  std::unique_ptr<EvdevGamepad> pad;
  std::string last_error;
  auto next_look = Clock::now();
  auto next_repeat = Clock::now();
  std::vector<GamepadEvent> in;
  std::vector<PendantEvent> out;
  auto send = [&] {
    for (const auto& e : out) send_(e);
    out.clear();
  };
  while (!quit_) {
    if (!pad) {
      if (Clock::now() < next_look) {
        std::this_thread::sleep_for(kRepeat);
        continue;
      }
      next_look = Clock::now() + kLookAgain;
      std::string path = device_;
      if (device_ == "auto") {
        const auto found = EvdevGamepad::find(dir_);
        if (found.empty()) continue;
        path = found.front();
      }
      std::string error;
      pad = EvdevGamepad::open(path, &error);
      if (!pad) {
        if (error != last_error && tell_) tell_(error);
        last_error = error;
        continue;
      }
      last_error.clear();
      if (tell_) tell_("gamepad " + pad->name() + " on " + pad->path() + ": ready to jog");
      continue;
    }
    pollfd p{pad->fd(), POLLIN, 0};
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next_repeat -
                                                                            Clock::now());
    poll(&p, 1, static_cast<int>(std::max<long>(0, wait.count())));
    if (p.revents) {
      in.clear();
      const bool alive = pad->read(in);
      for (const auto& e : in) pendant_.event(e, out);
      send();
      if (!alive) {
        if (tell_) tell_("gamepad " + pad->name() + " unplugged: its jog stopped");
        pad.reset();
        next_look = Clock::now() + kLookAgain;
        continue;
      }
    }
    if (Clock::now() >= next_repeat) {
      pendant_.tick(out);
      send();
      next_repeat = Clock::now() + kRepeat;
    }
  }
}

}  // namespace gantry::session
