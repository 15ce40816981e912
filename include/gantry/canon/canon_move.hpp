// Canonical moves: what the interpreter asks the machine to do, in machine units.
#pragma once

#include <array>
#include <optional>

#include "gantry/core/vec6.hpp"          // Vec6
#include "gantry/core/diagnostic.hpp"    // SourceLoc
#include "gantry/settings/settings.hpp"  // GroupSpeeds

namespace gantry {

// Line: a straight move. Arc: a circular move in `plane` (XY unless G-code's G18/G19 chose
// another) about `center`, through `sweep` radians (positive: counter-clockwise), the other
// axes moving in proportion (a helix). Dwell: a timed wait at rest. Stop: come to rest, then go on
// (MS and JS punctuate the moves around them this way). Output: at rest, switch output `output` on
// or off (SO). Independent: at rest, start (or end) an axis moving on its own beside the path (MI).
// SpindleSpeed: at rest, the spindle's speed output to `spindle_rpm` (TR).
enum class MoveKind { Line, Arc, Dwell, Stop, Output, Independent, SpindleSpeed };

// Move (cutting) speed or Jog (rapid) speed: the two speed sets of OpenSBP.
enum class SpeedClass { Move, Jog };

// The plane of an arc, named by its first and second axes; the sweep is counter-clockwise seen
// from the positive third axis (XY: Z, ZX: Y, YZ: X), as G-code's G17, G18 and G19 define.
enum class ArcPlane { XY, ZX, YZ };

// MI: one axis turning at a steady speed (an indexer) or oscillating, on its own, while the
// planned path moves the others. Neither: it comes to rest (off).
struct IndependentMotion {
  int axis = 4;          // 0 X .. 5 C (SB3's default: B)
  double speed = 0;      // turning: units/s, signed by direction; 0: not turning
  double accel = 0;      // turning: units/s^2, its ramps up and down
  double frequency = 0;  // oscillating: cycles/s; 0: not oscillating
  double travel = 0;     // oscillating: from the start point out and back, units, signed
  bool running() const { return speed != 0 || frequency != 0; }
};

// How far the file had run when a move was issued: statements executed and moves issued,
// this one counted. It rides with the move down to the step generator, so a run cut short
// reports what reached the card, not how far the interpreter had read ahead.
struct RunCount {
  std::size_t statements = 0, moves = 0;
};

struct CanonMove {
  MoveKind kind = MoveKind::Line;
  SpeedClass speed_class = SpeedClass::Move;
  Vec6 from = Vec6::Zero();
  Vec6 to = Vec6::Zero();
  GroupSpeeds speeds;  // the class's speeds in force when the move was issued
  // Arc: the centre of the circle along the plane's first and second axes: X, Y in the XY
  // plane (every OpenSBP arc); Z, X in ZX; Y, Z in YZ.
  double center_x = 0, center_y = 0;
  ArcPlane plane = ArcPlane::XY;  // Arc: the plane the circle lies in
  double sweep = 0;               // Arc: signed angle, radians; 2 pi is a full circle
  double dwell_s = 0;             // Dwell: how long the machine waits, s
  int output = 0;                 // Output: the switch, 1-based as SO numbers it
  bool keypad = false;            // a keypad jog: it ramps at VR's keypad ramp rate
  bool warning = false;           // Dwell: SW's warning before the run's first motion
  bool output_on = false;
  double spindle_rpm = 0;         // SpindleSpeed: the RPM TR asked for
  IndependentMotion independent;  // Independent: what the axis does from here on
  // Driver channels (bit k: channel k + 1) whose motors rest through this move while their
  // axis moves on its other channel: squaring a slaved axis at homing (docs/hardware.md).
  unsigned resting_channels = 0;
  SourceLoc loc;                  // the statement that asked for it
  RunCount count;                 // set by the interpreter as it issues the move
};

const char* kind_name(MoveKind k);
const char* speed_class_name(SpeedClass c);

// An input switch edge to watch for while moving (ON INPUT handlers, probes): switch
// `input` (1-12) closing or opening; `instant`: the pulses stop at the edge, otherwise the
// motion ramps down along the path. The interpreter asks for it through MachineLink; the
// machine arms it in order with the moves.
struct InputTrigger {
  int input = 0;
  bool closing = true;
  bool instant = false;
  int debounce = 1;  // the card's input samples in a row at the level (homing.debounce)
};

// What a file has set that changes how its moves are drawn, not how they run: the cutter
// (VC, an &Tool + C9 tool change, G-code's M6), the units its numbers are written in (VD,
// G-code's G20/G21) and the spindle speed (TR, S). A preview follows it (docs/preview.md).
struct DrawingState {
  double cutter_diameter = 0;        // VC's, in `units`
  int tool = 0;                      // the tool in the spindle (&Tool at C9, M6, M61); 0: none
  Units units = Units::Inches;       // of the canonical moves (VD's linear units)
  Units file_units = Units::Inches;  // the file's numbers (VD; G20/G21 in a G-code file)
  double spindle_rpm = 0;            // TR's
  int line = 0;                      // the statement it was seen at (not compared)
  bool same(const DrawingState& o) const {
    return cutter_diameter == o.cutter_diameter && tool == o.tool && units == o.units &&
           file_units == o.file_units && spindle_rpm == o.spindle_rpm;
  }
};

// Receives canonical moves in order. `flush` marks the end of the stream: nothing more will
// come, so everything buffered must be completed. The stream is one-way: what the live
// machine answers (where the tool is, its inputs, the keypad) reaches the interpreter through
// interp's MachineLink.
class MotionSink {
 public:
  virtual ~MotionSink() = default;
  virtual void move(const CanonMove& m) = 0;
  virtual void flush() = 0;
  // New values (VR ramps, VU steps per unit, VI channels) for the moves that follow; the
  // sender has brought the machine to rest just before (a Stop move).
  virtual void settings_changed(const Settings&) {}
  // The drawing state, before the first move and before each move it changed for (and at a
  // TR); nothing moves or rests for it. Only a preview takes it.
  virtual void drawing_changed(const DrawingState&) {}
};

}  // namespace gantry
