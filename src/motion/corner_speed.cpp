// Junction speed laws: SB3's ramp model, junction deviation, and the two physical bounds
// every mode obeys (the corner jump and the chord acceleration). Derivations: docs/planner.md.
#include "gantry/motion/corner_speed.hpp"

#include <algorithm>  // min, max, clamp
#include <cmath>      // sqrt, acos, hypot, copysign
#include <limits>     // infinity
#include <span>

#include "gantry/motion/path_limits.hpp"  // limit_along, nominal_path_speed

namespace gantry {
namespace {

constexpr double kFullRampAngle = 0.75;  // rad (43 deg): SB3 always ramps fully beyond it

// limit_along for a direction over the six axes.
double along(const Vec6& d, const std::array<double, kAxisCount>& limit) {
  return limit_along(std::span<const double>(d.data(), kAxisCount), limit);
}

// Angle between the XY projections of two directions; 0 when either has no XY part.
double xy_angle(const Vec6& a, const Vec6& b) {
  const double na = std::hypot(a[0], a[1]), nb = std::hypot(b[0], b[1]);
  if (na < 1e-9 || nb < 1e-9) return 0;
  return std::acos(std::clamp((a[0] * b[0] + a[1] * b[1]) / (na * nb), -1.0, 1.0));
}

// SB3: full ramp, graded slow corner, or none; and the 3D rule on Z, A, B, C speed changes.
double sb3_corner(const Junction& j, const Settings& s, double v, double full) {
  if (j.jog_in || j.jog_out) return full;  // SB3 ramps down and up around every jog
  const GroupSpeeds& rs = s.ramps.move_ramp_speed;
  const double group_ramp[kAxisCount] = {0, 0, rs.z, rs.a, rs.b, rs.c};
  for (int i = 2; i < kAxisCount; ++i) {
    const double change = std::abs(j.v_out * j.u_out[i] - j.v_in * j.u_in[i]);
    if (change > group_ramp[i] * s.ramps.threshold_3d / 100) return full;
  }
  // The turn over the last min_distance of path catches a curve of tiny segments; the turn
  // at the corner itself still counts when a short move comes before it (the longer check
  // adds ramping, never removes it: §8 fact 138).
  const double theta = std::max(xy_angle(j.u_in_long, j.u_out), xy_angle(j.u_in, j.u_out));
  if (theta >= kFullRampAngle) return full;
  const double criterion = sb3_criterion_angle(v, s);
  if (theta < criterion) return v;
  // From the slow corner speed at the criterion down to the full ramp at 0.75 rad.
  const double slow = v * s.ramps.slow_corner / 100;
  const double f = (kFullRampAngle - theta) / (kFullRampAngle - criterion);
  return std::max(full, full + (slow - full) * f);
}

}  // namespace

double jump_limited_speed(const Vec6& u_in, const Vec6& u_out, const Settings& s) {
  std::array<double, kAxisCount> jump{};
  for (int i = 0; i < kAxisCount; ++i) jump[i] = s.planner.corner_jump * s.axes[i].max_speed;
  return along(u_out - u_in, jump);
}

// An axis may change its speed at once by at most its corner jump J_i; any change beyond
// takes time at its acceleration a_i (the corner rule; the card's monitor checks the same
// joint bound). A stop from the ramp speed changes axis i at once from e_i to 0, and a start
// at path speed v along u from 0 to v u_i. Nothing rests in between unless a dwell does: a
// sync (PAUSE, a probe, an input or %(130) read) and an output take no machine time, so the
// card plays the start on the tick after the stop and the axis goes from e_i to v u_i at
// once. On a reversal that is |e_i| + v |u_i|, up to twice the ramp speed: 0.8 in/s on Z,
// whose jump is 0.44 in/s (issue 21: 2.8 times Z's acceleration by the card's measure).
// Over a rest of T the axis may also use a_i T, so for every axis
//     |v u_i - e_i| <= J_i + a_i T,  that is  v |u_i| <= J_i + a_i T + sign(u_i) e_i
// (the other side, v u_i >= e_i - J_i - a_i T, holds for every v >= 0 as |e_i| <= J_i).
// Onward in the stop's direction it costs nothing; Z reversing from 0.4 in/s starts at
// 0.04 in/s, or at its full ramp speed after (0.8 - 0.44) / 16 = 22.5 ms of dwell.
double start_after_stop(const Vec6& stopped, const Vec6& u_out, double rest_s, const Settings& s) {
  double v = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kAxisCount; ++i) {
    if (std::abs(u_out[i]) < 1e-12) continue;
    const double allowed =
        s.planner.corner_jump * s.axes[i].max_speed + s.axes[i].max_accel * rest_s;
    v = std::min(
        v, std::max(0.0, allowed + std::copysign(1.0, u_out[i]) * stopped[i]) / std::abs(u_out[i]));
  }
  return v;
}

