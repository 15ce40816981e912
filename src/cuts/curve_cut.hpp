// The part CC, CP, CG and CA share: a circle or ellipse arc of a nominal radius, offset for
// the cutter, placed so that its path starts at the tool (or about a given centre), then
// cut through the pass model.
#pragma once

#include <optional>

#include "gantry/cuts/cuts.hpp"

namespace gantry::cuts {

struct CurveCut {
  double radius = 1;  // nominal, before proportions
  double proportion_x = 1, proportion_y = 1;
  Side side = Side::True;
  int direction = 1;
  double begin = 0;          // degrees, clockwise from 12 o'clock
  double sweep = 360;        // degrees, 0 < sweep <= 360, in the command's direction
  std::optional<V2> centre;  // CP: given; otherwise the path starts at the tool
  PassOptions pass;
  bool tabs = false;  // the command asks for tabs (CC's feature 1 or CA's parameter)
  OptionIndex index;
};

CutPath cut_curve(const CutSetup& setup, const CurveCut& c);

// 1 or -1, or a CutError at `param`.
int checked_direction(int direction, size_t param);
void check_proportions(double px, double py, const OptionIndex& index);

// Shared with CR: the tabs a cut gets (asked for, or on in the file), its pass plan, and the
// checks of repetitions and feature.
TabPlan tab_plan(const CutSetup& setup, bool asked);
PassPlan pass_plan(const CutSetup& setup, const PassOptions& o);
void check_passes(const PassOptions& o, const OptionIndex& index);

double radians(double degrees);
double degrees(double radians);

}  // namespace gantry::cuts
