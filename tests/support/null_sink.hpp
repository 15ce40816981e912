// A motion sink for tests and fuzz targets that keeps nothing.
#pragma once

#include "gantry/canon/canon_move.hpp"

namespace gantry {

class NullSink : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

}  // namespace gantry
