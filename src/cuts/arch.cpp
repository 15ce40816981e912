// CA: an arch of a given span and height from where the tool is.
#include <fmt/format.h>  // messages

#include <cmath>  // atan, atan2, cos, sin

#include "curve_cut.hpp"

namespace gantry::cuts {

// Span L (the chord) and height h (the sagitta) give the circle: from the right triangle of
// half-chord, R - h and R, (R - h)^2 + (L/2)^2 = R^2, so R = (L^2/4 + h^2) / (2h); the arc
// spans 4 atan(2h / L) (half its angle at the centre is twice the angle the chord makes
// with the line from its end to the apex). h = L/2 is the half circle.
CutPath cut_arch(const CutSetup& setup, const ArchParams& p) {
  const double len = p.length, h = p.height;
  if (!(len > 0)) throw CutError(0, fmt::format("the arch length must be above 0, not {:g}", len));
  if (!(h > 0)) throw CutError(1, fmt::format("the arch height must be above 0, not {:g}", h));
  if (h > len / 2 * (1 + 1e-12))
    throw CutError(1, fmt::format("an arch is at most half as high as it is long (a half "
                                  "circle): height {:g} is more than half of {:g}; use CC or CG "
                                  "for a larger part of a circle",
                                  h, len));
  const int dir = checked_direction(p.direction, 3);
  const double radius = (len * len / 4 + h * h) / (2 * h);
  const double sweep = 4 * std::atan(2 * h / len);
  // The chord runs along u (alignment clockwise from +X); clockwise travel bulges to the
  // left of it (the arch rises above the chord at alignment 0), counter-clockwise mirrors it.
  const double al = radians(p.alignment);
  const V2 u(std::cos(al), -std::sin(al));
  const V2 left(-u.y(), u.x());
  const V2 centre = len / 2 * u + dir * (h - radius) * left;  // from the start
  const V2 rel = -centre;                                     // start from the centre
  CurveCut c;
  c.radius = radius;
  c.proportion_x = p.proportion_x;
  c.proportion_y = p.proportion_y;
  c.side = p.side;
  c.direction = dir;
  c.begin = degrees(std::atan2(rel.x(), rel.y()));
  c.sweep = degrees(sweep);
  c.pass = p.pass;
  c.pass.feature = 0;
  c.tabs = p.tabs;
  c.index = {2, 3, 7, 8, 9, 6};
  return cut_curve(setup, c);
}

}  // namespace gantry::cuts
