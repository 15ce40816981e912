// A gamepad as a pendant: its sticks and hat jog continuously, at a speed set by how far they
// are pushed, and its buttons press the pendant's buttons, as the profile's [pendant] section
// binds them.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gamepad/gamepad_event.hpp"         // GamepadEvent
#include "gantry/session/pendant_event.hpp"  // PendantEvent

namespace gantry::session {

struct GamepadBindings {
  struct Stick {
    int code = 0;         // ABS_*
    bool invert = false;  // a stick pushed up reads negative: "-ABS_Y" jogs Y+ when pushed up
  };
  std::array<std::vector<Stick>, 6> jog;  // per machine axis X Y Z A B C
  std::map<int, PendantEvent> buttons;    // BTN_* -> the pendant button it presses

  // The usual layout: the left stick and the hat jog X and Y, the right stick Z; A start/pause,
  // B stop, the shoulder buttons feed - and +, Select reset. Nothing that starts motion by
  // itself (homing, probing, macros) is bound unless the profile says so.
  static GamepadBindings usual();
  // From the profile's texts: `jog[i]` "ABS_X, -ABS_HAT0X"; `buttons` "BTN_SOUTH = start/pause,
  // BTN_TL = macro 3". Empty texts keep the usual binding. nullopt with `error` naming the bad
  // item and what is allowed.
  static std::optional<GamepadBindings> parse(const std::array<std::string, 6>& jog,
                                              const std::string& buttons, std::string* error);
};

// One pendant event from an action's name: "stop", "feed +", "macro 3" (nullopt: not one).
std::optional<PendantEvent> pendant_button_named(std::string_view name);

class GamepadPendant {
 public:
  // A held stick says so this often, well inside the dead-man time (PendantInput::kDeadMan).
  static constexpr int kRepeatMs = 40;

  explicit GamepadPendant(GamepadBindings b) : b_(std::move(b)) {}
  // The pendant events a gamepad event makes: a stick pushed from rest, or to another axis or
  // way, starts a jog at once; let go, it ends at once (Release); a button pressed.
  void event(const GamepadEvent& e, std::vector<PendantEvent>& out);
  // Every kRepeatMs: the held stick's report, which keeps its jog alive.
  void tick(std::vector<PendantEvent>& out);

 private:
  struct Jog {
    int axis = -1;  // none
    int dir = 0;
    double percent = 0;
  };
  Jog chosen() const;  // the most deflected bound stick

  GamepadBindings b_;
  std::map<int, double> sticks_;  // last value of each bound stick
  Jog jog_;
};

}  // namespace gantry::session
