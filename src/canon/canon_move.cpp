// Names of move kinds and speed classes, as reports and `gantry moves` print them.
#include "gantry/canon/canon_move.hpp"

namespace gantry {

const char* kind_name(MoveKind k) {
  switch (k) {
    case MoveKind::Dwell:
      return "dwell";
    case MoveKind::Line:
      return "line";
    case MoveKind::Arc:
      return "arc";
    case MoveKind::Stop:
      return "stop";
    case MoveKind::Output:
      return "output";
    case MoveKind::Independent:
      return "independent";
    case MoveKind::SpindleSpeed:
      return "spindle_speed";
  }
  return "?";
}

const char* speed_class_name(SpeedClass c) {
  return c == SpeedClass::Move ? "move" : "jog";
}

}  // namespace gantry
