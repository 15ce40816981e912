// Keys of the console and the window as a pendant: the profile's [pendant] keys bind a key's
// name ("F5", "Ctrl+Right", "a") to a pendant action, and both front ends send the events a
// bound key makes to the same PendantInput (the dead-man rule included).
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/session/pendant_event.hpp"  // PendantEvent

namespace gantry::session {

// A key's name as the bindings and the front ends write it: the modifiers Ctrl+, Alt+, Shift+
// in that order, then a printable character ("a", "A", "+") or a named key (Space, Enter, Tab,
// Backspace, Delete, Insert, Left, Right, Up, Down, Home, End, PageUp, PageDown, Escape,
// F1-F12). `text` as the profile writes it (any case for the names and modifiers; Esc, PgUp,
// PgDn, Return, Del, Ins, Control are understood); nullopt, with `why`, when it is not one or
// is an E-stop key (Ctrl+C and ! at the console, F12 in the window), which no binding may take.
std::optional<std::string> key_name(std::string_view text, std::string* why);

class KeyBindings {
 public:
  struct Problem {
    std::size_t item;     // the index of the profile's item
    std::string message;  // what is wrong
  };
  // From the profile's items, "KEY = action" each; a bad item is a problem and is left out.
  static KeyBindings parse(const std::vector<std::string>& items, std::vector<Problem>* problems);

  const PendantEvent* find(const std::string& key) const;
  bool empty() const { return keys_.empty(); }
  const std::map<std::string, PendantEvent>& all() const { return keys_; }

 private:
  std::map<std::string, PendantEvent> keys_;
};

// The pendant events a front end's keys make. A terminal sends no key release, only repeats:
// a continuous jog's key sends a wheel report each time it arrives and the pendant's dead-man
// rule (100 ms) ends the jog once the repeats stop; any other binding acts once per press, its
// repeats (the same key again within `repeat_gap`) ignored. A window knows presses, repeats
// and releases: a held jog key reports every 40 ms (tick) and its release ends the jog at once.
class KeyPendant {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr auto kRepeat = std::chrono::milliseconds(40);

  explicit KeyPendant(KeyBindings b, Clock::duration repeat_gap = std::chrono::milliseconds(600))
      : b_(std::move(b)), gap_(repeat_gap) {}

  // A key arrived (a terminal: a press or a repeat, it cannot tell). True when it is bound: the
  // front end then does nothing else with it.
  bool key(const std::string& name, Clock::time_point now, std::vector<PendantEvent>& out);
  // A window's press (`repeat`: the system's key repeat) and release.
  bool press(const std::string& name, bool repeat, Clock::time_point now,
             std::vector<PendantEvent>& out);
  bool release(const std::string& name, std::vector<PendantEvent>& out);
  // A window's held jog key: its report when due.
  void tick(Clock::time_point now, std::vector<PendantEvent>& out);

  const KeyBindings& bindings() const { return b_; }

 private:
  static bool continuous(const PendantEvent& e) {
    return e.kind == PendantEvent::Kind::Wheel && e.step == 0;
  }
  KeyBindings b_;
  Clock::duration gap_;
  std::string last_;  // the terminal's last bound key, and when it came
  Clock::time_point last_at_{};
  std::string held_;  // the window's held continuous jog key
  Clock::time_point next_report_{};
};

}  // namespace gantry::session
