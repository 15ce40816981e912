// The shapes the cut commands cut: an axis-aligned ellipse arc (a circle when both
// proportions are equal) offset by the cutter radius, and an axis-aligned rectangle.
#pragma once

#include "gantry/cuts/path.hpp"

namespace gantry::cuts {

// O, I or T: on which side of the nominal outline the cutter runs.
enum class Side { Out, In, True };

// The signed distance from the nominal outline to the cutter's centre, outward positive:
// half the cutter diameter outside (O), inside (I), or 0 on the line (T).
double side_offset(Side side, double cutter_diameter);

// An arc of the ellipse centre + (a sin t, b cos t), t in ShopBot's angles (0 at 12 o'clock,
// increasing clockwise), offset by `offset` along its outward normal. The offset curve of an
// ellipse is not an ellipse; it is exact here, and a circle stays a circle (radius a + offset).
struct Curve {
  V2 centre = V2::Zero();
  double a = 1, b = 1;  // semi-axes along X and Y
  double offset = 0;    // outward positive
  double begin = 0;     // radians, clockwise from 12 o'clock
  double sweep = 0;     // radians, positive clockwise; +-2 pi is a full turn

  bool circular() const { return a == b; }
  bool full() const;
  // The path point at angle t; relative() leaves out the centre.
  V2 relative(double t) const;
  V2 point(double t) const { return centre + relative(t); }
  // The same curve scaled by k about its centre (the offset scales too).
  Curve scaled(double k) const;
  // The smallest radius of curvature of the nominal ellipse: an inward offset must stay
  // below it, or the path would cross itself.
  double tightest_radius() const;
};

// The curve as a contour: one true arc for a circle; for an ellipse, lines whose every point
// is within `tolerance` of the exact offset curve.
Contour contour(const Curve& c, double tolerance);

// A rectangle's tool path: lower-left corner, size, the corner it starts at (1 upper left,
// 2 upper right, 3 lower right, 4 lower left) and its direction (1 clockwise, -1 counter).
struct Rect {
  V2 lower_left = V2::Zero();
  double w = 1, h = 1;
  int corner = 4;
  int direction = 1;
  V2 corner_point(int code) const;
  V2 start() const { return corner_point(corner); }
  Rect inset(double d) const;
};
Contour contour(const Rect& r);

}  // namespace gantry::cuts
