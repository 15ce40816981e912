// CG: an arc from where the tool is to an end point, about a centre given by its offset
// from the start (I, J) or found from a diameter (the arc under 180 degrees).
#include <fmt/format.h>  // messages

#include <cmath>  // atan2, sqrt

#include "curve_cut.hpp"

namespace gantry::cuts {

CutPath cut_gcode_arc(const CutSetup& setup, const GcodeArcParams& p) {
  const int dir = checked_direction(p.direction, 6);
  const V2 s = setup.start.head<2>();
  const V2 e = p.end;
  const double chord = (e - s).norm();
  // Closer than this, the end is the start: a full circle.
  const double same = 1e-9 * std::max(1.0, s.norm());
  V2 centre;
  double radius = 0;
  if (p.diameter) {
    radius = *p.diameter / 2;
    if (!(radius > 0)) throw CutError(0, "the diameter must be above 0 (or blank, to use I and J)");
    if (chord <= same)
      throw CutError(1,
                     "a circle cannot be made from a diameter alone: give an end point away "
                     "from the start, or the centre offsets I and J instead of the diameter");
    if (chord > 2 * radius * (1 + 1e-12))
      throw CutError(1, fmt::format("the end point is {:g} from the start, farther than the "
                                    "diameter {:g}",
                                    chord, *p.diameter));
    // The centre is on the perpendicular bisector of the chord, sqrt(r^2 - (chord/2)^2) from
    // its middle; on the right of the travel for a clockwise arc, which makes it the arc
    // under 180 degrees (the left for counter-clockwise).
    const V2 u = (e - s) / chord;
    const V2 right(u.y(), -u.x());
    const double h = std::sqrt(std::max(0.0, radius * radius - chord * chord / 4));
    centre = (s + e) / 2 + dir * h * right;
  } else {
    centre = s + p.center_offset;
    radius = p.center_offset.norm();
    if (!(radius > same))
      throw CutError(3, "the centre offsets I and J are both 0: the centre is the start point");
    const double end_radius = (e - centre).norm();
    if (chord > same && std::abs(end_radius - radius) > setup.tolerance + 1e-4 * radius)
      throw CutError(1, fmt::format("the end point is {:g} from the centre but the start is "
                                    "{:g}: the end is not on the circle",
                                    end_radius, radius));
  }
  // From here CG is CC: the begin and end angles of the start and end about that centre.
  CurveCut c;
  c.radius = radius;
  c.proportion_x = p.proportion_x;
  c.proportion_y = p.proportion_y;
  c.side = p.side;
  c.direction = dir;
  const V2 rs = s - centre, re = e - centre;
  const double begin = degrees(std::atan2(rs.x(), rs.y()));
  const std::optional<double> end =
      chord > same ? std::optional<double>(degrees(std::atan2(re.x(), re.y()))) : std::nullopt;
  angles(begin, end, dir, &c.begin, &c.sweep);
  c.pass = p.pass;
  c.index = {5, 6, 9, 10, 11, 8};
  return cut_curve(setup, c);
}

}  // namespace gantry::cuts
