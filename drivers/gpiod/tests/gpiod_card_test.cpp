// The libgpiod card through its seams: FakeGpioLines for the hardware and VirtualClock for
// time, so every test is deterministic and runs in milliseconds. The tests at the end open a
// real chip and skip themselves where there is none.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "gantry/hal/pin_map.hpp"
#include "gantry/hal/word_ring.hpp"
#include "gantry/settings/settings.hpp"
#include "gpiod/fake_gpio_lines.hpp"
#include "gpiod/gpio_map.hpp"
#include "gpiod/gpio_map_profile.hpp"
#include "gpiod/gpiod_card.hpp"
#include "gpiod/libgpiod_lines.hpp"
#include "gpiod/open_gpiod.hpp"
#include "gpiod/pacer_schedule.hpp"
#include "gpiod/tick_player.hpp"
#include "gpiod/virtual_clock.hpp"

namespace gantry {
namespace {

using namespace std::chrono_literals;

// Output word bits and the lines they drive in the test map.
constexpr std::uint32_t kXStep = 1u << 0, kXDir = 1u << 8, kYStep = 1u << 1;
constexpr unsigned kXStepLine = 10, kXDirLine = 11, kYStepLine = 12;
// Input lines and the input-word bits they set.
constexpr unsigned kLimitLine = 20, kEStopLine = 21, kProbeLine = 22;
constexpr std::uint32_t kLimitBit = 1u << 0, kEStopBit = 1u << 4, kProbeBit = 1u << 5;

constexpr double kPacerHz = 1000;  // 1 ms ticks: round numbers in virtual time
constexpr std::int64_t kPeriodNs = 1'000'000;

GpioMap test_map() {
  GpioMap map;
  map.chip_path = "/dev/gpiochip-test";
  map.pacer_hz = kPacerHz;
  map.outputs = {{0, kXStepLine}, {8, kXDirLine}, {1, kYStepLine}};
  map.inputs = {{kLimitLine, 0}, {kEStopLine, 4}, {kProbeLine, 5}};
  map.input_sample_hz = 100;  // every 10 ticks
  map.queue_words = 64;
  map.start_words = 4;
  map.realtime = false;  // tests must not need privileges or lock the test process's memory
  return map;
}

// A card on fake lines and a virtual clock; the fake stamps changes with the card's tick.
struct Rig {
  FakeGpioLines* lines;
  VirtualClock* clock;
  std::unique_ptr<GpiodCard> card;

  explicit Rig(const GpioMap& map, VirtualClock::Mode mode = VirtualClock::Mode::FreeRunning,
               const std::function<void(FakeGpioLines&)>& before_open = {}) {
    auto fake = std::make_unique<FakeGpioLines>(map);
    auto virtual_clock = std::make_unique<VirtualClock>(mode);
    lines = fake.get();
    clock = virtual_clock.get();
    if (before_open) before_open(*fake);
    card = std::make_unique<GpiodCard>(map, std::move(fake), std::move(virtual_clock));
    lines->set_tick_source([c = card.get()] { return c->ticks_played(); });
  }
};

// Polls `done` for up to two seconds of real time.
bool eventually(const std::function<bool()>& done) {
  const auto limit = std::chrono::steady_clock::now() + 2s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > limit) return false;
    std::this_thread::sleep_for(100us);
  }
  return true;
}

bool contains(const std::vector<std::string>& messages, const std::string& text) {
  for (const std::string& m : messages)
    if (m.find(text) != std::string::npos) return true;
  return false;
}

// --- Words to lines -------------------------------------------------------------------------

TEST(GpiodCard, WordsBecomeLineChangesAtTheirTicks) {
  Rig rig(test_map());
  rig.card->start(kPacerHz);
  const std::vector<std::uint32_t> words = {
      0,               // tick 0: the lines already show 0 (initial_word)
      kXStep,          // 1: X step pulse
      0,               // 2
      kXDir,           // 3: X direction flips
      kXDir | kXStep,  // 4
      kXDir,           // 5
      kXDir | kYStep,  // 6: Y step
      kXDir | kYStep,  // 7-9: held
      kXDir | kYStep,
      kXDir | kYStep,
  };
  rig.card->write(words);
  rig.card->drain();

  const std::vector<LineChange> expected = {
      {1, kXStepLine, 1}, {2, kXStepLine, 0}, {3, kXDirLine, 1},
      {4, kXStepLine, 1}, {5, kXStepLine, 0}, {6, kYStepLine, 1},
  };
  EXPECT_EQ(rig.lines->changes(), expected);
  EXPECT_EQ(rig.card->ticks_played(), words.size());
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.lines->level(kYStepLine), 1);
}

