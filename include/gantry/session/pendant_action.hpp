// The pendant's actions by name, as the profile's [pendant] bindings write them (keys, gamepad
// buttons): a button ("stop", "feed +", "macro 3"), a continuous jog ("jog x+", "jog z- 50%")
// or a step jog ("step y-", "step x+ 0.01").
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "gantry/session/pendant_event.hpp"  // PendantEvent

namespace gantry::session {

// A step jog's size when the binding gives none: VD's keypad step, read when it plays.
inline constexpr double kKeypadStep = -1;

// The event an action's name makes (case and spaces as written are forgiven): a Button, or a
// Wheel of one detent (`step` > 0 or kKeypadStep: a step jog; 0: a continuous jog at
// `percent`). nullopt when it is none.
std::optional<PendantEvent> pendant_action_named(std::string_view name);

// The action's name as pendant_action_named reads it back ("stop", "macro 3", "jog z- 50%",
// "step x+ 0.25", "step y+" for VD's keypad step): what the front ends' help lists for a
// bound key. "" for an event no binding makes (Lost, Release, Lead).
std::string pendant_action_text(const PendantEvent& e);

// The actions, for messages: "reset", "stop", ... "macro 1" to "macro 10", "jog x+", "step x+".
std::string pendant_action_names();

}  // namespace gantry::session
