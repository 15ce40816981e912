// Run under umockdev (tests/gamepad_umockdev.sh): finds the emulated gamepad, opens it and
// prints each event as the bindings would see it, until `count` events or two quiet seconds.
#include <poll.h>

#include <cstdio>
#include <cstdlib>

#include "gamepad/evdev_gamepad.hpp"

int main(int argc, char** argv) {
  using namespace gantry;
  const int count = argc > 1 ? std::atoi(argv[1]) : 0;
  const auto found = EvdevGamepad::find();
  for (const auto& p : found) std::printf("found %s\n", p.c_str());
  if (found.empty()) return 1;
  std::string error;
  auto pad = EvdevGamepad::open(found.front(), &error);
  if (!pad) {
    std::printf("%s\n", error.c_str());
    return 1;
  }
  std::printf("name %s\n", pad->name().c_str());
  int seen = 0;
  std::vector<GamepadEvent> events;
  while (seen < count) {
    pollfd p{pad->fd(), POLLIN, 0};
    if (poll(&p, 1, 2000) <= 0) break;
    events.clear();
    const bool alive = pad->read(events);
    for (const auto& e : events) {
      std::printf("%s %g\n", code_name(e.kind, e.code).c_str(), e.value);
      ++seen;
    }
    if (!alive) break;
  }
  return 0;
}
