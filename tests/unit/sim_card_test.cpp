// SimCard decoding and timing checks on hand-made words, the kinematics monitor on
// computed step trains, and StepGenerator -> SimCard end to end.
#include <gtest/gtest.h>

#include "segment_builders.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "gantry/motion/planned_segment.hpp"
#include "gantry/motion/trapezoid.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/step/step_generator.hpp"
#include "sim/kinematics_monitor.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

// Default pins: X step bit 0, dir bit 8; Y step bit 1, dir bit 9; ... Direction low means
// positive travel unless invert_dir.
constexpr std::uint32_t kXStep = 1u << 0, kXDir = 1u << 8;
constexpr std::uint32_t kYStep = 1u << 1, kYDir = 1u << 9;

std::uint32_t step_bit(int axis) {
  return 1u << axis;
}
std::uint32_t dir_bit(int axis) {
  return 1u << (8 + axis);
}

std::uint64_t count(const SimCard& card, TimingRule rule) {
  std::uint64_t n = 0;
  for (const TimingViolation& v : card.first_violations()) n += v.rule == rule;
  return n;
}

void play(SimCard& card, const std::vector<std::uint32_t>& words) {
  card.write(words);
}

// ---------------------------------------------------------------------------------------
// Inputs and faults: the simulated switches, operator and producer.

constexpr std::uint32_t kZStep = 1u << 2, kZDir = 1u << 10;

TEST(SimCardInputs, AtRestOnlyTheActiveLowEStopReadsHigh) {
  SimCard card(default_settings());  // E-stop bit 0 active-low, probe bit 1, limits 2-7
  EXPECT_EQ(card.inputs(), 1u);
  EXPECT_EQ(card.fault(), CardFault::None);
}

TEST(SimCardInputs, ProbeTouchesTheSurfaceWithoutStoppingTheCard) {
  SimWorld w;
  w.probe_z = -1.5 / 1018.5916;  // between Z's first and second step down
  SimCard card(default_settings(), false, w);
  play(card, {kZDir, kZDir, kZDir | kZStep, kZDir});
  EXPECT_EQ(card.inputs() & 2u, 0u);
  play(card, {kZDir | kZStep, kZDir, kZDir});
  EXPECT_EQ(card.inputs() & 2u, 2u);
  EXPECT_EQ(card.fault(), CardFault::None);
  EXPECT_EQ(card.ticks_played(), 7u);
}

TEST(SimCardInputs, ALimitSwitchStopsTheCardAfterTheStepThatTripsIt) {
  SimWorld w;
  w.max_switch[0] = 2 / 916.7324;  // X's second step reaches it
  SimCard card(default_settings(), false, w);
  play(card, {kXStep, 0, kXStep, 0, kXStep, 0, kXStep, 0});
  EXPECT_EQ(card.fault(), CardFault::Limit);
  EXPECT_EQ(card.ticks_played(), 3u);  // the word with the second step played, no more
  EXPECT_EQ(card.steps()[0], 2);
  EXPECT_EQ(card.inputs() & (1u << 3), 1u << 3);  // X max input active
  play(card, {kXStep, 0});
  EXPECT_EQ(card.ticks_played(), 3u);
}

TEST(SimCardInputs, EStopAtItsTimeStopsTheCardAndReadsLow) {
  SimWorld w;
  w.estop_at_s = 10 * 5e-6;  // tick 10 on the 200 kHz pacer
  SimCard card(default_settings(), false, w);
  card.start(200000);
  play(card, std::vector<std::uint32_t>(25, 0));
  EXPECT_EQ(card.fault(), CardFault::EStop);
  EXPECT_EQ(card.ticks_played(), 10u);
  EXPECT_EQ(card.inputs() & 1u, 0u);
}

TEST(SimCardInputs, AProducerStallWithWordsStillDueIsAnUnderrun) {
  SimWorld w;
  w.stall_at_s = 7 * 5e-6;
  SimCard card(default_settings(), false, w);
  card.start(200000);
  play(card, {kXStep, 0, 0, 0});
  EXPECT_EQ(card.fault(), CardFault::None);  // the queue ran dry with nothing due
  play(card, {kXStep, 0, 0, 0, kXStep, 0});
  EXPECT_EQ(card.fault(), CardFault::Underrun);
  EXPECT_EQ(card.ticks_played(), 7u);
  EXPECT_EQ(card.steps()[0], 2);
}

TEST(SimCardInputs, InputEventsSetTheirBitsAtTheirTimes) {
  SimWorld w;
  w.input_events = {{3 * 5e-6, 12, true}, {6 * 5e-6, 12, false}};
  SimCard card(default_settings(), false, w);
  card.start(200000);
  play(card, {0, 0, 0});
  EXPECT_EQ(card.inputs() & (1u << 12), 0u);
  play(card, {0});
  EXPECT_EQ(card.inputs() & (1u << 12), 1u << 12);
  EXPECT_EQ(card.sample_inputs().tick, 4u);
  EXPECT_EQ(card.sample_inputs().bits, card.inputs());
  play(card, {0, 0, 0});
  EXPECT_EQ(card.inputs() & (1u << 12), 0u);
  EXPECT_EQ(card.fault(), CardFault::None);
}