TEST(GpiodCard, OnlyChangedLinesAreWritten) {
  Rig rig(test_map());
  rig.card->start(kPacerHz);
  constexpr std::uint32_t kUnmapped = (1u << 3) | (1u << 20);  // no line for these bits
  rig.card->write(std::vector<std::uint32_t>{kUnmapped, 0, kUnmapped, kXStep, kXStep | kUnmapped,
                                             kXStep, kXStep | kXDir});
  rig.card->drain();

  // Unmapped bits make no write; X step changes once, X direction once, each on its own.
  const std::vector<LineChange> expected = {{3, kXStepLine, 1}, {6, kXDirLine, 1}};
  EXPECT_EQ(rig.lines->changes(), expected);
  EXPECT_EQ(rig.lines->write_calls(), 2u);
  EXPECT_EQ(rig.card->ticks_played(), 7u);
}

TEST(GpiodCard, ABitDrivesEveryLineMappedToIt) {
  GpioMap map = test_map();
  map.outputs.push_back({1, 13});  // a ganged Y axis: one step bit, two drivers
  Rig rig(map);
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>{0, kYStep, kYStep, 0});
  rig.card->drain();

  const std::vector<LineChange> expected = {
      {1, kYStepLine, 1}, {1, 13, 1}, {3, kYStepLine, 0}, {3, 13, 0}};
  EXPECT_EQ(rig.lines->changes(), expected);
  EXPECT_EQ(rig.lines->write_calls(), 2u);  // both lines in one call
}

TEST(GpiodCard, SleepsOnlyUntilTicksWhereSomethingHappens) {
  GpioMap map = test_map();
  map.queue_words = 128;  // the 100 words go in at once
  Rig rig(map);
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>(100, kXDir));
  rig.card->drain();

  // One wake-up for the direction change at tick 0 (also an input sample), one per later
  // input sample (ticks 10, 20, ..., 90) and one at tick 100, where the stream ends: the 90
  // ticks in between repeat the output and are slept through.
  EXPECT_EQ(rig.clock->sleeps(), 11u);
  EXPECT_EQ(rig.card->ticks_played(), 100u);
  EXPECT_EQ(rig.lines->changes(), (std::vector<LineChange>{{0, kXDirLine, 1}}));
}

TEST(GpiodCard, DeadlinesAreExactMultiplesOfThePeriod) {
  Rig rig(test_map(), VirtualClock::Mode::Gated);
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>{kXStep, 0, kXStep, 0, kXStep});

  std::vector<std::int64_t> deadlines;
  for (int tick = 0; tick < 5; ++tick) {
    auto due = rig.clock->wait_for_sleeper();
    ASSERT_TRUE(due) << "the player did not sleep before tick " << tick;
    deadlines.push_back(*due);
    rig.clock->advance_to(*due);
  }
  for (int tick = 1; tick < 5; ++tick) EXPECT_EQ(deadlines[tick] - deadlines[0], tick * kPeriodNs);
  rig.card->stop(0);
}

// --- Inputs ---------------------------------------------------------------------------------

TEST(GpiodCard, InputLinesSetTheirBitsOfTheInputWord) {
  Rig rig(test_map(), VirtualClock::Mode::FreeRunning, [](FakeGpioLines& lines) {
    lines.set_input(kLimitLine, 1);
    lines.set_input(kProbeLine, 1);
  });
  // Sampled when the card opens, before start(); the E-stop line is low, unmapped bits 0.
  EXPECT_EQ(rig.card->inputs(), kLimitBit | kProbeBit);

  rig.lines->set_input(kLimitLine, 0);
  rig.lines->set_input(kEStopLine, 1);
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>(5, 0));
  rig.card->drain();
  EXPECT_EQ(rig.card->inputs(), kEStopBit | kProbeBit);
  EXPECT_EQ(rig.card->fault(), CardFault::None);  // no E-stop bits configured
}

