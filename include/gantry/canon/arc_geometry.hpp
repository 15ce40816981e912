// Arc geometry the interpreters, the planner, the preview and export share: an arc plane's axes,
// its radius, and its chords within a tolerance (what a planner runs an arc through).
#pragma once

#include <array>
#include <vector>

#include "gantry/canon/canon_move.hpp"  // CanonMove (Arc)

namespace gantry {

// The axes (0 X .. 5 C) of an arc plane: its first, second and third (normal) axis.
// XY: X, Y, Z; ZX: Z, X, Y; YZ: Y, Z, X.
std::array<int, 3> plane_axes(ArcPlane plane);

// The chord ends of `arc` after its start, the last one exactly arc.to. A chord across an
// angle t of a circle of radius r strays from the arc by its sagitta r (1 - cos(t / 2)), so
// chords of at most t = 2 acos(1 - tolerance / r) stay within `tolerance`; the sweep is cut
// into equal chords no longer than that (at least one; four per full turn at the least, so
// a coarse tolerance still gives a shape).
std::vector<Vec6> arc_chords(const CanonMove& arc, double tolerance);
// How many chords that is (a double: an absurd arc's count does not fit an int). The
// interpreter refuses an arc of more than kMaxArcChords (a 1e12-turn helix, a circle a
// million miles wide), before it is planned.
double arc_chord_count(const CanonMove& arc, double tolerance);
inline constexpr double kMaxArcChords = 1e6;

// The arc's radius (from its centre to its start, in its plane).
double arc_radius(const CanonMove& arc);

}  // namespace gantry
