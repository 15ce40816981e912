// The progress every front end shows (issue 25: after a stop at line 24 the window said "line
// 58 of 58 (100 %)", and "remaining 0:00:03" at 100 % while idle).
#include "gantry/session/run_progress.hpp"

#include <gtest/gtest.h>

#include "gantry/session/feed_override.hpp"
#include "gantry/session/readout_lines.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry::session {
namespace {

ControllerStatus status(MachineState st, std::size_t line, std::size_t lines, int playing,
                        double elapsed, double remaining) {
  ControllerStatus s;
  s.state = st;
  s.line = line;
  s.lines = lines;
  s.playing_line = playing;
  s.elapsed_s = elapsed;
  s.remaining_s = remaining;
  return s;
}

TEST(RunProgress, UnderWayTheLineIsTheOnePlayingAndTheFractionTheTimeOfTheEstimate) {
  // The interpreter has read ahead to line 40; the card plays line 12.
  const RunProgress p = run_progress(status(MachineState::Running, 40, 58, 12, 15, 45));
  EXPECT_EQ(p.line, 12u);
  EXPECT_DOUBLE_EQ(p.fraction, 0.25);
  EXPECT_EQ(p.label(), "line 12 of 58 (25 %)");
  EXPECT_EQ(p.times(), "elapsed 0:00:15  remaining 0:00:45");
  EXPECT_FALSE(p.over);
}

TEST(RunProgress, WithoutAnEstimateTheLinesBeforeThePlayingOneAreDone) {
  const RunProgress p = run_progress(status(MachineState::Running, 9, 11, 6, 3, 0));
  EXPECT_EQ(p.label(), "line 6 of 11 (45 %)");
  EXPECT_EQ(p.times(), "elapsed 0:00:03  remaining -");
}

TEST(RunProgress, AStoppedRunShowsWhereTheMotionStoppedNotHowFarItWasRead) {
  ControllerStatus s = status(MachineState::Stopped, 58, 58, 24, 30, 90);
  s.stopped_at.line = 24;
  s.message = "stopped by the operator";
  const RunProgress p = run_progress(s);
  EXPECT_EQ(p.line, 24u);
  EXPECT_EQ(p.label(), "line 24 of 58 (25 %)");  // 30 s of the 120 s estimate
  EXPECT_EQ(p.times(), "elapsed 0:00:30  remaining -");
  EXPECT_TRUE(p.over);
  s.state = MachineState::EStop;
  EXPECT_EQ(run_progress(s).line, 24u);
}

// Issue 25: while a file FP called played its line 3, the label said "line 3 of 4", the
// called file's line against the top-level file's count. The label keeps the calling line;
// the listing follows the called file (file, file_line).
TEST(RunProgress, WhileACalledFilePlaysTheLabelKeepsTheLineThatCalledIt) {
  ControllerStatus s = status(MachineState::Running, 2, 4, 3, 1, 0);
  s.file = std::make_shared<const std::string>("top.sbp");
  s.playing_file = std::make_shared<const std::string>("called.sbp");
  RunProgress p = run_progress(s);
  EXPECT_EQ(p.label(), "line 2 of 4 (25 %)");
  EXPECT_EQ(*p.file, "called.sbp");
  EXPECT_EQ(p.file_line, 3u);
  // Stopped in it: the same.
  s.state = MachineState::Stopped;
  s.message = "stopped by the operator";
  s.stopped_at.line = 3;
  s.stopped_at.file = s.playing_file;
  p = run_progress(s);
  EXPECT_EQ(p.line, 2u);
  EXPECT_EQ(p.file_line, 3u);
  // Its own lines: the line playing (a pointer of its own, the same name).
  s = status(MachineState::Running, 3, 4, 3, 1, 0);
  s.file = std::make_shared<const std::string>("top.sbp");
  s.playing_file = std::make_shared<const std::string>("top.sbp");
  EXPECT_EQ(run_progress(s).label(), "line 3 of 4 (50 %)");
}

// The reader is ahead of the card: at line 4 while the card still plays the file line 3
// called. The label gives the calling line the motion carries.
TEST(RunProgress, WhileACalledFilePlaysTheLabelGivesTheCallingLineOfTheMotionNotTheReaders) {
  ControllerStatus s = status(MachineState::Running, 4, 4, 2, 1, 0);
  s.file = std::make_shared<const std::string>("top.sbp");
  s.playing_file = std::make_shared<const std::string>("called.sbp");
  s.playing_caller_line = 3;
  EXPECT_EQ(run_progress(s).label(), "line 3 of 4 (50 %)");
  EXPECT_EQ(run_progress(s).file_line, 2u);
  s.state = MachineState::Stopped;
  s.message = "stopped by the operator";
  s.stopped_at.file = s.playing_file;
  s.stopped_at.line = 2;
  s.stopped_at.caller_line = 3;
  EXPECT_EQ(run_progress(s).line, 3u);
}

TEST(RunProgress, ACompletedRunIsWholeAndHasNothingRemaining) {
  const RunProgress p = run_progress(status(MachineState::Idle, 58, 58, 58, 118.6, 3));
  EXPECT_EQ(p.label(), "line 58 of 58 (100 %)");
  EXPECT_EQ(p.times(), "elapsed 0:01:59  remaining -");
}

TEST(RunProgress, NothingRunYet) {
  const RunProgress p = run_progress(ControllerStatus{});
  EXPECT_EQ(p.label(), "line 0 of 0 (0 %)");
  EXPECT_EQ(clock_text(3725), "1:02:05");
}

TEST(SpindleText, OnOffAndTheSpeedPlayedOrRecorded) {
  ControllerStatus s;
  EXPECT_EQ(spindle_text(s, 0), "spindle off");
  s.outputs = 0b101;
  s.spindle_rpm = 18000;
  EXPECT_EQ(spindle_text(s, 12000), "spindle on, 18000 RPM");  // the card's, not the file's
  s.spindle_rpm = 0;
  EXPECT_EQ(spindle_text(s, 12000), "spindle on, 12000 RPM (set on the spindle; TR recorded it)");
}

// feed_override.min 15 and max 150 (WinCNC's override L15 H150): the bounds are steps of
// their own, and reset (100 %) stays within them.
TEST(FeedOverride, TheProfilesBoundsHold) {
  Settings s = default_settings();
  s.feed_override.min = 15;
  s.feed_override.max = 150;
  const FeedOverrideBounds b = feed_override_bounds(s);
  EXPECT_DOUBLE_EQ(stepped_feed_override(0.2, -1, b), 0.15);
  EXPECT_DOUBLE_EQ(stepped_feed_override(0.15, 1, b), 0.2);
  EXPECT_DOUBLE_EQ(stepped_feed_override(1.5, 1, b), 1.5);
  EXPECT_DOUBLE_EQ(clamped_feed_override(2.0, b), 1.5);
  s.feed_override.max = 80;
  EXPECT_DOUBLE_EQ(clamped_feed_override(1.0, feed_override_bounds(s)), 0.8);
}

TEST(FeedOverride, StepsOfTenPercentWithinTenToTwoHundred) {
  const FeedOverrideBounds b = feed_override_bounds(default_settings());  // 10 % to 200 %
  EXPECT_DOUBLE_EQ(stepped_feed_override(1.0, 1, b), 1.1);
  EXPECT_DOUBLE_EQ(stepped_feed_override(1.0, -3, b), 0.7);
  EXPECT_DOUBLE_EQ(stepped_feed_override(1.04, 1, b), 1.1);  // to a whole ten
  EXPECT_DOUBLE_EQ(stepped_feed_override(1.04, -1, b), 1.0);
  EXPECT_DOUBLE_EQ(stepped_feed_override(0.1, -1, b), 0.1);
  EXPECT_DOUBLE_EQ(stepped_feed_override(2.0, 1, b), 2.0);
  EXPECT_DOUBLE_EQ(clamped_feed_override(5, b), 2.0);
  EXPECT_EQ(feed_override_text(1.2), "feed 120 %");
}

TEST(SpeedsText, VsSpeedsAndTheOverride) {
  SpeedSettings v;
  v.move = {2, 0.5, 0, 0, 0};
  v.jog = {6, 3, 0, 0, 0};
  EXPECT_EQ(speeds_text(v, Units::Inches, 0.9), "move XY 2, Z 0.5  jog XY 6, Z 3 in/s; feed 90 %");
}

}  // namespace
}  // namespace gantry::session