TEST(TickPlayer, SamplesTheInputsEveryNTicks) {
  const GpioMap map = test_map();
  FakeGpioLines lines(map);
  WordRing ring(map.queue_words);
  TickPlayer player(map, lines, ring);
  lines.set_tick_source([&] { return player.ticks_played(); });
  lines.set_input(kProbeLine, 1, 3);  // goes high at tick 3: first seen by the tick-10 sample
  ASSERT_EQ(player.sample_every_ticks(), 10u);

  std::vector<std::uint32_t> words;  // a change every tick: the player stops at every one
  for (int i = 0; i < 25; ++i) words.push_back(i % 2 ? kXStep : 0);
  ring.push(words);
  player.begin_stream();
  std::vector<std::uint32_t> inputs_after;  // inputs() once each tick has played
  for (;;) {
    const std::uint64_t tick = player.next_event_tick();
    if (player.play_through(tick, 0, true) != TickPlayer::Outcome::Played) break;
    inputs_after.push_back(player.inputs());
  }
  EXPECT_EQ(player.ticks_played(), 25u);
  EXPECT_EQ(lines.read_calls(), 3u);  // ticks 0, 10, 20
  ASSERT_EQ(inputs_after.size(), 25u);
  EXPECT_EQ(inputs_after[0], 0u);
  EXPECT_EQ(inputs_after[9], 0u);
  EXPECT_EQ(inputs_after[10], kProbeBit);
}

TEST(GpiodCard, ActiveEStopInputFaultsAtTheNextSampleWithoutPlayingThatTick) {
  GpioMap map = test_map();
  map.estop_bits = kEStopBit;
  map.active_low_bits = kEStopBit;  // normally closed: high while released
  Rig rig(map, VirtualClock::Mode::FreeRunning, [](FakeGpioLines& lines) {
    lines.set_input(kEStopLine, 1);
    lines.set_input(kEStopLine, 0, 13);  // pressed at tick 13
  });
  rig.card->start(kPacerHz);
  std::vector<std::uint32_t> words;
  for (int i = 0; i < 30; ++i) words.push_back(i % 2 ? kXStep : 0);
  rig.card->write(words);
  rig.card->drain();

  EXPECT_EQ(rig.card->fault(), CardFault::EStop);
  EXPECT_EQ(rig.card->ticks_played(), 20u);  // seen by the tick-20 sample, before its word
  EXPECT_EQ(rig.lines->changes().back().tick, 19u);
  EXPECT_EQ(rig.card->queued_words(), 10u);  // ticks 20-29 stay queued until stop()
  rig.card->write(words);                    // dropped after a fault
  EXPECT_EQ(rig.card->queued_words(), 10u);
}

TEST(GpiodCard, ActiveLimitInputFaultsTheCard) {
  GpioMap map = test_map();
  map.limit_bits = kLimitBit;  // active high
  Rig rig(map, VirtualClock::Mode::FreeRunning,
          [](FakeGpioLines& lines) { lines.set_input(kLimitLine, 1, 5); });
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>(30, kXDir));
  rig.card->drain();
  EXPECT_EQ(rig.card->fault(), CardFault::Limit);
  EXPECT_EQ(rig.card->ticks_played(), 10u);
}

TEST(GpiodCard, ALimitSwitchTripsAsItClosesSoTheToolCanMoveOffIt) {
  GpioMap map = test_map();
  map.limit_bits = kLimitBit;  // active high
  Rig rig(map, VirtualClock::Mode::FreeRunning, [](FakeGpioLines& lines) {
    lines.set_input(kLimitLine, 1);      // the tool stopped on it
    lines.set_input(kLimitLine, 0, 12);  // moved off it
    lines.set_input(kLimitLine, 1, 25);  // and onto it again
  });
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>(40, kXDir));
  rig.card->drain();
  EXPECT_EQ(rig.card->fault(), CardFault::Limit);
  EXPECT_EQ(rig.card->ticks_played(), 30u);  // seen by the tick-30 sample
}

// limits.travel_only and limits.debounce on the GPIO card's input path: the profile's rule
// (LimitFilter, every card's), X's min switch on the limit line.
GpioMap limit_rule_map(bool travel_only, int debounce) {
  GpioMap map = test_map();
  map.limit_bits = kLimitBit;  // active high
  Settings s = default_settings();
  s.limits.travel_only = travel_only;
  s.limits.debounce = debounce;
  s.inputs.min_bit = {0, -1, -1, -1, -1, -1};  // X's min switch is input bit 0
  s.inputs.max_bit = {-1, -1, -1, -1, -1, -1};
  map.limit_rule = LimitFilter(s, kPacerHz);
  return map;
}

