// Test helpers: positions and planned segments written in one line.
#pragma once

#include <vector>

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

// Keeps every segment the planner sends, and counts its flushes.
class Collect : public SegmentSink {
 public:
  void segment(const PlannedSegment& s) override { segs.push_back(s); }
  void flush() override { ++flushes; }
  std::vector<PlannedSegment> segs;
  int flushes = 0;
};

}  // namespace gantry::test
