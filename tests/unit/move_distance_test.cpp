// MD's angle forms: the spec's worked examples (commands.md §3.9).
#include <gtest/gtest.h>

#include "gantry/commands/move_distance.hpp"

namespace gantry {
namespace {

TEST(MoveDistanceHeading, AbsoluteDegreesClockFacesAndCompassPoints) {
  EXPECT_EQ(md_heading("90", std::nullopt), 90.0);
  EXPECT_EQ(md_heading("-45", std::nullopt), -45.0);
  EXPECT_EQ(md_heading("3:00", std::nullopt), 90.0);  // +X
  EXPECT_EQ(md_heading("1:30", std::nullopt), 45.0);
  EXPECT_EQ(md_heading("12:00", std::nullopt), 0.0);
  EXPECT_EQ(md_heading("E", std::nullopt), 90.0);
  EXPECT_EQ(md_heading("n", std::nullopt), 0.0);
  EXPECT_EQ(md_heading("SSW", std::nullopt), 202.5);
  EXPECT_EQ(md_heading("NNW", std::nullopt), 337.5);
  EXPECT_EQ(md_heading("W", std::nullopt), 270.0);
}

TEST(MoveDistanceHeading, RightAndLeftTurnFromTheLastMoveOrAreIgnoredWithoutOne) {
  EXPECT_EQ(md_heading("30R", 90.0), 120.0);
  EXPECT_EQ(md_heading("30L", 10.0), 340.0);
  EXPECT_EQ(md_heading("90r", -90.0), 0.0);
  EXPECT_EQ(md_heading("30R", std::nullopt), 30.0);  // the first move: R/L ignored
}

TEST(MoveDistanceHeading, AnythingElseIsNotAnAngle) {
  for (const char* bad : {"", "NS", "EEE", "NNNE", "3:75", "x", "12:", "R", "1.5.2", ":30"})
    EXPECT_FALSE(md_heading(bad, 0.0)) << bad;
}

}  // namespace
}  // namespace gantry
