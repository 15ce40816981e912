// What a terminal's key events mean for the keypad: a tap (one fixed step) or a held key
// (a continuous jog). A terminal sends a key once when it goes down, then repeats it after
// its repeat delay while it is held, and never says when it comes up (docs/console.md).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

namespace gantry::console {

class KeyTaps {
 public:
  using Clock = std::chrono::steady_clock;
  using ms = std::chrono::milliseconds;

  // `release`: no repeat for this long and the key is up (auto-repeats come every 30-50 ms,
  // faster than a hand taps). `repeat_delay`: the terminal's wait before it repeats a held
  // key; the same key again later than this is a new press.
  KeyTaps(ms release, ms repeat_delay) : release_(release), repeat_delay_(repeat_delay) {}

  enum class Meaning {
    Step,  // a press: one fixed step, now
    Wait,  // a second press or the terminal's first repeat: a step unless a repeat follows
    Held,  // a repeat within `release` of the last: the key is held
  };
  // The key `key` (any number naming a key and its modifiers) came at `now`.
  Meaning key(std::uint32_t key, Clock::time_point now);
  // A Wait that no repeat followed within `release`: true once, when it is due as a step.
  bool step_due(Clock::time_point now);
  // Whether key `key` still repeats at `now` (its last event within `release`).
  bool held(std::uint32_t key, Clock::time_point now) const;

 private:
  ms release_, repeat_delay_;
  struct Event {
    std::uint32_t key;
    Clock::time_point at;
  };
  std::optional<Event> last_;  // the last key event
  bool waiting_ = false;       // the last event was a Wait not yet decided
};

}  // namespace gantry::console
