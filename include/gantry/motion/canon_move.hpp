// Canonical moves: what the interpreter asks the machine to do, in machine units.
#pragma once

#include "gantry/core/axes.hpp"          // Vec6
#include "gantry/core/diagnostic.hpp"    // SourceLoc
#include "gantry/settings/settings.hpp"  // GroupSpeeds

namespace gantry {

// Line: a straight move. Arc: a circular move in the XY plane about `center`, through
// `sweep` radians (positive: counter-clockwise), the other axes moving in proportion (a
// helix). Dwell: a timed wait at rest. Stop: come to rest, then go on (MS and JS punctuate
// the moves around them this way). Output: at rest, switch output `output` on or off (SO).
enum class MoveKind { Line, Arc, Dwell, Stop, Output };

// Move (cutting) speed or Jog (rapid) speed: the two speed sets of OpenSBP.
enum class SpeedClass { Move, Jog };

struct CanonMove {
  MoveKind kind = MoveKind::Line;
  SpeedClass speed_class = SpeedClass::Move;
  Vec6 from = Vec6::Zero();
  Vec6 to = Vec6::Zero();
  GroupSpeeds speeds;                 // the class's speeds in force when the move was issued
  double center_x = 0, center_y = 0;  // Arc: the centre of the circle
  double sweep = 0;                   // Arc: signed angle, radians; 2 pi is a full circle
  double dwell_s = 0;                 // Dwell: how long the machine waits, s
  int output = 0;                     // Output: the switch, 1-based as SO numbers it
  bool keypad = false;  // a keypad jog: it ramps at VR's keypad ramp rate
  bool output_on = false;
  SourceLoc loc;  // the statement that asked for it
};

const char* kind_name(MoveKind k);
const char* speed_class_name(SpeedClass c);

// Receives canonical moves in order. `flush` marks the end of the stream: nothing more will
// come, so everything buffered must be completed.
class MotionSink {
 public:
  virtual ~MotionSink() = default;
  virtual void move(const CanonMove& m) = 0;
  virtual void flush() = 0;
  // New values (VR ramps, VU steps per unit, VI channels) for the moves that follow; the
  // sender has brought the machine to rest just before (a Stop move).
  virtual void settings_changed(const Settings&) {}
};

}  // namespace gantry
