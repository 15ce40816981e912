// Circles, ellipses and their arcs, cut through the pass model.
#include "curve_cut.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // max
#include <cmath>      // fmod, floor

namespace gantry::cuts {

double radians(double degrees) {
  return degrees * M_PI / 180;
}
double degrees(double radians) {
  return radians * 180 / M_PI;
}

CutSetup CutSetup::from(const Settings& s, const V3& start) {
  CutSetup out;
  out.start = start;
  out.cutter = s.cutter.diameter;
  out.safe_z = s.cutter.safe_z;
  out.pocket_overlap = s.cutter.pocket_overlap;
  out.plunge_negative = s.cutter.plunge_negative;
  out.tolerance = s.planner.chord_tolerance;
  out.tab_sizes = s.tabs;
  return out;
}

void angles(std::optional<double> begin, std::optional<double> end, int direction,
            double* begin_out, double* sweep_out) {
  const double b = begin ? *begin : direction > 0 ? 0.0 : 360.0;
  double s = 360;
  if (end) {
    s = direction > 0 ? *end - b : b - *end;
    s -= 360 * std::floor(s / 360);  // into [0, 360)
    if (s < 1e-9 || s > 360 - 1e-9) s = 360;
  }
  *begin_out = b;
  *sweep_out = s;
}

int checked_direction(int direction, size_t param) {
  if (direction != 1 && direction != -1)
    throw CutError(param, "the direction is 1 (clockwise) or -1 (counter-clockwise)");
  return direction;
}

void check_proportions(double px, double py, const OptionIndex& index) {
  if (!(px > 0)) throw CutError(index.proportion_x, "proportion X must be above 0");
  if (!(py > 0)) throw CutError(index.proportion_y, "proportion Y must be above 0");
}

TabPlan tab_plan(const CutSetup& setup, bool asked) {
  TabPlan t;
  t.on = asked || setup.file_tabs;
  t.sizes = setup.tab_sizes;
  t.first = setup.file_tabs && setup.first_tab > 0 ? setup.first_tab : setup.tab_sizes.spacing;
  t.most = setup.file_tabs ? setup.tabs_left : 0;
  return t;
}

PassPlan pass_plan(const CutSetup& setup, const PassOptions& o) {
  PassPlan p;
  p.z_start = setup.start.z();
  p.plunge = o.plunge;
  p.repetitions = o.repetitions;
  p.spiral = o.feature == 3 || o.feature == 4;
  p.bottom_pass = o.feature == 4;
  p.from_zero = o.from_zero;
  p.pull_up = !o.no_pull_up;
  p.safe_z = setup.safe_z;
  p.plunge_negative = setup.plunge_negative;
  return p;
}

void check_passes(const PassOptions& o, const OptionIndex& index) {
  if (o.repetitions < 1) throw CutError(index.repetitions, "repetitions must be 1 or more");
  if (o.feature < 0 || o.feature > 4)
    throw CutError(index.feature,
                   "the feature is 0 (none), 1 (tabs), 2 (pocket), 3 (spiral plunge) or 4 (spiral "
                   "and bottom pass)");
}

CutPath cut_curve(const CutSetup& setup, const CurveCut& c) {
  checked_direction(c.direction, c.index.direction);
  check_proportions(c.proportion_x, c.proportion_y, c.index);
  check_passes(c.pass, c.index);
  Curve curve;
  curve.a = c.radius * c.proportion_x;
  curve.b = c.radius * c.proportion_y;
  curve.offset = side_offset(c.side, setup.cutter);
  curve.begin = radians(c.begin);
  curve.sweep = c.direction * radians(c.sweep);
  if (curve.circular() && !(curve.a + curve.offset > 1e-9))
    throw CutError(c.index.side,
                   fmt::format("with I the cutter ({:g} across) leaves no path inside a circle "
                               "{:g} across",
                               setup.cutter, 2 * curve.a));
  if (!curve.circular() && curve.offset < 0 && -curve.offset >= curve.tightest_radius() - 1e-9)
    throw CutError(c.index.side,
                   fmt::format("with I the cutter ({:g} across) is wider than this ellipse's "
                               "tightest curve ({:g} across): its path would cross itself",
                               setup.cutter, 2 * curve.tightest_radius()));
  curve.centre = c.centre ? *c.centre : V2(setup.start.head<2>()) - curve.relative(curve.begin);
  const bool pocket = c.pass.feature == 2;
  if (pocket && !curve.full())
    throw CutError(c.index.feature,
                   "a pocket needs a full circle (leave the end angle blank, or equal to the "
                   "begin angle)");
  std::vector<Contour> rings = {contour(curve, setup.tolerance)};
  PassPlan plan = pass_plan(setup, c.pass);
  if (pocket) {
    const double step = setup.cutter * (1 - setup.pocket_overlap / 100);
    if (!(step > 0))
      throw CutError(c.index.feature, "a pocket needs a cutter diameter above 0 (VC)");
    // The farthest the path gets from the centre (a circle's radius; sampled on an ellipse).
    double reach = 0;
    for (int i = 0; i < 3600; ++i)
      reach = std::max(reach, curve.relative(curve.begin + 2 * M_PI * i / 3600).norm());
    reach += setup.tolerance;
    const std::vector<double> scales = pocket_scales(reach, step);
    for (size_t i = 1; i < scales.size(); ++i)
      rings.push_back(contour(curve.scaled(scales[i]), setup.tolerance));
    plan.pocket = Pocket::OutsideIn;
  } else {
    plan.tabs = tab_plan(setup, c.tabs || c.pass.feature == 1);
  }
  const V2 from = curve.point(curve.begin);
  const V3 start = c.centre ? V3(from.x(), from.y(), setup.start.z()) : setup.start;
  CutPath path = run_passes(start, rings, curve.full(), plan);
  if (c.centre) {  // CP: first to the start point, at the current height
    PathBuilder approach(setup.start);
    approach.line(start, Role::Approach);
    CutPath out = approach.take();
    out.moves.insert(out.moves.end(), path.moves.begin(), path.moves.end());
    out.tabs = path.tabs;
    return out;
  }
  return path;
}

}  // namespace gantry::cuts
