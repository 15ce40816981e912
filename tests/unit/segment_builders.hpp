// Test helpers: positions and planned segments written in one line.
#pragma once

#include "gantry/motion/planned_segment.hpp"

namespace gantry::test {

inline Vec6 vec(double x, double y = 0, double z = 0, double a = 0, double b = 0, double c = 0) {
  Vec6 v;
  v << x, y, z, a, b, c;
  return v;
}

// A straight segment with the trapezoid planned over its Euclidean length.
inline PlannedSegment segment(const Vec6& from, const Vec6& to, double v_entry, double v_max,
                              double v_exit, double accel) {
  PlannedSegment s;
  s.from = from;
  s.to = to;
  s.profile = Trapezoid::plan((to - from).norm(), v_entry, v_max, v_exit, accel);
  return s;
}

}  // namespace gantry::test
