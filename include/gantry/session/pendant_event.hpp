// What a pendant says, whatever it is (the XHC USB pendant, keys, a gamepad): jog wheel
// detents, its buttons, and the loss of its link.
#pragma once

#include <cstdint>
#include <string_view>

namespace gantry::session {

enum class PendantButton : std::uint8_t {
  Reset,         // acknowledge an E-stop
  Stop,
  StartPause,    // pause a running file, resume a paused one (or close SK's keypad)
  FeedPlus,
  FeedMinus,
  SpindlePlus,
  SpindleMinus,
  MachineHome,   // C3
  SafeZ,         // Z up to the safe height (VC)
  WorkHome,      // JH: safe Z, then X and Y to working 0
  SpindleOnOff,  // output 1
  ProbeZ,        // C2: zero Z on the plate
  Macro,         // macros 1-10: what the profile binds (a custom cut, a part file)
};

std::string_view button_name(PendantButton b);

struct PendantEvent {
  enum class Kind : std::uint8_t {
    Wheel,   // detents turned (or a continuous jog's key held: one report each turn)
    Button,  // pressed
    Lost,    // unplugged, or its stream stopped: a jog it started stops at once
    Release,  // a continuous jog's key or stick let go: the jog ends at once
    Lead,     // the XHC wheel with the feed knob at Lead: `delta` detents of the spindle speed
  };
  Kind kind = Kind::Wheel;
  // Wheel: the axis (0-5), the detents (signed), and the mode: step > 0 moves that length a
  // detent (a negative step: VD's keypad step); step 0 jogs continuously at `percent` of the
  // jog speed while reports come.
  int axis = 0;
  int delta = 0;
  double step = 0;
  double percent = 100;
  // Button.
  PendantButton button = PendantButton::Reset;
  int macro = 0;  // 1-10 (Macro)
};

}  // namespace gantry::session
