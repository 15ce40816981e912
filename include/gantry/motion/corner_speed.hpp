// How fast the tool may pass from one straight move into the next: the speed laws of the
// planner's modes. docs/planner.md derives each.
#pragma once

#include "gantry/core/vec6.hpp"          // Vec6
#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

// The two moves meeting at a junction, as the corner laws see them.
struct Junction {
  Vec6 u_in, u_out;                  // unit directions of the incoming and outgoing moves
  Vec6 u_in_long;                    // sb3: incoming direction over the last min_distance of path
  double v_in = 0, v_out = 0;        // their cruise speeds (path speed limits), units/s
  double rest_in = 0, rest_out = 0;  // speeds each may start or stop at (see rest_speed)
  double len_in = 0, len_out = 0;    // their lengths, units
  double a_in = 0, a_out = 0;        // their accelerations along the path, units/s^2
  bool jog_in = false, jog_out = false;
  bool punctuated = false;  // an MS or JS between them: always a full ramp
};

// The largest path speed v at which no axis changes speed by more than its corner jump
// (planner.corner_jump x max_speed) when the direction changes from u_in to u_out:
// max_i v |u_out_i - u_in_i| <= J_i. From rest, pass u_in = 0.
double jump_limited_speed(const Vec6& u_in, const Vec6& u_out, const Settings& s);

// The speed a move may start from or stop at: SB3 starts and ends every ramp at the ramp
// speed (VR, of the move's class, along the path, and within the corner jump); the junction
// and stop modes start from rest.
double rest_speed(const Vec6& unit, bool jog, const Settings& s);

// The largest path speed at which a move along `u_out` may start from rest when the axes
// stopped at velocities `stopped` (units/s, each within its corner jump) and have rested
// `rest_s` seconds since: the stop's jump and the start's together stay within the corner
// jump, plus what each axis could accelerate over the rest (derivation in the .cpp).
double start_after_stop(const Vec6& stopped, const Vec6& u_out, double rest_s, const Settings& s);

// The largest speed through the junction in the settings' planner mode, never above either
// move's cruise speed. Every mode also keeps each axis's speed change within its corner jump
// and, on a polyline that approximates a curve, the centripetal acceleration within the
// axes' limits.
double corner_speed(const Junction& j, const Settings& s);

// SB3's criterion angle at path speed v (radians): a change of direction larger than this
// slows the tool. 0.75 rad (43 deg) and above always ramps fully; below it the criterion
// falls as 1/v through SB3's stated point (5 deg at 10 in/s).
double sb3_criterion_angle(double v, const Settings& s);

}  // namespace gantry
