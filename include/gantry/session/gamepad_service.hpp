// A gamepad on its own thread: found when it is plugged in (looked for every second), read,
// and its events sent on as the pendant's, with a held stick's report every 40 ms.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <thread>

#include "gantry/session/gamepad_pendant.hpp"  // GamepadBindings

namespace gantry::session {

class GamepadService {
 public:
  // `device`: "auto" (the first gamepad under `dir`) or a device path. `send`: each pendant
  // event, on this service's thread. `tell`: notes for the operator (found, unplugged, a
  // device that cannot be opened: once until it changes).
  GamepadService(std::string device, GamepadBindings bindings,
                 std::function<void(const PendantEvent&)> send,
                 std::function<void(const std::string&)> tell, std::string dir = "/dev/input");
  ~GamepadService();  // the thread ends within one poll (40 ms)
  GamepadService(const GamepadService&) = delete;
  GamepadService& operator=(const GamepadService&) = delete;

 private:
  void run();

  std::string device_, dir_;
  GamepadPendant pendant_;
  std::function<void(const PendantEvent&)> send_;
  std::function<void(const std::string&)> tell_;
  std::atomic<bool> quit_{false};
  std::thread thread_;
};

}  // namespace gantry::session