TEST(GpiodCard, TravelOnlyTripsOnlyWhileTheAxisStepsTowardsTheSwitch) {
  for (const bool towards_minus : {true, false}) {
    Rig rig(limit_rule_map(true, 1), VirtualClock::Mode::FreeRunning,
            [](FakeGpioLines& lines) { lines.set_input(kLimitLine, 1, 5); });
    rig.card->start(kPacerHz);
    const std::uint32_t dir = towards_minus ? kXDir : 0;  // the direction line high: minus
    std::vector<std::uint32_t> words;
    for (int i = 0; i < 30; ++i) words.push_back(dir | (i % 2 ? kXStep : 0));
    rig.card->write(words);
    rig.card->drain();
    EXPECT_EQ(rig.card->fault(), towards_minus ? CardFault::Limit : CardFault::None);
    EXPECT_EQ(rig.card->ticks_played(), towards_minus ? 10u : 30u);  // the tick-10 sample
  }
}

TEST(GpiodCard, ADebouncedLimitCountsInputSamples) {
  // Active for one sample (10) only: forgotten; for two (10, 20): trips at the second.
  for (const int until : {15, 25}) {
    Rig rig(limit_rule_map(false, 2), VirtualClock::Mode::FreeRunning,
            [until](FakeGpioLines& lines) {
              lines.set_input(kLimitLine, 1, 5);
              lines.set_input(kLimitLine, 0, until);
            });
    rig.card->start(kPacerHz);
    rig.card->write(std::vector<std::uint32_t>(40, kXDir));
    rig.card->drain();
    EXPECT_EQ(rig.card->fault(), until == 15 ? CardFault::None : CardFault::Limit) << until;
    EXPECT_EQ(rig.card->ticks_played(), until == 15 ? 40u : 20u) << until;
  }
}

TEST(GpiodCard, TheWatchReportsAnEdgeAtTheTickOfItsSample) {
  Rig rig(test_map(), VirtualClock::Mode::FreeRunning,
          [](FakeGpioLines& lines) { lines.set_input(kProbeLine, 1, 23); });  // closes at 23
  rig.card->start(kPacerHz);
  EXPECT_FALSE(rig.card->watch_fired());
  rig.card->watch({kProbeBit, kProbeBit, 0});
  rig.card->write(std::vector<std::uint32_t>(40, kXDir));
  rig.card->drain();
  const std::optional<InputEdge> e = rig.card->watch_fired();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->tick, 30u);  // the sample after it, not the end of the words
  EXPECT_EQ(e->bit, 5);
  EXPECT_EQ(e->bits & kProbeBit, kProbeBit);
  rig.card->watch({});  // disarmed: nothing fired
  EXPECT_FALSE(rig.card->watch_fired());
}

// --- Underrun, drain, stop ------------------------------------------------------------------

TEST(GpiodCard, RunningDryBeforeDrainIsAnUnderrunWithExactTicks) {
  // Once with a word changing every tick, once with a held word the player sleeps through.
  for (bool toggling : {true, false}) {
    SCOPED_TRACE(toggling ? "toggling words" : "held word");
    Rig rig(test_map());
    rig.card->start(kPacerHz);
    std::vector<std::uint32_t> words;
    for (int i = 0; i < 10; ++i) words.push_back(toggling && i % 2 ? kXStep : kXDir);
    rig.card->write(words);  // at least start_words: plays, and nothing more comes

    ASSERT_TRUE(eventually([&] { return rig.card->fault() != CardFault::None; }));
    EXPECT_EQ(rig.card->fault(), CardFault::Underrun);
    EXPECT_EQ(rig.card->ticks_played(), 10u);
    rig.card->write(words);  // dropped: the card plays nothing more until started again
    rig.card->drain();       // returns at once after a fault
    EXPECT_EQ(rig.card->ticks_played(), 10u);
    EXPECT_EQ(rig.card->queued_words(), 0u);
  }
}

TEST(GpiodCard, DrainPlaysAShortStreamAndEndsItCleanly) {
  Rig rig(test_map());
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>{kXStep, 0});  // below start_words: waits
  rig.card->drain();                                       // ...until drain
  EXPECT_EQ(rig.card->ticks_played(), 2u);
  EXPECT_EQ(rig.card->fault(), CardFault::None);

  rig.card->write(std::vector<std::uint32_t>{kXStep, 0, kXStep});  // a second stream
  rig.card->drain();
  EXPECT_EQ(rig.card->ticks_played(), 5u);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.lines->changes().size(), 5u);
}

