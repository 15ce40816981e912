// The generators of the cut commands CA, CC, CG, CP and CR: each a pure function from where
// the tool is, the command's parameters and the settings to a tool path. A parameter the
// geometry cannot use throws CutError naming its position in the command's list.
#pragma once

#include <optional>

#include "gantry/cuts/passes.hpp"
#include "gantry/cuts/path.hpp"
#include "gantry/cuts/shapes.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry::cuts {

// What a cut reads besides its parameters.
struct CutSetup {
  V3 start = V3::Zero();  // the tool's position (the running file's coordinates)
  double cutter = 0.25;   // VC diameter
  double safe_z = 1;
  double pocket_overlap = 10;  // percent of the cutter diameter
  bool plunge_negative = true;
  double tolerance = 0.0005;  // ellipses as lines within this of the exact curve
  TabSettings tab_sizes;
  // VB in a file: tabs on for every cut, where the first one is, and how many are left (0:
  // no limit).
  bool file_tabs = false;
  double first_tab = 0;
  int tabs_left = 0;

  static CutSetup from(const Settings& s, const V3& start);
};

// The options after the shape, shared by the circle-like commands and CA.
struct PassOptions {
  double plunge = 0;
  int repetitions = 1;
  int feature = 0;  // 1 tabs, 2 pocket, 3 spiral, 4 spiral and bottom pass
  bool no_pull_up = false;
  bool from_zero = false;
};

// Positions of the shared options in each command's list, for errors.
struct OptionIndex {
  size_t side, direction, proportion_x, proportion_y, feature, repetitions;
};

// Begin angle and sweep (degrees) from CC's or CP's begin and end angles: a blank begin is 0
// clockwise and 360 counter-clockwise, a blank end a full circle; the sweep is the angle from
// begin to end in the direction of travel, within one turn, 0 meaning a whole turn.
void angles(std::optional<double> begin, std::optional<double> end, int direction,
            double* begin_out, double* sweep_out);

struct CircleParams {  // CC
  double diameter = 0;
  Side side = Side::True;
  int direction = 1;
  std::optional<double> begin, end;  // degrees; blank as SB3 says
  double proportion_x = 1, proportion_y = 1;
  PassOptions pass;
};
CutPath cut_circle(const CutSetup& setup, const CircleParams& p);

struct CenterCircleParams {  // CP
  double diameter = 0;
  V2 center = V2::Zero();  // absolute, in the file's coordinates
  Side side = Side::True;
  int direction = 1;
  double begin = 0, end = 0;
  double proportion_x = 1, proportion_y = 1;
  PassOptions pass;
};
CutPath cut_center_circle(const CutSetup& setup, const CenterCircleParams& p);

struct GcodeArcParams {            // CG
  std::optional<double> diameter;  // the diameter method (minor arcs only) when given
  V2 end = V2::Zero();             // absolute
  V2 center_offset = V2::Zero();   // I, J from the start
  Side side = Side::True;
  int direction = 1;
  double proportion_x = 1, proportion_y = 1;
  PassOptions pass;
};
CutPath cut_gcode_arc(const CutSetup& setup, const GcodeArcParams& p);

struct ArchParams {  // CA
  double length = 0, height = 0;
  Side side = Side::True;
  int direction = 1;
  double alignment = 0;  // degrees clockwise from +X
  double proportion_x = 1, proportion_y = 1;
  bool tabs = false;
  PassOptions pass;  // its feature is unused: CA's tabs are their own parameter
};
CutPath cut_arch(const CutSetup& setup, const ArchParams& p);

struct RectParams {  // CR
  double length_x = 0;
  std::optional<double> length_y;  // blank: a square
  Side side = Side::True;
  int direction = 1;
  int corner = 4;
  double plunge = 0;
  int repetitions = 1;
  int feature = 0;  // 1 tabs, 2 pocket outside-in, 3 pocket inside-out
  bool from_zero = false;
};
CutPath cut_rectangle(const CutSetup& setup, const RectParams& p);

}  // namespace gantry::cuts