TEST(SimCardInputs, APositionInputReadsItsLevelWhileTheAxisIsThere) {
  SimWorld w;
  w.position_inputs.push_back({12, true, 0, 1.5 / 916.7324, true});  // X's second step on
  SimCard card(default_settings(), false, w);
  EXPECT_EQ(card.inputs() & (1u << 12), 0u);
  play(card, {kXStep, 0});
  EXPECT_EQ(card.inputs() & (1u << 12), 0u);
  play(card, {kXStep, 0});
  EXPECT_EQ(card.inputs() & (1u << 12), 1u << 12);
  play(card, {kXDir, kXDir | kXStep, kXDir});  // back to one step: off again
  EXPECT_EQ(card.inputs() & (1u << 12), 0u);
}

TEST(SimCardInputs, OnlyAnEventStillToComeMayChangeAnInputAtRest) {
  SimWorld w;
  w.input_events = {{3 * 5e-6, 12, true}};
  SimCard card(default_settings(), false, w);
  card.start(200000);
  EXPECT_TRUE(card.input_may_change(12, true));
  EXPECT_FALSE(card.input_may_change(12, false));
  play(card, {0, 0, 0, 0, 0});
  EXPECT_FALSE(card.input_may_change(12, true));  // it has passed
}

TEST(SimCardInputs, StopDropsWhatFollowsAndIdlesTheLines) {
  SimCard card(default_settings());
  play(card, {kXStep});
  card.stop(0);
  play(card, {kXStep, 0, kXStep});
  EXPECT_EQ(card.ticks_played(), 1u);
  EXPECT_EQ(card.steps()[0], 1);
  EXPECT_EQ(card.fault(), CardFault::None);
}

// ---------------------------------------------------------------------------------------
// Real time (--realtime): a late producer is an underrun, as on a real card (issue 22: the
// card moved its clock forward instead, and 2,749 late blocks ran as "done").

// `seconds` of idle words at the default 200 kHz.
std::vector<std::uint32_t> idle_for(double seconds) {
  return std::vector<std::uint32_t>(static_cast<std::size_t>(seconds * 200000), 0u);
}

TEST(SimCardRealtime, AProducerLateWhileWordsAreDueIsAnUnderrunWithItsLateness) {
  SimCard card(default_settings(), true);
  card.set_realtime_queue(0.001);
  card.set_start_words(0);  // the first word starts a stream
  card.start(200000);
  play(card, idle_for(0.002));
  EXPECT_EQ(card.fault(), CardFault::None);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));  // the producer starves it
  play(card, idle_for(0.002));
  EXPECT_EQ(card.fault(), CardFault::Underrun);
  EXPECT_EQ(card.ticks_played(), 400u);  // the late words never played
  ASSERT_TRUE(card.late_s().has_value());
  EXPECT_GE(*card.late_s(), 0.028);  // at least the sleep, less the 2 ms of words queued
  EXPECT_NE(card.fault_detail().find("ms late: the card's queue ran dry at 0.0020 s"),
            std::string::npos)
      << card.fault_detail();
}

TEST(SimCardRealtime, RestBetweenStretchesOfOutputIsNoUnderrun) {
  SimCard card(default_settings(), true);
  card.set_realtime_queue(0.001);
  card.set_start_words(0);  // the first word starts a stream
  card.start(200000);
  play(card, idle_for(0.002));
  card.end_stream();  // at rest (a hold, the end of a move)
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  play(card, idle_for(0.002));
  card.drain();
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  play(card, idle_for(0.002));
  EXPECT_EQ(card.fault(), CardFault::None);
  EXPECT_EQ(card.ticks_played(), 1200u);
  EXPECT_EQ(card.fault_detail(), "");
}

// A stream that begins on an empty queue plays once half the lead is queued (10 ms at the
// default 20 ms), as the real cards start theirs: a producer that writes the first block,
// then is late, has that head start, and is no more late for words that never started.
// A shorter stream plays when it ends at rest.
TEST(SimCardRealtime, AStreamStartsOnceHalfTheLeadIsQueuedOrAtRest) {
  SimCard card(default_settings(), true);
  EXPECT_EQ(card.start_words(), 2000u);  // 10 ms at 200 kHz
  EXPECT_EQ(SimCard(default_settings(), false).start_words(), 0u);
  card.start(200000);
  play(card, idle_for(0.005));
  EXPECT_EQ(card.clock_tick(), 0u);  // below the threshold: its clock stands
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  play(card, idle_for(0.005));  // 10 ms queued: it starts now
  EXPECT_EQ(card.fault(), CardFault::None);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  play(card, idle_for(0.002));  // its 10 ms have played: late
  EXPECT_EQ(card.fault(), CardFault::Underrun);
  EXPECT_EQ(card.ticks_played(), 2000u);

  SimCard rest(default_settings(), true);
  rest.start(200000);
  play(rest, idle_for(0.002));
  rest.end_stream();  // at rest below the threshold: what it holds plays from now
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_EQ(rest.clock_tick(), 400u);
  play(rest, idle_for(0.002));  // a new stream after the last one played out
  rest.drain();
  EXPECT_EQ(rest.fault(), CardFault::None);
  EXPECT_EQ(rest.ticks_played(), 800u);
}

