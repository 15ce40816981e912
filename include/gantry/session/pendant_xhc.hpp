// The XHC WHB04B pendant's reports as pendant events (key presses, Fn combinations, the step
// and continuous modes, the wheel), and its display from the live machine's status.
#pragma once

#include <vector>

#include "gantry/machine/controller.hpp"      // ControllerStatus
#include "gantry/session/pendant_event.hpp"  // PendantEvent
#include "pendant/xhc_protocol.hpp"          // XhcReport, XhcDisplay

namespace gantry::session {

class XhcTranslator {
 public:
  // `machine`: the display starts in machine coordinates (the profile's
  // pendant.xhc_coordinates), else in work coordinates.
  explicit XhcTranslator(bool machine = false) : machine_(machine) {}
  // The events one report makes: the keys newly pressed (with Fn held: the macro printed
  // beside the key), the wheel's detents (Lead events with the feed knob at Lead), Lost when
  // the pendant goes to sleep. Macro-10 switches the display between work and machine
  // coordinates (as the pendant's documentation reserves it); Fn + Macro-10 is macro 10.
  std::vector<PendantEvent> events(const pendant::XhcReport& r);
  void reset();  // unplugged: nothing held

  bool step_mode() const { return step_mode_; }
  int axis() const { return axis_; }  // the axis knob's (-1: off)
  bool machine_coordinates() const { return machine_; }

 private:
  bool machine_ = false;
  bool step_mode_ = true;  // the safer mode until the operator picks continuous
  int axis_ = 0;
  pendant::XhcKey held1_ = pendant::XhcKey::None, held2_ = pendant::XhcKey::None;
};

// The display: the three axes of the selected group (X Y Z, or A B C when the knob is on A,
// B or C) at `at` (work coordinates, or machine ones when `machine`: the flag tells the
// display which it shows), the feed override in percent, the spindle's speed, the mode, and
// RESET while an E-stop waits.
pendant::XhcDisplay xhc_display(const ControllerStatus& s, const Vec6& at, bool step_mode,
                                int axis, bool machine = false);

}  // namespace gantry::session
