// The pass model shared by the cut commands: plunge per pass and repetitions, spiral
// plunge and bottom pass, pocketing rings, tabs on the last pass, the return to the start Z
// at the end and the plunge from Z 0 (docs/cuts.md, D8-D10).
#pragma once

#include <vector>

#include "gantry/cuts/path.hpp"
#include "gantry/settings/settings.hpp"  // TabSettings

namespace gantry::cuts {

enum class Pocket { None, OutsideIn, InsideOut };

// Where tabs go: VB's sizes, where the first one starts along the path, and at most how
// many (0: as many as fit).
struct TabPlan {
  bool on = false;
  TabSettings sizes;
  double first = 0;
  int most = 0;
};

struct PassPlan {
  double z_start = 0;  // where Z is when the command starts
  double plunge = 0;   // Z change of each pass
  int repetitions = 1;
  bool spiral = false;       // Z descends along each pass instead of before it
  bool bottom_pass = false;  // one more pass, flat, at the final depth
  bool from_zero = false;    // Z goes to 0 first; passes are measured from 0
  bool pull_up = true;       // at the end, back to z_start (unless "no pull up")
  double safe_z = 1;
  bool plunge_negative = true;  // VC 5: which way is into the material
  Pocket pocket = Pocket::None;
  TabPlan tabs;

  // Where an open path's passes go back to their start: out of the material, the higher (in
  // the lifting sense) of Safe-Z and the start Z.
  double clear_z() const;
  // Whether Z `to` is out of the material from Z `from` (up, with VC's plunge "-").
  bool is_up(double from, double to) const { return plunge_negative ? to > from : to < from; }
  double depth(int pass) const;  // Z of pass k (0: the reference)
};

// The tab lifts along a contour of length `length`: up over the leads, level for the size,
// down over the leads, starting at `first` and every `spacing` after (start to start); a tab
// that would run past the end is left out. `count` receives how many there are.
Profile tab_profile(double length, const TabPlan& t, double lift, int* count);

// Tabs on a path that arrives one move at a time (plain moves while VB's tabbing or FP's tab
// feature is on): the part of the same tab series, the tabs of `t` laid along a path from
// distance 0, that lies between `from` and `to` on it, as a profile of the distance from
// `from`. Tabs do not have to fit before `to` (the path may go on). `ended` receives how many
// of the series' tabs end at or before `to`.
Profile tab_window(const TabPlan& t, double lift, double from, double to, int* ended);

// One move of such a path: the tool is at `tool`, `lift_now` above where the file has it
// (the height of a tab it is on), and follows `piece` (in XY) to Z `z_to`, `travel` along the
// path from its start. The move is cut at the breakpoints of the tab profile, each part a
// line or a helix; the path ends `path.end().z() - z_to` above `z_to`. `ended` as above.
CutPath tab_stretch(const V3& tool, double lift_now, const Piece& piece, double z_to, double travel,
                    const TabPlan& t, double lift, int* ended);

// Runs the passes over `rings` from `start`: rings[0] is the tool path; the others, inner
// rings for pocketing, each starting on a straight line from rings[0]'s start that stays in
// the cleared area. `closed`: the path ends where it starts.
CutPath run_passes(const V3& start, const std::vector<Contour>& rings, bool closed,
                   const PassPlan& plan);

// The scale factors of the rings that pocket a convex path whose farthest point is `reach`
// from the centre it is scaled about, with a step-over of at most `step` between rings,
// the innermost within step / 2 of the centre: 1, then down to (step / 2) / reach.
std::vector<double> pocket_scales(double reach, double step);
// The insets of the rings that pocket a w x h rectangle: 0, then up to min(w, h) / 2 -
// step / 2, at most `step` apart.
std::vector<double> pocket_insets(double w, double h, double step);

}  // namespace gantry::cuts