// Started again after a stop (an E-stop acknowledged), the tick count goes on: the wall
// clock's origin must follow it, or the card waits for ticks that have already played (a
// wedge) and a late producer goes unseen.
TEST(SimCardRealtime, ARestartNeitherWaitsForTheTicksBeforeItNorHidesALateProducer) {
  SimCard card(default_settings(), true);
  card.set_realtime_queue(0.001);
  card.set_start_words(0);  // the first word starts a stream
  card.start(200000);
  play(card, idle_for(0.3));
  card.stop(0);
  card.start(200000);
  const auto before = std::chrono::steady_clock::now();
  play(card, idle_for(0.002));
  EXPECT_LT(std::chrono::steady_clock::now() - before, std::chrono::milliseconds(150));
  EXPECT_EQ(card.fault(), CardFault::None);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  play(card, idle_for(0.002));
  EXPECT_EQ(card.fault(), CardFault::Underrun);
  EXPECT_EQ(card.ticks_played(), 60400u);
}

// ---------------------------------------------------------------------------------------
// Step counting.

TEST(SimCardSteps, CountsRisingEdgesAsPositiveSteps) {
  SimCard card(default_settings());
  play(card, {0, kXStep, 0, 0, kXStep, 0, kXStep, 0});
  EXPECT_EQ(card.steps()[0], 3);
  for (int i = 1; i < kAxisCount; ++i) EXPECT_EQ(card.steps()[i], 0);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, AHeldLineIsOneStep) {
  SimCard card(default_settings());
  play(card, {kXStep, kXStep, kXStep, kXStep, 0, 0});
  EXPECT_EQ(card.steps()[0], 1);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, DirectionHighCountsNegative) {
  SimCard card(default_settings());
  play(card, {kXDir, kXDir, kXDir | kXStep, kXDir, kXDir | kXStep, kXDir, kXDir | kXStep, kXDir});
  EXPECT_EQ(card.steps()[0], -3);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, CountsBothDirectionsToTheNetPosition) {
  SimCard card(default_settings());
  // +2, then the direction goes high and stays 2 ticks before three -1 steps.
  play(card, {kXStep, 0, kXStep, 0, kXDir, kXDir, kXDir | kXStep, kXDir, kXDir | kXStep, kXDir,
              kXDir | kXStep, kXDir, 0, 0, kXStep, 0});
  EXPECT_EQ(card.steps()[0], 2 - 3 + 1);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, EveryAxisCountsOnItsOwnBits) {
  SimCard card(default_settings());
  std::vector<std::uint32_t> words;
  std::uint32_t dirs = 0;
  for (int i = 0; i < kAxisCount; i += 2) dirs |= dir_bit(i);  // X, Z, B negative
  words.push_back(dirs);
  for (int i = 0; i < kAxisCount; ++i) {  // axis i steps i + 1 times
    for (int k = 0; k <= i; ++k) {
      words.push_back(dirs | step_bit(i));
      words.push_back(dirs);
    }
  }
  play(card, words);
  EXPECT_EQ(card.steps(), (Steps6{-1, 2, -3, 4, -5, 6}));
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, SimultaneousStepsOnTwoAxes) {
  SimCard card(default_settings());
  play(card, {kXStep | kYStep, 0, kXStep | kYStep, 0, kYStep, 0});
  EXPECT_EQ(card.steps()[0], 2);
  EXPECT_EQ(card.steps()[1], 3);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, InvertDirMakesDirectionHighPositive) {
  Settings s = default_settings();
  s.pins[0].invert_dir = true;
  SimCard card(s);
  // The line rests high (positive): three steps with it high, then two with it low.
  play(card, {kXDir, kXDir | kXStep, kXDir, kXDir | kXStep, kXDir, kXDir | kXStep, kXDir, 0, 0,
              kXStep, 0, kXStep, 0});
  EXPECT_EQ(card.steps()[0], 3 - 2);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, InvertDirRestsHighSoALowLineIsAChange) {
  Settings s = default_settings();
  s.pins[0].invert_dir = true;
  SimCard card(s);
  play(card, {0, kXStep, 0});  // low from the first word: negative, and set 1 tick before
  EXPECT_EQ(card.steps()[0], -1);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, ActiveLowStepsIdleHighAndCountFallingEdges) {
  Settings s = default_settings();
  s.pins[0].step_active_low = true;
  s.card.step_pulse_us = 10;  // 2 ticks: a high gap of 1 tick would be a short pulse
  SimCard card(s);
  play(card, {kXStep, kXStep, 0, 0, kXStep, 0, 0, kXStep, kXStep});
  EXPECT_EQ(card.steps()[0], 2);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, ActiveLowIdleLevelIsNotAStep) {
  Settings s = default_settings();
  s.pins[0].step_active_low = true;
  SimCard card(s);
  play(card, std::vector<std::uint32_t>(10, kXStep));
  EXPECT_EQ(card.steps()[0], 0);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, ActiveLowWithInvertDir) {
  Settings s = default_settings();
  s.pins[1].step_active_low = true;
  s.pins[1].invert_dir = true;
  SimCard card(s);
  const std::uint32_t idle = kYStep | kYDir;
  play(card, {idle, kYDir, idle, kYDir, idle, kYStep, kYStep, 0, kYStep});
  EXPECT_EQ(card.steps()[1], 2 - 1);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardSteps, CountsWordsAndTime) {
  SimCard card(default_settings());
  play(card, std::vector<std::uint32_t>(1000, 0));
  play(card, std::vector<std::uint32_t>(500, 0));
  EXPECT_EQ(card.ticks_played(), 1500u);
  EXPECT_EQ(card.ticks_played(), 1500u);
  EXPECT_NEAR(card.time_s(), 1500 * 5e-6, 1e-12);
}