double rest_speed(const Vec6& unit, bool jog, const Settings& s) {
  if (s.planner.mode != PlannerMode::SB3) return 0;
  const GroupSpeeds& rs = jog ? s.ramps.jog_ramp_speed : s.ramps.move_ramp_speed;
  return std::min(nominal_path_speed(unit, rs), jump_limited_speed(Vec6::Zero(), unit, s));
}

double sb3_criterion_angle(double v, const Settings& s) {
  // 5 deg at 10 in/s: the criterion times the speed is a constant, 0.8727 in/s.
  const double k = 10 * 5 * M_PI / 180 * (s.units == Units::Millimetres ? 25.4 : 1);
  return v > 0 ? std::min(kFullRampAngle, k / v) : kFullRampAngle;
}

double corner_speed(const Junction& j, const Settings& s) {
  const double v = std::min(j.v_in, j.v_out);
  const double jump = jump_limited_speed(j.u_in, j.u_out, s);
  // A full ramp: down to the rest speed, and no axis jumping by more than its corner jump
  // (a reversal at the rest speed would be twice the rest speed on that axis).
  const double full = std::min({j.rest_in, j.rest_out, v, jump});
  if (s.planner.mode == PlannerMode::Stop || j.punctuated) return full;
  if (s.planner.mode == PlannerMode::SB3 && (j.jog_in || j.jog_out)) return full;  // see sb3_corner
  const Vec6 du = j.u_out - j.u_in;
  const double turn = du.norm();  // 2 sin(phi / 2) for a turn of phi
  if (turn < 1e-12) return s.planner.mode == PlannerMode::SB3 ? sb3_corner(j, s, v, full) : v;
  // The acceleration the turn may use: the velocity changes along du, so axis i takes the
  // share |du_i| / |du| of it, out of what the moves' own acceleration leaves that axis.
  std::array<double, kAxisCount> spare{};
  for (int i = 0; i < kAxisCount; ++i)
    spare[i] = std::max(0.0, s.axes[i].max_accel - std::max(j.a_in * std::abs(j.u_in[i]),
                                                            j.a_out * std::abs(j.u_out[i])));
  const double a_turn = along(du / turn, spare);

  double vc;
  if (s.planner.mode == PlannerMode::SB3) {
    vc = sb3_corner(j, s, v, full);
  } else {
    // Junction deviation: the corner taken as an arc tangent to both moves that stays within
    // delta of the corner point has radius R = delta sin(h) / (1 - sin(h)), h half the angle
    // between the reversed incoming and the outgoing direction (sin(h) = cos(phi / 2));
    // the speed is that of centripetal acceleration a_turn on it.
    const double sin_h = std::sqrt(std::max(0.0, 1 - turn * turn / 4));
    const double r = s.planner.junction_deviation * sin_h / std::max(1e-12, 1 - sin_h);
    vc = std::sqrt(a_turn * r);
  }
  // Chord acceleration: passing corners of turn phi every l units at speed v changes the
  // velocity by v |du| every l / v seconds, an acceleration v^2 |du| / l; l is the shorter
  // of the two moves. On a polyline that approximates a curve this is its centripetal
  // acceleration.
  const double chord = std::sqrt(a_turn * std::min(j.len_in, j.len_out) / turn);
  return std::min({vc, v, chord, jump});
}

}  // namespace gantry
