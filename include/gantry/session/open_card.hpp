// The card a run plays on: the simulated card, or real hardware when its driver is built in.
#pragma once

#include <memory>
#include <string>

#include "gantry/hal/card.hpp"           // Card
#include "gantry/settings/settings.hpp"  // Settings
#include "sim/sim_world.hpp"             // SimWorld

namespace gantry::session {

struct CardChoice {
  std::string type;       // "sim", "pci7200" or "gpiod"
  bool realtime = false;  // sim: play in wall-clock time
  SimWorld world;         // sim: switches, E-stop, stalls
  std::string trace;      // sim: pin trace file
};

// Whether a card of `type` plays in wall-clock time: real hardware, or the simulated card
// with --realtime. Someone may stand at the machine then (SW's warning is for them).
inline bool plays_in_real_time(const std::string& type, bool realtime) {
  return type != "sim" || realtime;
}

// nullptr with the reason (naming the fix) when the card cannot be opened.
std::unique_ptr<Card> open_card(const CardChoice& choice, const Settings& settings,
                                std::string* error);

}  // namespace gantry::session
