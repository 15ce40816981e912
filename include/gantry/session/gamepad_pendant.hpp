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
  std::map<int, PendantEvent> buttons;    // BTN_* -> the pendant action it presses
  // A hat's way pressed as a button ({ABS_HAT0X, +1} -> "step x+"): a D-pad that reports as a
  // hat steps exactly (that hat then jogs no more as a stick).
  std::map<std::pair<int, int>, PendantEvent> hats;

  // The usual layout: the left stick and the hat jog X and Y, the right stick Z; A start/pause,
  // B stop, the shoulder buttons feed - and +, Select reset. Nothing that starts motion by
  // itself (homing, probing, macros) is bound unless the profile says so.
  static GamepadBindings usual();
  // From the profile's texts: `jog[i]` "ABS_X, -ABS_HAT0X"; `buttons` "BTN_SOUTH = start/pause,
  // BTN_TL = macro 3, BTN_DPAD_UP = step y+, ABS_HAT0X+ = step x+ 0.01" (any pendant action,
  // pendant_action.hpp). Empty texts keep the usual binding. nullopt with `error` naming the bad
  // item and what is allowed.
  static std::optional<GamepadBindings> parse(const std::array<std::string, 6>& jog,
                                              const std::string& buttons, std::string* error);
};

class GamepadPendant {
 public:
  // A held stick says so this often, well inside the dead-man time (PendantInput::kDeadMan).
  static constexpr int kRepeatMs = 40;

  explicit GamepadPendant(GamepadBindings b) : b_(std::move(b)) {}
  // The pendant events a gamepad event makes: a stick pushed from rest, or to another axis or
  // way, starts a jog at once; let go, it ends at once (Release); a button (or a hat's way
  // bound as one) pressed: its action, a button bound to a continuous jog jogs while held.
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

  void press(int code, bool down, const PendantEvent& action, std::vector<PendantEvent>& out);

  GamepadBindings b_;
  std::map<int, double> sticks_;  // last value of each bound stick
  std::map<int, int> hat_way_;    // each hat bound as buttons: its way (-1, 0, 1)
  Jog jog_;
  int held_ = -1;                 // the code of a button held that jogs continuously
  PendantEvent held_jog_;
};

}  // namespace gantry::session
