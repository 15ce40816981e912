// CC (a circle from where the tool is) and CP (a circle about a given centre).
#include <fmt/format.h>  // messages

#include "curve_cut.hpp"

namespace gantry::cuts {

namespace {

void check_diameter(double d, size_t param) {
  if (!(d > 0)) throw CutError(param, fmt::format("the diameter must be above 0, not {:g}", d));
}

}  // namespace

CutPath cut_circle(const CutSetup& setup, const CircleParams& p) {
  check_diameter(p.diameter, 0);
  CurveCut c;
  c.radius = p.diameter / 2;
  c.proportion_x = p.proportion_x;
  c.proportion_y = p.proportion_y;
  c.side = p.side;
  c.direction = checked_direction(p.direction, 2);
  angles(p.begin, p.end, p.direction, &c.begin, &c.sweep);
  c.pass = p.pass;
  c.index = {1, 2, 7, 8, 9, 6};
  return cut_curve(setup, c);
}

CutPath cut_center_circle(const CutSetup& setup, const CenterCircleParams& p) {
  check_diameter(p.diameter, 0);
  CurveCut c;
  c.radius = p.diameter / 2;
  c.proportion_x = p.proportion_x;
  c.proportion_y = p.proportion_y;
  c.side = p.side;
  c.direction = checked_direction(p.direction, 4);
  angles(p.begin, p.end, p.direction, &c.begin, &c.sweep);
  c.centre = p.center;
  c.pass = p.pass;
  c.index = {3, 4, 9, 10, 11, 8};
  return cut_curve(setup, c);
}

}  // namespace gantry::cuts