TEST(SimCardSteps, EdgesAcrossWriteCallsAreDecoded) {
  SimCard card(default_settings());
  play(card, {0, kXStep});
  play(card, {kXStep, 0});  // the pulse continues across the call: still one step
  play(card, {kXStep});
  play(card, {0});
  EXPECT_EQ(card.steps()[0], 2);
  EXPECT_EQ(card.timing_violations(), 0u);
}

// ---------------------------------------------------------------------------------------
// Timing rules.

TEST(SimCardTiming, CleanSequenceHasNoViolations) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;  // 2 ticks
  s.card.dir_setup_us = 10;   // 2 ticks
  SimCard card(s);
  play(card, {0, kXStep, kXStep, 0, kXStep, kXStep, 0, kXDir, kXDir, kXDir | kXStep, kXDir | kXStep,
              kXDir, kXDir, 0, 0, kXStep, kXStep, 0});
  EXPECT_EQ(card.steps()[0], 2 - 1 + 1);
  EXPECT_EQ(card.timing_violations(), 0u);
  EXPECT_TRUE(card.first_violations().empty());
}

TEST(SimCardTiming, PulseShorterThanTheSettingIsAViolation) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;  // 2 ticks
  SimCard card(s);
  play(card, {0, 0, kXStep, 0, 0, 0});  // 1 tick wide, ends at tick 3
  EXPECT_EQ(card.steps()[0], 1);        // still counted
  ASSERT_EQ(card.timing_violations(), 1u);
  ASSERT_EQ(card.first_violations().size(), 1u);
  const TimingViolation& v = card.first_violations()[0];
  EXPECT_EQ(v.rule, TimingRule::PulseWidth);
  EXPECT_EQ(v.axis, 0);
  EXPECT_EQ(v.tick, 3u);
}

TEST(SimCardTiming, PulseOfExactlyTheSettingIsFine) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;
  SimCard card(s);
  play(card, {0, kYStep, kYStep, 0, kYStep, kYStep, kYStep, 0});
  EXPECT_EQ(card.steps()[1], 2);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardTiming, ActiveLowShortPulseIsAViolation) {
  Settings s = default_settings();
  s.pins[0].step_active_low = true;
  s.card.step_pulse_us = 10;
  SimCard card(s);
  play(card, {kXStep, 0, kXStep, kXStep});  // low for one tick only
  EXPECT_EQ(card.steps()[0], 1);
  ASSERT_EQ(card.timing_violations(), 1u);
  EXPECT_EQ(card.first_violations()[0].rule, TimingRule::PulseWidth);
}

TEST(SimCardTiming, DirectionChangedWithTheStepIsASetupViolation) {
  SimCard card(default_settings());  // setup 5 us = 1 tick
  play(card, {0, kXDir | kXStep, kXDir, kXDir});
  EXPECT_EQ(card.steps()[0], -1);
  ASSERT_EQ(card.timing_violations(), 1u);
  const TimingViolation& v = card.first_violations()[0];
  EXPECT_EQ(v.rule, TimingRule::DirSetup);
  EXPECT_EQ(v.axis, 0);
  EXPECT_EQ(v.tick, 1u);
}

TEST(SimCardTiming, DirectionChangedLessThanSetupBeforeTheStepIsAViolation) {
  Settings s = default_settings();
  s.card.dir_setup_us = 10;  // 2 ticks
  SimCard card(s);
  play(card, {0, kXDir, kXDir | kXStep, kXDir});  // 1 tick of setup
  ASSERT_EQ(card.timing_violations(), 1u);
  EXPECT_EQ(card.first_violations()[0].rule, TimingRule::DirSetup);
  EXPECT_EQ(card.first_violations()[0].tick, 2u);
}

TEST(SimCardTiming, DirectionChangedExactlySetupBeforeTheStepIsFine) {
  Settings s = default_settings();
  s.card.dir_setup_us = 10;
  SimCard card(s);
  play(card, {0, kXDir, kXDir, kXDir | kXStep, kXDir});
  EXPECT_EQ(card.steps()[0], -1);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardTiming, ZeroSetupAllowsDirectionWithTheStep) {
  Settings s = default_settings();
  s.card.dir_setup_us = 0;
  SimCard card(s);
  play(card, {0, kXDir | kXStep, kXDir});
  EXPECT_EQ(card.steps()[0], -1);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardTiming, DirectionChangedDuringAPulseIsAViolation) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;  // the pulse is 2 ticks, so it is still high at tick 2
  SimCard card(s);
  play(card, {0, kXStep, kXStep | kXDir, kXDir, kXDir});
  EXPECT_EQ(card.steps()[0], 1);  // direction at the active edge was positive
  ASSERT_EQ(card.timing_violations(), 1u);
  const TimingViolation& v = card.first_violations()[0];
  EXPECT_EQ(v.rule, TimingRule::DirDuringPulse);
  EXPECT_EQ(v.axis, 0);
  EXPECT_EQ(v.tick, 2u);
}

TEST(SimCardTiming, DirectionChangedWithTheTrailingEdgeIsNotDuringThePulse) {
  SimCard card(default_settings());
  play(card, {0, kXStep, kXDir, kXDir, kXDir | kXStep, kXDir});
  EXPECT_EQ(card.steps()[0], 0);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardTiming, StepsTwoTicksApartAreTheFastestLegalRate) {
  // One word per tick: the closest two rising edges of one line can be is 2 ticks (high, low,
  // high), which is exactly pacer / 2, the allowed rate.
  SimCard card(default_settings());
  play(card, {kXStep, 0, kXStep, 0, kXStep, 0, kXStep, 0});
  EXPECT_EQ(card.steps()[0], 4);
  EXPECT_EQ(card.timing_violations(), 0u);
}

