// "A motion ended since the last look", from the controller's activity counter: a front end
// that polls its status sees every end, even of a move that began and ended between two polls,
// and never waits for motion to see it.
#pragma once

#include <cstdint>

#include "gantry/machine/controller.hpp"  // ControllerStatus

namespace gantry::session {

class ActivityWatch {
 public:
  // True once for the look after one or more activities ended; the machine is then settled
  // (the status was read once the activity had come to rest or halted).
  bool ended(const ControllerStatus& st) {
    if (st.activities_ended == seen_) return false;
    seen_ = st.activities_ended;
    return true;
  }
  // From now on, only ends after `st` count.
  void seen(const ControllerStatus& st) { seen_ = st.activities_ended; }

 private:
  std::uint64_t seen_ = 0;
};

}  // namespace gantry::session
