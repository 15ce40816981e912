// The window keypad's tap-or-hold rule in continuous mode: a press is one step of the keypad
// step, a key or button held past a threshold jogs until it is let go (docs/console.md,
// "Taps and held keys"). Nothing here draws or moves: the window asks it what to do.
#pragma once

#include <chrono>

namespace gantry::ui {

class JogPress {
 public:
  using Clock = std::chrono::steady_clock;
  // Held longer than this, a press becomes a continuous jog: UGS's jog buttons' long press
  // and GNOME's key repeat delay, so the window does what the terminal does at its usual
  // repeat delay; a tap (a key or a click, 50 to 200 ms) is well inside it.
  static constexpr std::chrono::milliseconds kHold{500};

  explicit JogPress(Clock::duration hold = kHold) : hold_(hold) {}

  // Key or button `id` went down at `now`: its one step is due now (the caller jogs it). Any
  // press before forgets the one before (another key is a press of its own).
  void press(int id, Clock::time_point now);
  // Each frame: true once, when the key still down has been held past the threshold and the
  // machine is at rest (`at_rest`: the press's step has played): start the continuous jog.
  bool start_continuous(Clock::time_point now, bool at_rest);
  // Key or button `id` went up: true when it holds a continuous jog, which is to be released
  // (a tap's step plays to its end).
  bool release(int id);
  // The jog is over or was refused (a stop, an E-stop, the soft limit): forget the press.
  void reset() { id_ = -1, continuous_ = false; }

  int id() const { return id_; }                   // the key held (-1: none)
  bool continuous() const { return continuous_; }  // ... and its continuous jog started

 private:
  Clock::duration hold_;
  int id_ = -1;
  Clock::time_point pressed_at_;
  bool continuous_ = false;
};

}  // namespace gantry::ui