TEST(SimCardTiming, EachViolationIsCountedAndTheFirstSixteenKept) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;
  SimCard card(s);
  std::vector<std::uint32_t> words;
  for (int k = 0; k < 20; ++k) {  // twenty 1-tick pulses on Y
    words.push_back(kYStep);
    words.push_back(0);
    words.push_back(0);
  }
  play(card, words);
  EXPECT_EQ(card.steps()[1], 20);
  EXPECT_EQ(card.timing_violations(), 20u);
  ASSERT_EQ(card.first_violations().size(), 16u);
  for (std::size_t k = 0; k < 16; ++k) {
    EXPECT_EQ(card.first_violations()[k].axis, 1);
    EXPECT_EQ(card.first_violations()[k].rule, TimingRule::PulseWidth);
    EXPECT_EQ(card.first_violations()[k].tick, 3 * k + 1);
  }
}

TEST(SimCardTiming, ViolationsOnDifferentAxesAreAttributed) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;
  SimCard card(s);
  // Y: a 1-tick pulse. X: direction and step in one word.
  play(card, {kYStep, 0, kXDir | kXStep, kXDir | kXStep, kXDir});
  ASSERT_EQ(card.timing_violations(), 2u);
  EXPECT_EQ(count(card, TimingRule::PulseWidth), 1u);
  EXPECT_EQ(count(card, TimingRule::DirSetup), 1u);
  EXPECT_EQ(card.first_violations()[0].axis, 1);
  EXPECT_EQ(card.first_violations()[0].rule, TimingRule::PulseWidth);
  EXPECT_EQ(card.first_violations()[1].axis, 0);
  EXPECT_EQ(card.first_violations()[1].rule, TimingRule::DirSetup);
}

// The card plays a run of identical words in one step and checks the rules at the edges
// only (issue 27): an edge inside long runs is judged at its own tick.
std::vector<std::uint32_t> runs(std::initializer_list<std::pair<std::uint32_t, int>> parts) {
  std::vector<std::uint32_t> words;
  for (const auto& [w, n] : parts) words.insert(words.end(), static_cast<std::size_t>(n), w);
  return words;
}

TEST(SimCardRuns, AShortPulseBetweenLongRunsIsReportedAtItsTick) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;  // 2 ticks
  SimCard card(s);
  play(card, runs({{0, 5001}, {kXStep, 1}, {0, 7000}}));  // 1 tick wide, ends at tick 5002
  EXPECT_EQ(card.steps()[0], 1);
  EXPECT_EQ(card.ticks_played(), 12002u);
  ASSERT_EQ(card.timing_violations(), 1u);
  EXPECT_EQ(card.first_violations()[0].rule, TimingRule::PulseWidth);
  EXPECT_EQ(card.first_violations()[0].tick, 5002u);
}

TEST(SimCardRuns, ADirectionChangeTooCloseToAStepInsideLongRunsIsReported) {
  Settings s = default_settings();
  s.card.dir_setup_us = 10;  // 2 ticks
  SimCard card(s);
  // Direction at 3000, the step one tick later; then a long pulse with the direction
  // changed under it at 9000.
  play(card, runs({{0, 3000}, {kXDir, 1}, {kXDir | kXStep, 4000}, {kXStep, 3000}, {0, 999}}));
  EXPECT_EQ(card.steps()[0], -1);
  ASSERT_EQ(card.timing_violations(), 2u);
  EXPECT_EQ(card.first_violations()[0].rule, TimingRule::DirSetup);
  EXPECT_EQ(card.first_violations()[0].tick, 3001u);
  EXPECT_EQ(card.first_violations()[1].rule, TimingRule::DirDuringPulse);
  EXPECT_EQ(card.first_violations()[1].tick, 7001u);
}

TEST(SimCardRuns, AnEStopInsideARunStopsTheCardAtItsTick) {
  SimWorld w;
  w.estop_at_s = 12345 * 5e-6;
  SimCard card(default_settings(), false, w);
  card.start(200000);
  play(card, std::vector<std::uint32_t>(20000, 0));
  EXPECT_EQ(card.fault(), CardFault::EStop);
  EXPECT_EQ(card.ticks_played(), 12345u);
}

TEST(SimCardRuns, AnInputEventInsideARunFiresTheWatchAtItsTick) {
  SimWorld w;
  w.input_events = {{7777 * 5e-6, 12, true}};
  SimCard card(default_settings(), false, w);
  card.start(200000);
  card.watch({1u << 12, 1u << 12, 1u << 12});  // stop the card on it
  play(card, std::vector<std::uint32_t>(10000, 0));
  ASSERT_TRUE(card.watch_fired());
  EXPECT_EQ(card.watch_fired()->tick, 7777u);
  EXPECT_EQ(card.ticks_played(), 7777u);
}

