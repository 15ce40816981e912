// Where the tool is, as a console shows it: at rest, the interpreter's exact position; under
// way, the steps the card has played, in the working frame and units of the last snapshot.
#pragma once

#include <array>

#include "gantry/core/vec6.hpp"           // Vec6, kAxisCount
#include "gantry/interp/interpreter.hpp"  // ModalState
#include "gantry/machine/controller.hpp"  // ControllerStatus
#include "gantry/settings/settings.hpp"   // Settings, Units

namespace gantry::session {

class LivePosition {
 public:
  // At rest: the frame (where working 0 is), the exact position and the units.
  void snapshot(const ModalState& m, const Settings& s);
  // While moving: the played steps in the units and frame of the last snapshot.
  Vec6 from_steps(const ControllerStatus& st) const;
  // `rest`: the front end knows the machine is at rest, so the snapshot's position is exact.
  // As reported: a rotary axis with axes.<axis>.wrap modulo it.
  Vec6 at(const ControllerStatus& st, bool rest) const {
    return wrapped(rest ? position_ : from_steps(st));
  }
  Vec6 wrapped(Vec6 p) const;

  const Vec6& exact() const { return position_; }              // at the last snapshot
  Vec6 table_base() const { return position_ + table_zero_; }  // ... in table base coordinates

 private:
  Vec6 offset_ = Vec6::Zero();      // where working 0 is in the machine frame
  Vec6 position_ = Vec6::Zero();    // the interpreter's exact position
  Vec6 table_zero_ = Vec6::Zero();  // where working 0 is in table base coordinates
  std::array<double, kAxisCount> steps_per_unit_{};
  std::array<AxisSettings, kAxisCount> axes_{};  // their wrap
};

// A coordinate as shown: no "-0.0000".
inline double shown(double v) {
  return v < 5e-5 && v > -5e-5 ? 0.0 : v;
}

}  // namespace gantry::session
