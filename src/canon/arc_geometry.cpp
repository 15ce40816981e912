// Chordal approximation of arcs.
#include "gantry/canon/arc_geometry.hpp"

#include <algorithm>  // max, min
#include <cmath>      // acos, ceil, cos, sin, atan2, hypot

namespace gantry {

std::array<int, 3> plane_axes(ArcPlane plane) {
  switch (plane) {
    case ArcPlane::ZX:
      return {2, 0, 1};
    case ArcPlane::YZ:
      return {1, 2, 0};
    case ArcPlane::XY:
      break;
  }
  return {0, 1, 2};
}

double arc_radius(const CanonMove& arc) {
  const std::array<int, 3> ax = plane_axes(arc.plane);
  return std::hypot(arc.from[ax[0]] - arc.center_x, arc.from[ax[1]] - arc.center_y);
}

double arc_chord_count(const CanonMove& arc, double tolerance) {
  const double r = arc_radius(arc);
  double max_step = M_PI / 2;
  if (r > tolerance) max_step = std::min(max_step, 2 * std::acos(1 - tolerance / r));
  return std::max(1.0, std::ceil(std::abs(arc.sweep) / max_step - 1e-9));  // 1 for nan
}

std::vector<Vec6> arc_chords(const CanonMove& arc, double tolerance) {
  const std::array<int, 3> ax = plane_axes(arc.plane);
  const int u = ax[0], v = ax[1];
  const double r = arc_radius(arc);
  // The interpreter refuses an arc of more chords; the bound keeps the conversion defined.
  const int n = static_cast<int>(std::min(arc_chord_count(arc, tolerance), kMaxArcChords));
  const double a0 = std::atan2(arc.from[v] - arc.center_y, arc.from[u] - arc.center_x);
  std::vector<Vec6> out;
  out.reserve(static_cast<size_t>(n));
  for (int i = 1; i < n; ++i) {
    const double f = static_cast<double>(i) / n;
    Vec6 p = arc.from + (arc.to - arc.from) * f;  // the other axes move in proportion
    p[u] = arc.center_x + r * std::cos(a0 + arc.sweep * f);
    p[v] = arc.center_y + r * std::sin(a0 + arc.sweep * f);
    out.push_back(p);
  }
  out.push_back(arc.to);
  return out;
}

}  // namespace gantry
