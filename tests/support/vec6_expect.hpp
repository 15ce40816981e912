// Positions and speeds as tests write and compare them.
#pragma once

#include <gtest/gtest.h>

#include "gantry/core/axes.hpp"  // kAxisCount, kAxisLetters
#include "gantry/core/vec6.hpp"
#include "gantry/settings/settings.hpp"  // GroupSpeeds

namespace gantry {

// A location by its axes, X first.
inline Vec6 at(double x, double y = 0, double z = 0, double a = 0, double b = 0, double c = 0) {
  Vec6 v;
  v << x, y, z, a, b, c;
  return v;
}

// Every axis of `actual` within `tolerance` of `expected`.
inline void expect_vec(const Vec6& actual, const Vec6& expected, double tolerance = 1e-12) {
  for (int i = 0; i < kAxisCount; ++i)
    EXPECT_NEAR(actual[i], expected[i], tolerance) << "axis " << kAxisLetters[i];
}

inline void expect_speeds(const GroupSpeeds& s, double xy, double z, double a, double b, double c) {
  EXPECT_DOUBLE_EQ(s.xy, xy);
  EXPECT_DOUBLE_EQ(s.z, z);
  EXPECT_DOUBLE_EQ(s.a, a);
  EXPECT_DOUBLE_EQ(s.b, b);
  EXPECT_DOUBLE_EQ(s.c, c);
}

}  // namespace gantry
