// CR: a rectangle whose start corner is where the tool is.
#include <fmt/format.h>  // messages

#include "curve_cut.hpp"

namespace gantry::cuts {

CutPath cut_rectangle(const CutSetup& setup, const RectParams& p) {
  const double lx = p.length_x, ly = p.length_y.value_or(p.length_x);
  if (!(lx > 0)) throw CutError(0, fmt::format("length X must be above 0, not {:g}", lx));
  if (!(ly > 0)) throw CutError(1, fmt::format("length Y must be above 0, not {:g}", ly));
  const int dir = checked_direction(p.direction, 3);
  if (p.corner < 1 || p.corner > 4)
    throw CutError(4,
                   "the start corner is 1 (upper left), 2 (upper right), 3 (lower right) or "
                   "4 (lower left)");
  PassOptions o;
  o.plunge = p.plunge;
  o.repetitions = p.repetitions;
  o.from_zero = p.from_zero;
  if (p.repetitions < 1) throw CutError(6, "repetitions must be 1 or more");
  if (p.feature < 0 || p.feature > 3)
    throw CutError(7,
                   "the feature is 0 (none), 1 (tabs), 2 (pocket, outside in) or 3 (pocket, "
                   "inside out)");
  // The tool path's size: the cutter's width more (O) or less (I) than the nominal size.
  const double grow = 2 * side_offset(p.side, setup.cutter);
  Rect r;
  r.w = lx + grow;
  r.h = ly + grow;
  if (!(r.w > 1e-9) || !(r.h > 1e-9))
    throw CutError(2, fmt::format("with I the cutter ({:g} across) leaves no path inside a "
                                  "{:g} x {:g} rectangle",
                                  setup.cutter, lx, ly));
  r.corner = p.corner;
  r.direction = dir;
  r.lower_left = V2(setup.start.head<2>()) - (r.corner_point(p.corner) - r.lower_left);
  std::vector<Contour> rings = {contour(r)};
  PassPlan plan = pass_plan(setup, o);
  if (p.feature == 2 || p.feature == 3) {
    const double step = setup.cutter * (1 - setup.pocket_overlap / 100);
    if (!(step > 0)) throw CutError(7, "a pocket needs a cutter diameter above 0 (VC)");
    const std::vector<double> insets = pocket_insets(r.w, r.h, step);
    for (size_t i = 1; i < insets.size(); ++i) rings.push_back(contour(r.inset(insets[i])));
    plan.pocket = p.feature == 2 ? Pocket::OutsideIn : Pocket::InsideOut;
  } else {
    plan.tabs = tab_plan(setup, p.feature == 1);
  }
  return run_passes(setup.start, rings, true, plan);
}

}  // namespace gantry::cuts