// Issue 26: a hold comes to rest and the stream ends there (Card::end_stream). The card ran
// dry after it and faulted (an underrun) while the tool stood still.
TEST(GpiodCard, AStreamEndedAtRestRunsDryCleanlyAndTheNextWordsStartANewOne) {
  Rig rig(test_map());
  rig.card->start(kPacerHz);
  std::vector<std::uint32_t> words;
  for (int i = 0; i < 10; ++i) words.push_back(i % 2 ? kXStep : kXDir);
  rig.card->write(words);
  rig.card->end_stream();  // at rest after these
  ASSERT_TRUE(eventually([&] { return rig.card->ticks_played() == 10u; }));
  rig.card->write(words);  // the resume, once the card has run dry
  rig.card->end_stream();
  ASSERT_TRUE(eventually(
      [&] { return rig.card->ticks_played() == 20u || rig.card->fault() != CardFault::None; }));
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  rig.card->write(std::vector<std::uint32_t>{kXStep, 0});  // below start_words: the end starts it
  rig.card->end_stream();
  ASSERT_TRUE(eventually(
      [&] { return rig.card->ticks_played() == 22u || rig.card->fault() != CardFault::None; }));
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.card->ticks_played(), 22u);
}

TEST(GpiodCard, StopDropsQueuedWordsAndSetsTheIdleWord) {
  Rig rig(test_map(), VirtualClock::Mode::Gated);
  rig.card->start(kPacerHz);
  std::vector<std::uint32_t> words;
  for (int i = 0; i < 8; ++i) words.push_back(kXDir | (i % 2 ? kXStep : 0));
  rig.card->write(words);

  for (int tick = 0; tick < 3; ++tick) {  // play ticks 0, 1 and 2
    auto due = rig.clock->wait_for_sleeper();
    ASSERT_TRUE(due);
    rig.clock->advance_to(*due);
  }
  ASSERT_TRUE(rig.clock->wait_for_sleeper());  // asleep before tick 3
  EXPECT_EQ(rig.card->ticks_played(), 3u);

  constexpr std::uint32_t kIdle = kYStep;  // an active-low Y step line rests high
  rig.card->stop(kIdle);
  EXPECT_EQ(rig.card->ticks_played(), 3u);
  EXPECT_EQ(rig.card->queued_words(), 0u);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  const std::vector<LineChange> expected = {
      {0, kXDirLine, 1}, {1, kXStepLine, 1}, {2, kXStepLine, 0},
      {3, kXDirLine, 0}, {3, kYStepLine, 1},  // the idle word, at the tick reached
  };
  EXPECT_EQ(rig.lines->changes(), expected);

  rig.card->write(words);  // dropped until the next start()
  EXPECT_EQ(rig.card->queued_words(), 0u);

  rig.card->start(kPacerHz);  // plays again, from tick 0
  rig.card->write(std::vector<std::uint32_t>{kIdle | kXStep});
  auto due = rig.clock->wait_for_sleeper(50ms);  // the stream waits for start_words...
  EXPECT_FALSE(due);
  std::thread drainer([&] { rig.card->drain(); });  // ...or drain()
  due = rig.clock->wait_for_sleeper();
  ASSERT_TRUE(due);
  rig.clock->advance_to(*due);  // tick 0
  due = rig.clock->wait_for_sleeper();
  ASSERT_TRUE(due);
  rig.clock->advance_to(*due);  // tick 1: no word, drain() asked: the stream ends
  drainer.join();
  EXPECT_EQ(rig.card->ticks_played(), 1u);
  EXPECT_EQ(rig.lines->level(kXStepLine), 1);
}

TEST(GpiodCard, WriteWaitsWhileTheQueueIsFull) {
  GpioMap map = test_map();
  map.queue_words = 16;
  map.start_words = 16;
  Rig rig(map, VirtualClock::Mode::Gated);
  rig.card->start(kPacerHz);
  std::vector<std::uint32_t> words;
  for (int i = 0; i < 40; ++i) words.push_back(i % 2 ? kXStep : 0);
  std::thread writer([&] { rig.card->write(words); });  // blocks until 24 words have played

  for (std::uint64_t tick = 0; tick < words.size(); ++tick) {
    // Only advance once the word is queued: the producer is slow in real time, not late.
    ASSERT_TRUE(
        eventually([&] { return rig.card->ticks_played() + rig.card->queued_words() > tick; }));
    auto due = rig.clock->wait_for_sleeper();
    ASSERT_TRUE(due) << "tick " << tick;
    rig.clock->advance_to(*due);
  }
  writer.join();
  ASSERT_TRUE(eventually([&] { return rig.card->ticks_played() == words.size(); }));
  rig.card->stop(0);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  const std::vector<LineChange> changes = rig.lines->changes();
  // Ticks 1-39 (the step line follows every word, in order), then stop's idle word at 40.
  ASSERT_EQ(changes.size(), 40u);
  for (std::size_t i = 0; i < changes.size(); ++i)
    EXPECT_EQ(changes[i], (LineChange{i + 1, kXStepLine, static_cast<int>((i + 1) % 2)}));
}

