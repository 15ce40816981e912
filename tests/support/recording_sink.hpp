// A motion sink for tests: keeps every canonical move, every settings change and the
// number of flushes, in order.
#pragma once

#include <vector>

#include "gantry/canon/canon_move.hpp"

namespace gantry {

class RecordingSink : public MotionSink {
 public:
  void move(const CanonMove& m) override { moves.push_back(m); }
  void flush() override { ++flushes; }
  void settings_changed(const Settings& s) override { changes.push_back(s); }

  std::vector<CanonMove> moves;
  std::vector<Settings> changes;  // what each settings_changed carried (VR, VU, VD ...)
  int flushes = 0;
};

}  // namespace gantry
