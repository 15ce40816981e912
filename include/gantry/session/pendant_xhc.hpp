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
  // The events one report makes: the keys newly pressed (with Fn held: the macro printed
  // beside the key), the wheel's detents, Lost when the pendant goes to sleep.
  std::vector<PendantEvent> events(const pendant::XhcReport& r);
  void reset();  // unplugged: nothing held

  bool step_mode() const { return step_mode_; }
  int axis() const { return axis_; }  // the axis knob's (-1: off)

 private:
  bool step_mode_ = true;  // the safer mode until the operator picks continuous
  int axis_ = 0;
  pendant::XhcKey held1_ = pendant::XhcKey::None, held2_ = pendant::XhcKey::None;
};

// The display: the three axes of the selected group (X Y Z, or A B C when the knob is on A,
// B or C) in work coordinates (`work`, else `machine`), the feed override in percent, the
// spindle's speed, the mode, and RESET while an E-stop waits.
pendant::XhcDisplay xhc_display(const ControllerStatus& s, const Vec6& work, bool step_mode,
                                int axis);

}  // namespace gantry::session