// --- Timing ---------------------------------------------------------------------------------

TEST(GpiodCard, TicksLateBeyondTheToleranceAreCounted) {
  Rig rig(test_map());  // tolerance: half a tick, 500 us
  std::vector<std::uint32_t> words;
  for (int i = 0; i < 10; ++i) words.push_back(i % 2 ? kXStep : 0);

  rig.clock->make_late(400'000, 3);  // within the tolerance
  rig.card->start(kPacerHz);
  rig.card->write(words);
  rig.card->drain();
  EXPECT_EQ(rig.card->late_ticks(), 0u);
  EXPECT_EQ(rig.card->worst_late_ns(), 400'000);

  rig.clock->make_late(600'000, 2);  // beyond it
  rig.card->start(kPacerHz);
  rig.card->write(words);
  rig.card->drain();
  EXPECT_EQ(rig.card->late_ticks(), 2u);
  EXPECT_EQ(rig.card->worst_late_ns(), 600'000);
  EXPECT_EQ(rig.card->ticks_played(), 10u);  // late ticks still play, in order
  EXPECT_EQ(rig.card->fault(), CardFault::None);
}

TEST(PacerSchedule, DeadlinesAreExactForRatesThatDoNotDivideASecond) {
  const PacerSchedule at_1khz(1000, 5);
  EXPECT_EQ(at_1khz.deadline(0), 5);
  EXPECT_EQ(at_1khz.deadline(7), 5 + 7'000'000);

  const PacerSchedule at_3hz(3, 0);
  EXPECT_EQ(at_3hz.deadline(1), 333'333'333);
  EXPECT_EQ(at_3hz.deadline(2), 666'666'666);
  EXPECT_EQ(at_3hz.deadline(3), 1'000'000'000);

  // 30 kHz for a day (2.592e9 ticks): no drift, no overflow.
  const PacerSchedule at_30khz(30'000, 0);
  EXPECT_EQ(at_30khz.deadline(2'592'000'000), 86'400'000'000'000);
  EXPECT_EQ(at_30khz.deadline(2'592'000'001), 86'400'000'033'333);
}

// --- Hardware errors and the pacer limit -----------------------------------------------------

TEST(GpiodCard, AFailedLineWriteIsAHardwareFault) {
  Rig rig(test_map());
  rig.lines->fail_next_write(EIO);
  rig.card->start(kPacerHz);
  rig.card->write(std::vector<std::uint32_t>{0, 0, kXStep, 0});
  rig.card->drain();
  EXPECT_EQ(rig.card->fault(), CardFault::Hardware);
  EXPECT_EQ(rig.card->ticks_played(), 2u);  // the failed tick did not play
  EXPECT_NE(rig.card->error().find("GPIO write failed at tick 2"), std::string::npos)
      << rig.card->error();
}

TEST(GpiodCard, RefusesAPacerAboveTheMaximum) {
  Rig rig(test_map());
  rig.card->start(200'000);  // the PCI-7200 profile's default rate
  EXPECT_EQ(rig.card->fault(), CardFault::Hardware);
  EXPECT_EQ(rig.card->error(),
            "gpiod: pacer rate 200000 Hz is above the GPIO card's maximum of 50000 Hz: ticks "
            "are timed in software through the GPIO character device, which cannot keep ticks "
            "that short; set the profile's [card] clock_hz / pacer_divisor to 50000 Hz or less "
            "(see drivers/gpiod/README.md)");
  rig.card->write(std::vector<std::uint32_t>(8, kXStep));
  rig.card->drain();
  EXPECT_EQ(rig.card->ticks_played(), 0u);
  EXPECT_TRUE(rig.lines->changes().empty());

  rig.card->start(kGpiodMaxPacerHz);  // the maximum itself is accepted
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.card->error(), "");
  rig.card->stop(0);
}

// --- Map validation -------------------------------------------------------------------------

TEST(GpioMap, TheTestMapIsValid) {
  EXPECT_TRUE(validate_gpio_map(test_map(), 32).empty());
}

TEST(GpioMap, ALineUsedTwiceIsNamedWithBothUsers) {
  GpioMap map = test_map();
  map.outputs.push_back({9, kXDirLine});
  map.inputs.push_back({kXStepLine, 7});
  const auto errors = validate_gpio_map(map);
  EXPECT_EQ(errors, (std::vector<std::string>{
                        "gpiod: line 11 is used twice (output bit 8 and output bit 9)",
                        "gpiod: line 10 is used twice (output bit 0 and input bit 7)"}));
}

TEST(GpioMap, BitsOutOfRangeAreRefused) {
  GpioMap map = test_map();
  map.outputs.push_back({32, 3});
  map.inputs.push_back({4, -1});
  const auto errors = validate_gpio_map(map);
  EXPECT_EQ(errors,
            (std::vector<std::string>{"gpiod: output bit 32 (line 3) is out of range 0-31",
                                      "gpiod: input bit -1 (line 4) is out of range 0-31"}));
}

TEST(GpioMap, OffsetsTheChipDoesNotHaveAreRefused) {
  const auto errors = validate_gpio_map(test_map(), 21);  // lines 0-20: 21 and 22 missing
  EXPECT_EQ(
      errors,
      (std::vector<std::string>{
          "gpiod: line 21 (input bit 4) is not on /dev/gpiochip-test: it has 21 lines, 0-20",
          "gpiod: line 22 (input bit 5) is not on /dev/gpiochip-test: it has 21 lines, 0-20"}));
}

TEST(GpioMap, EveryOtherProblemIsReportedTogether) {
  GpioMap map = test_map();
  map.outputs.clear();
  map.inputs.push_back({30, 5});  // bit 5 already comes from the probe line
  map.estop_bits = 1u << 9;       // no line sets bit 9
  map.active_low_bits = kProbeBit;
  map.queue_words = 100;
  map.start_words = 0;
  map.input_sample_hz = 5000;
  map.rt_priority = 0;
  const auto errors = validate_gpio_map(map);
  EXPECT_EQ(errors.size(), 8u) << join_lines(errors);
  EXPECT_TRUE(contains(errors, "no output lines"));
  EXPECT_TRUE(contains(errors, "input bit 5 is set by two lines"));
  EXPECT_TRUE(contains(errors, "E-stop/limit input bit(s) 9 have no input line"));
  EXPECT_TRUE(contains(errors, "active-low bit(s) 5 are neither E-stop nor limit bits"));
  EXPECT_TRUE(contains(errors, "queue of 100 words is not a power of two"));
  EXPECT_TRUE(contains(errors, "start threshold of 0 words"));
  EXPECT_TRUE(contains(errors, "input sample rate 5000 Hz is outside 10 Hz to the pacer rate"));
  EXPECT_TRUE(contains(errors, "real-time priority 0 is outside 1-99"));
}

TEST(GpioMap, APacerAboveTheMaximumIsRefused) {
  GpioMap map = test_map();
  map.pacer_hz = 200'000;
  EXPECT_TRUE(contains(validate_gpio_map(map),
                       "pacer rate 200000 Hz is above the GPIO card's "
                       "maximum of 50000 Hz"));
  map.pacer_hz = 0;
  EXPECT_TRUE(contains(validate_gpio_map(map), "pacer rate 0 Hz is not a positive rate"));
  EXPECT_THROW(GpiodCard(map, std::make_unique<FakeGpioLines>(map)), std::invalid_argument);
}

TEST(GpioMap, TheProfileGivesThePacerTheIdleWordAndTheFaultInputs) {
  Settings settings = default_settings();
  settings.card.clock_hz = 20'000;
  settings.card.pacer_divisor = 1;
  settings.pins[1].step_active_low = true;  // Y: idle high
  GpioMap map = test_map();
  apply_profile(map, settings);
  EXPECT_EQ(map.pacer_hz, 20'000);
  EXPECT_EQ(map.initial_word, PinMap::from(settings.pins).idle_word());
  EXPECT_TRUE(map.initial_word & kYStep);
  // default.toml: E-stop on bit 0 (active low), limits on bits 2-7 (active high).
  EXPECT_EQ(map.estop_bits, 1u << 0);
  EXPECT_EQ(map.limit_bits, 0xFCu);
  EXPECT_EQ(map.active_low_bits, 1u << 0);
  // The test map wires bits 0, 4 and 5 only: the profile's other switches need lines.
  EXPECT_TRUE(contains(validate_gpio_map(map),
                       "gpiod: E-stop/limit input bit(s) 2, 3, 6, 7 have no input line; map "
                       "a line to each, or set the profile's bit to -1 (not wired)"));
}

// --- Opening a chip -------------------------------------------------------------------------

TEST(OpenGpiod, AMissingChipNamesTheFix) {
  GpioMap map = test_map();
  map.chip_path = "/nonexistent/gpiochip9";
  std::string error;
  EXPECT_EQ(open_gpiod(map, &error), nullptr);
  EXPECT_EQ(error,
            "/nonexistent/gpiochip9: no such GPIO chip; list the chips with `gpiodetect` (Debian "
            "package gpiod) and set the chip path; see drivers/gpiod/README.md");
}

TEST(OpenGpiod, AFileThatIsNotAChipIsNamed) {
  GpioMap map = test_map();
  map.chip_path = "/dev/null";
  std::string error;
  EXPECT_EQ(open_gpiod(map, &error), nullptr);
  EXPECT_EQ(error,
            "/dev/null: not a GPIO character device (expected /dev/gpiochipN; see `gpiodetect`); "
            "see drivers/gpiod/README.md");
}

TEST(OpenGpiod, PermissionDeniedNamesTheFix) {
  // Root opens any file, so the message is checked where it is made.
  EXPECT_EQ(chip_open_error("/dev/gpiochip0", EACCES),
            "/dev/gpiochip0: permission denied; add the user to the gpio group or a udev rule; "
            "see drivers/gpiod/README.md");
}

TEST(OpenGpiod, AnInvalidMapIsRefusedBeforeTheChipIsOpened) {
  GpioMap map = test_map();
  map.chip_path = "/nonexistent/gpiochip9";
  map.pacer_hz = 200'000;
  std::string error;
  EXPECT_EQ(open_gpiod(map, &error), nullptr);
  EXPECT_NE(error.find("pacer rate 200000 Hz is above"), std::string::npos) << error;
  EXPECT_EQ(error.find("no such GPIO chip"), std::string::npos) << error;
}

// --- A real chip (skipped where there is none) -----------------------------------------------

// GANTRY_GPIOD_TEST_CHIP picks another chip (a gpio-sim or gpio-mockup one, say).
std::string real_chip_path() {
  const char* path = std::getenv("GANTRY_GPIOD_TEST_CHIP");
  return path ? path : "/dev/gpiochip0";
}

bool real_chip_usable(const std::string& path, std::string* why) {
  if (!std::filesystem::exists(path)) {
    *why = path + " does not exist (no GPIO chip on this machine)";
    return false;
  }
  if (access(path.c_str(), R_OK | W_OK) != 0) {
    *why = path + " is not accessible to this user (see drivers/gpiod/README.md, permissions)";
    return false;
  }
  return true;
}

TEST(RealChip, OpensAndRefusesAnOffsetItDoesNotHave) {
  const std::string path = real_chip_path();
  std::string why;
  if (!real_chip_usable(path, &why)) GTEST_SKIP() << why;
  std::string error;
  auto chip = probe_gpio_chip(path, &error);
  ASSERT_TRUE(chip) << error;
  EXPECT_GT(chip->lines, 0u);

  GpioMap map = test_map();
  map.chip_path = path;
  map.inputs.clear();
  map.outputs = {{0, chip->lines}};  // one past the last line: refused before any request
  EXPECT_EQ(open_gpiod(map, &error), nullptr);
  EXPECT_NE(error.find(path + ": it has " + std::to_string(chip->lines) + " lines"),
            std::string::npos)
      << error;
}

// Drives a line only when told which one is safe: GANTRY_GPIOD_TEST_LINE=<offset>.
TEST(RealChip, PlaysWordsOnALineNamedSafeToDrive) {
  const std::string path = real_chip_path();
  std::string why;
  if (!real_chip_usable(path, &why)) GTEST_SKIP() << why;
  const char* line = std::getenv("GANTRY_GPIOD_TEST_LINE");
  if (!line)
    GTEST_SKIP() << "set GANTRY_GPIOD_TEST_LINE to a line of " << path
                 << " that is safe to toggle (nothing wired to it)";
  GpioMap map;
  map.chip_path = path;
  map.pacer_hz = 10'000;
  map.outputs = {{0, static_cast<unsigned>(std::stoul(line))}};
  map.queue_words = 1024;
  map.start_words = 512;
  map.realtime = false;
  std::string error;
  auto lines = LibgpiodLines::open(map, &error);
  ASSERT_TRUE(lines) << error;
  GpiodCard card(map, std::move(lines));
  card.start(map.pacer_hz);
  std::vector<std::uint32_t> words(2000);
  for (std::size_t i = 0; i < words.size(); ++i) words[i] = i % 2;
  card.write(words);
  card.drain();
  EXPECT_EQ(card.fault(), CardFault::None) << card.error();
  EXPECT_EQ(card.ticks_played(), words.size());
  card.stop(0);
  RecordProperty("late_ticks", std::to_string(card.late_ticks()));
  RecordProperty("worst_late_ns", std::to_string(card.worst_late_ns()));
}

}  // namespace
}  // namespace gantry