// The same words written at once and one at a time: the same steps, violations (and their
// ticks), time and trace. One word per write has no run to skip.
TEST(SimCardRuns, WordsInOneWriteDecodeAsWordsWrittenOneByOne) {
  Settings s = default_settings();
  s.card.step_pulse_us = 10;
  s.card.dir_setup_us = 10;
  std::vector<std::uint32_t> words;
  std::uint32_t state = 0;
  for (int k = 0; k < 3000; ++k) {  // pulses, direction changes and the pump, some too close
    const int n = 1 + (k * 7919) % 23;
    switch (k % 5) {
      case 0:
        state ^= kXStep;
        break;
      case 1:
        state ^= 1u << 16;
        break;  // the charge pump: no rule
      case 2:
        state ^= kYStep;
        break;
      case 3:
        state ^= (k % 3 == 0 ? kXDir : kYDir);
        break;
      default:
        state ^= kXStep | kYStep;
    }
    words.insert(words.end(), static_cast<std::size_t>(n), state);
  }
  const std::string trace_a = testing::TempDir() + "runs_a.trace";
  const std::string trace_b = testing::TempDir() + "runs_b.trace";
  {
    SimCard a(s, false, {}, trace_a), b(s, false, {}, trace_b);
    play(a, words);
    for (std::uint32_t w : words) play(b, {w});
    EXPECT_EQ(a.steps(), b.steps());
    EXPECT_EQ(a.ticks_played(), b.ticks_played());
    EXPECT_GT(a.timing_violations(), 0u);
    EXPECT_EQ(a.timing_violations(), b.timing_violations());
    ASSERT_EQ(a.first_violations().size(), b.first_violations().size());
    for (std::size_t k = 0; k < a.first_violations().size(); ++k) {
      EXPECT_EQ(a.first_violations()[k].tick, b.first_violations()[k].tick);
      EXPECT_EQ(a.first_violations()[k].rule, b.first_violations()[k].rule);
      EXPECT_EQ(a.first_violations()[k].axis, b.first_violations()[k].axis);
    }
    a.stop(0);
    b.stop(0);
  }  // the traces are complete once the cards are gone
  {  // without a trace the pump's flips are no edge: the same again, and the same last word
    SimCard a(s), b(s);
    play(a, words);
    for (std::uint32_t w : words) play(b, {w});
    EXPECT_EQ(a.steps(), b.steps());
    EXPECT_EQ(a.ticks_played(), b.ticks_played());
    EXPECT_EQ(a.last_word(), b.last_word());
    EXPECT_EQ(a.last_word(), words.back());
    EXPECT_EQ(a.timing_violations(), b.timing_violations());
    ASSERT_EQ(a.first_violations().size(), b.first_violations().size());
    for (std::size_t k = 0; k < a.first_violations().size(); ++k)
      EXPECT_EQ(a.first_violations()[k].tick, b.first_violations()[k].tick);
  }
  std::ifstream fa(trace_a), fb(trace_b);
  const std::string ta((std::istreambuf_iterator<char>(fa)), {}),
      tb((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_GT(ta.size(), 1000u);
  EXPECT_EQ(ta, tb);
}

TEST(SimCardTiming, RuleNamesAreDistinct) {
  EXPECT_STRNE(rule_name(TimingRule::PulseWidth), rule_name(TimingRule::DirSetup));
  EXPECT_STRNE(rule_name(TimingRule::DirSetup), rule_name(TimingRule::DirDuringPulse));
  EXPECT_STRNE(rule_name(TimingRule::PulseWidth), rule_name(TimingRule::DirDuringPulse));
}

// ---------------------------------------------------------------------------------------
// KinematicsMonitor on computed step trains (default axes: X 916.7324 steps/in, 8 in/s,
// 20 in/s^2; A 13.8889 steps/deg, 90 deg/s, 360 deg/s^2).

constexpr double kTick = 5e-6;

std::array<AxisLimits, kAxisCount> default_limits() {
  const Settings s = default_settings();
  std::array<AxisLimits, kAxisCount> out{};
  for (int i = 0; i < kAxisCount; ++i)
    out[i] = {s.axes[i].steps_per_unit, s.axes[i].max_speed, s.axes[i].max_accel};
  return out;
}

// Steps at a constant rate of `v` units/s for `seconds`, from `start_tick`.
std::vector<std::int64_t> constant_rate(double spu, double v, double seconds,
                                        std::int64_t start_tick = 0) {
  std::vector<std::int64_t> ticks;
  const double period = 1 / (spu * v);
  for (int k = 0; k * period <= seconds; ++k)
    ticks.push_back(start_tick + std::llround(k * period / kTick));
  return ticks;
}

// Steps under constant acceleration `a` from rest: step k at t_k = sqrt(2 k / (spu a)).
std::vector<std::int64_t> constant_accel(double spu, double a, double seconds) {
  std::vector<std::int64_t> ticks;
  for (int k = 0;; ++k) {
    const double t = std::sqrt(2.0 * k / (spu * a));
    if (t > seconds) break;
    ticks.push_back(std::llround(t / kTick));
  }
  return ticks;
}

TEST(KinematicsMonitor, ConstantRateGivesTheVelocityRatio) {
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  for (std::int64_t t : constant_rate(limits[0].steps_per_unit, 2.0, 0.5)) m.on_step(0, t, true);
  m.finish();
  EXPECT_NEAR(m.velocity_ratio(0), 2.0 / 8.0, 0.25 * 0.005);
  EXPECT_NEAR(m.max_velocity_ratio(), 2.0 / 8.0, 0.25 * 0.005);
  EXPECT_LT(m.accel_ratio(0), 0.05);  // constant speed: only tick rounding
  EXPECT_DOUBLE_EQ(m.velocity_ratio(1), 0);
}

TEST(KinematicsMonitor, ConstantRateNegativeAndRotary) {
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  for (std::int64_t t : constant_rate(limits[0].steps_per_unit, 6.0, 0.3)) m.on_step(0, t, false);
  for (std::int64_t t : constant_rate(limits[3].steps_per_unit, 45.0, 0.5)) m.on_step(3, t, true);
  m.finish();
  EXPECT_NEAR(m.velocity_ratio(0), 6.0 / 8.0, 0.75 * 0.005);
  EXPECT_NEAR(m.velocity_ratio(3), 45.0 / 90.0, 0.5 * 0.005);
  EXPECT_NEAR(m.max_velocity_ratio(), 0.75, 0.75 * 0.005);
}

TEST(KinematicsMonitor, ConstantAccelerationGivesTheAccelRatio) {
  const auto limits = default_limits();
  const double a = 10;  // half of X's 20 in/s^2
  KinematicsMonitor m(limits, kTick);
  for (std::int64_t t : constant_accel(limits[0].steps_per_unit, a, 0.3)) m.on_step(0, t, true);
  m.finish();
  EXPECT_NEAR(m.accel_ratio(0), a / 20, 0.05 * a / 20);
  EXPECT_NEAR(m.max_accel_ratio(), a / 20, 0.05 * a / 20);
  // The last window's mean velocity is just below the final 3 in/s.
  EXPECT_GT(m.velocity_ratio(0), 2.8 / 8);
  EXPECT_LE(m.velocity_ratio(0), 3.0 / 8);
  EXPECT_EQ(m.violations(), 0u);
}

// From rest the first windows hold few steps and read up to about 1.5 % high (a train at
// exactly 20 in/s^2 reads 1.014), so 90 % of the limit is safely within it.
TEST(KinematicsMonitor, AccelerationWithinTheLimitIsNoViolation) {
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  for (std::int64_t t : constant_accel(limits[0].steps_per_unit, 18, 0.3)) m.on_step(0, t, true);
  m.finish();
  EXPECT_NEAR(m.accel_ratio(0), 0.9, 0.05 * 0.9);
  EXPECT_EQ(m.violations(), 0u);
  EXPECT_TRUE(m.first_violations().empty());
}

TEST(KinematicsMonitor, ExcessiveAccelerationGivesARatioAboveOne) {
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  for (std::int64_t t : constant_accel(limits[0].steps_per_unit, 30, 0.2)) m.on_step(0, t, true);
  m.finish();
  EXPECT_NEAR(m.accel_ratio(0), 1.5, 0.075);
  // Every window-to-window change is one: 0.2 s in windows of at least 10 ms.
  EXPECT_GT(m.violations(), 5u);
  ASSERT_FALSE(m.first_violations().empty());
  const KinematicsMonitor::Violation& v = m.first_violations().front();
  EXPECT_EQ(v.axis, 0);
  EXPECT_TRUE(v.accel);
  EXPECT_NEAR(v.ratio, 1.5, 0.075);
}

TEST(KinematicsMonitor, SpeedAboveTheLimitGivesARatioAboveOne) {
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  for (std::int64_t t : constant_rate(limits[0].steps_per_unit, 10.0, 0.2)) m.on_step(0, t, true);
  for (std::int64_t t : constant_rate(limits[4].steps_per_unit, 100.0, 0.2)) m.on_step(4, t, false);
  m.finish();
  EXPECT_NEAR(m.velocity_ratio(0), 10.0 / 8.0, 1.25 * 0.005);
  EXPECT_NEAR(m.velocity_ratio(4), 100.0 / 90.0, 1.11 * 0.005);
  EXPECT_GT(m.max_velocity_ratio(), 1.0);
  // Every window of both axes: about 20 each in 0.2 s.
  EXPECT_GE(m.violations(), 30u);
  ASSERT_FALSE(m.first_violations().empty());
  EXPECT_FALSE(m.first_violations().front().accel);
  EXPECT_EQ(m.first_violations().front().axis, 0);
}

TEST(KinematicsMonitor, InstantReversalShowsAsALargeAcceleration) {
  // 2 in/s forward for 0.1 s, then straight back at 2 in/s: windows are cut at the reversal,
  // so the speed is right on both sides and the sign change reads as a huge acceleration.
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  const auto fwd = constant_rate(limits[0].steps_per_unit, 2.0, 0.1);
  for (std::int64_t t : fwd) m.on_step(0, t, true);
  for (std::int64_t t : constant_rate(limits[0].steps_per_unit, 2.0, 0.1, fwd.back() + 109))
    m.on_step(0, t, false);
  m.finish();
  EXPECT_NEAR(m.velocity_ratio(0), 0.25, 0.25 * 0.005);
  EXPECT_GT(m.accel_ratio(0), 10);  // about 4 in/s over ~10 ms = 400 in/s^2 = 20 x 20
}

TEST(KinematicsMonitor, ReversalClosesAWindowBeforeItIsFull) {
  // 5 steps forward and 5 back at 2 in/s, all within one 10 ms window's span: two windows,
  // +2 and -2 in/s about 2.7 ms apart, so a huge acceleration; one mixed window would read
  // a steady 2 in/s.
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  const auto train = constant_rate(limits[0].steps_per_unit, 2.0, 0.005);
  ASSERT_GE(train.size(), 10u);
  for (std::size_t k = 0; k < 10; ++k) m.on_step(0, train[k], k < 5);
  m.finish();
  EXPECT_NEAR(m.velocity_ratio(0), 0.25, 0.25 * 0.01);
  EXPECT_GT(m.accel_ratio(0), 50);  // 4 in/s over 545 ticks = 1467 in/s^2 = 73 x 20
}

TEST(KinematicsMonitor, FinishClosesTheOpenWindow) {
  // A train shorter than one 10 ms window is only measured when the run is finished.
  const auto limits = default_limits();
  KinematicsMonitor m(limits, kTick);
  for (std::int64_t t : constant_rate(limits[0].steps_per_unit, 4.0, 0.005)) m.on_step(0, t, true);
  EXPECT_DOUBLE_EQ(m.velocity_ratio(0), 0);
  m.finish();
  EXPECT_NEAR(m.velocity_ratio(0), 0.5, 0.5 * 0.01);
}

TEST(KinematicsMonitor, SimCardFeedsItFromDecodedSteps) {
  Settings s = default_settings();
  SimCard card(s);
  card.start(s.card.pacer_hz());
  const auto ticks = constant_rate(s.axes[1].steps_per_unit, 4.0, 0.2);
  std::vector<std::uint32_t> words(static_cast<std::size_t>(ticks.back() + 2), 0);
  for (std::int64_t t : ticks) words[static_cast<std::size_t>(t)] = kYStep;
  play(card, words);
  EXPECT_EQ(card.steps()[1], static_cast<std::int64_t>(ticks.size()));
  EXPECT_EQ(card.timing_violations(), 0u);
  EXPECT_NEAR(card.kinematics().velocity_ratio(1), 0.5, 0.5 * 0.005);
  EXPECT_LT(card.kinematics().max_accel_ratio(), 0.05);
}

// ---------------------------------------------------------------------------------------
// StepGenerator -> SimCard.

using test::segment;
using test::vec;

struct EndToEnd {
  explicit EndToEnd(const Settings& s) : settings(s), card(s), gen(s, card) {
    card.start(s.card.pacer_hz());
  }
  Settings settings;
  SimCard card;
  StepGenerator gen;
};

TEST(SimCardEndToEnd, StepsMatchTheGeneratorAndNothingIsViolated) {
  EndToEnd e(default_settings());
  const Vec6 p0 = Vec6::Zero(), p1 = vec(0.5, 0.25, -0.1, 3), p2 = vec(0.2, 0.4, 0.05, -2, 1),
             p3 = vec(0.2, 0.1, 0.05, -2, 1, 4), p4 = vec(0.3, 0.1, -0.02);
  // Speeds and accelerations within every axis's limits, as the planner would make them.
  e.gen.segment(segment(p0, p1, 0, 1.5, 0, 10));
  e.gen.segment(segment(p1, p2, 0, 2.0, 0, 12));
  e.gen.segment(segment(p2, p3, 0, 3.0, 0, 14));
  e.gen.segment(segment(p3, p4, 0, 2.0, 0, 14));
  e.gen.flush();
  EXPECT_EQ(e.card.steps(), e.gen.position());
  for (int i = 0; i < kAxisCount; ++i)
    EXPECT_EQ(e.card.steps()[i], std::llround(p4[i] * e.settings.axes[i].steps_per_unit))
        << "axis " << i;
  EXPECT_EQ(e.card.timing_violations(), 0u);
  EXPECT_EQ(e.card.ticks_played(), static_cast<std::uint64_t>(e.gen.tick()));
  EXPECT_LE(e.card.kinematics().max_velocity_ratio(), 1.0);
  EXPECT_LE(e.card.kinematics().max_accel_ratio(), 1.0);
}

TEST(SimCardEndToEnd, WideningPulseAndSetupKeepsTheCardHappy) {
  Settings s = default_settings();
  s.card.step_pulse_us = 12;  // 3 ticks
  s.card.dir_setup_us = 17;   // 4 ticks
  s.pins[0].invert_dir = true;
  s.pins[1].step_active_low = true;
  EndToEnd e(s);
  const Vec6 p1 = vec(0.3, -0.2, 0.1), p2 = vec(-0.1, 0.1, -0.1), p3 = vec(0.05, 0.1, 0);
  e.gen.segment(segment(Vec6::Zero(), p1, 0, 2.0, 0, 14));
  e.gen.segment(segment(p1, p2, 0, 2.0, 0, 14));
  e.gen.segment(segment(p2, p3, 0, 1.0, 0, 14));
  e.gen.flush();
  EXPECT_EQ(e.card.steps(), e.gen.position());
  EXPECT_EQ(e.card.steps()[0], std::llround(0.05 * s.axes[0].steps_per_unit));
  EXPECT_EQ(e.card.timing_violations(), 0u);
}

TEST(SimCardEndToEnd, AbruptFastReversalHasNoViolations) {
  EndToEnd e(default_settings());
  const double spu = e.settings.axes[0].steps_per_unit;
  const double v = 100e3 / spu;
  const Vec6 p1 = vec(20 / spu), p2 = vec(10 / spu);
  e.gen.segment(segment(Vec6::Zero(), p1, v, v, v, 1e6));
  e.gen.segment(segment(p1, p2, v, v, v, 1e6));
  e.gen.flush();
  EXPECT_EQ(e.card.steps(), e.gen.position());
  EXPECT_EQ(e.card.steps()[0], 10);
  EXPECT_EQ(e.card.timing_violations(), 0u);
}

}  // namespace
}  // namespace gantry
