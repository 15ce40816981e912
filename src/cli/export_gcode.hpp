// `gantry export-gcode`: any program's canonical moves written as plain G-code.
#pragma once

#include <string>

#include "gantry/canon/canon_move.hpp"  // MotionSink, CanonMove

namespace gantry {

// Writes each move as it comes (docs/gcode.md, "Exporting"): G90 with the coordinates of the
// machine's frame, G20 or G21 as the machine's units (and again when a run changes them), F
// in units per minute, arcs as G2/G3 with incremental centre offsets in their plane, dwells
// as G4 P seconds, stops as G4 P0, output switches as M64/M65 P<switch>.
class GcodeWriter : public MotionSink {
 public:
  GcodeWriter(const Settings& settings, const std::string& source);
  void move(const CanonMove& m) override;
  void flush() override {}
  void settings_changed(const Settings& s) override;
  // The program, ended with M2.
  std::string finish();

 private:
  void units(Units u);
  std::string axes(const Vec6& to, bool all);

  std::string out_;
  Units units_;
  Vec6 at_ = Vec6::Zero();  // the last position written
  bool started_ = false;
  double feed_ = -1;  // the last F written, units/min
  int plane_ = -1;    // the last G17/G18/G19 written
};

}  // namespace gantry
