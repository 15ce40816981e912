// CC (a circle from where the tool is) and CP (a circle about a given centre).
#include <fmt/format.h>  // messages

#include "curve_cut.hpp"

namespace gantry::cuts {

namespace {

// What CC and CP share; `direction_param` and `index` place their parameters for errors.
template <class Params>
CurveCut circle_curve(const Params& p, size_t direction_param, const OptionIndex& index) {
  if (!(p.diameter > 0))
    throw CutError(0, fmt::format("the diameter must be above 0, not {:g}", p.diameter));
  CurveCut c;
  c.radius = p.diameter / 2;
  c.proportion_x = p.proportion_x;
  c.proportion_y = p.proportion_y;
  c.side = p.side;
  c.direction = checked_direction(p.direction, direction_param);
  angles(p.begin, p.end, p.direction, &c.begin, &c.sweep);
  c.pass = p.pass;
  c.index = index;
  return c;
}

}  // namespace

CutPath cut_circle(const CutSetup& setup, const CircleParams& p) {
  return cut_curve(setup, circle_curve(p, 2, {1, 2, 7, 8, 9, 6}));
}

CutPath cut_center_circle(const CutSetup& setup, const CenterCircleParams& p) {
  CurveCut c = circle_curve(p, 4, {3, 4, 9, 10, 11, 8});
  c.centre = p.center;
  return cut_curve(setup, c);
}

}  // namespace gantry::cuts
