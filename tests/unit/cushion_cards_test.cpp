// The cushioned stop (limits.cushion_steps, limits.esc_steps) on the real cards: the emulated
// PCI-7200 and the GPIO card on fake lines play it from their own real-time threads, and
// every pulse they play is the simulated card's for the same move cut at the same tick
// (docs/hardware.md, "Cushioned stop"). Time is each card's virtual time, stepped by the test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "gantry/hal/limit_filter.hpp"
#include "gantry/hal/pin_map.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/step/step_generator.hpp"
#include "gpiod/fake_gpio_lines.hpp"
#include "gpiod/gpio_map_profile.hpp"
#include "gpiod/gpiod_card.hpp"
#include "gpiod/virtual_clock.hpp"
#include "pci7200/emulated_pci7200.hpp"
#include "pci7200/open_pci7200.hpp"
#include "pci7200/pci7200_card.hpp"
#include "pin_trace.hpp"
#include "segment_builders.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

using namespace std::chrono_literals;
using test::channel_pulses;
using test::TracePulse;
using test::vec;
using Trace = std::vector<std::pair<std::int64_t, std::uint32_t>>;
namespace fs = std::filesystem;

// Passes everything to a real card, but lets the step generator write the whole move before
// the card plays (no lead to keep: queues_words() is false), and keeps the words written.
class WriteAhead : public Card {
 public:
  explicit WriteAhead(Card& inner) : inner_(inner) {}
  void start(double hz) override { inner_.start(hz); }
  void write(std::span<const std::uint32_t> w) override {
    words_.insert(words_.end(), w.begin(), w.end());
    inner_.write(w);
  }
  void drain() override { inner_.drain(); }
  void end_stream() override { inner_.end_stream(); }
  void stop(std::uint32_t idle) override { inner_.stop(idle); }
  void stop_cushioned(std::uint32_t idle, int steps) override {
    inner_.stop_cushioned(idle, steps);
  }
  std::optional<CushionPlayed> cushion_played() const override { return inner_.cushion_played(); }
  std::uint64_t ticks_played() const override { return inner_.ticks_played(); }
  std::uint32_t inputs() const override { return inner_.inputs(); }
  CardFault fault() const override { return inner_.fault(); }
  const std::vector<std::uint32_t>& words() const { return words_; }

 private:
  Card& inner_;
  std::vector<std::uint32_t> words_;
};

// What a card played, as the simulated card's pin trace has it (each change of the output
// word, from its tick on), and what it and the step generator said.
struct CardRun {
  Trace trace;
  std::optional<CushionPlayed> cushion;
  CardFault fault = CardFault::None;
  Steps6 reported{};  // the step generator's played position: what the controller reports
  std::uint64_t ticks = 0;
  std::vector<std::uint32_t> written;  // the generator's words
};

Trace trace_of_words(const std::vector<std::uint32_t>& played) {
  Trace t;
  for (std::size_t i = 0; i < played.size(); ++i)
    if (i == 0 || played[i] != played[i - 1])
      t.emplace_back(static_cast<std::int64_t>(i), played[i]);
  return t;
}

// X and Y pulses of a trace.
struct Pulses {
  std::vector<TracePulse> x, y;
};
Pulses pulses(const Settings& s, const Trace& t) {
  return {channel_pulses(t, s.pins[0].step_bit, s.pins[0].dir_bit),
          channel_pulses(t, s.pins[1].step_bit, s.pins[1].dir_bit)};
}
std::int64_t count(const std::vector<TracePulse>& p) {
  std::int64_t n = 0;
  for (const TracePulse& q : p) n += q.positive ? 1 : -1;
  return n;
}
std::int64_t count_from(const std::vector<TracePulse>& p, std::uint64_t tick) {
  std::int64_t n = 0;
  for (const TracePulse& q : p)
    if (q.tick >= static_cast<std::int64_t>(tick)) n += q.positive ? 1 : -1;
  return n;
}
bool same_pulses(const std::vector<TracePulse>& a, const std::vector<TracePulse>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].tick != b[k].tick || a[k].positive != b[k].positive) return false;
  return true;
}

// X at 4 in/s (Y at 2 with `diagonal`), cruising: the move every card is given.
PlannedSegment the_move(bool diagonal) {
  return test::segment(vec(0), diagonal ? vec(1.0, 0.5) : vec(1.0), 4, 4, 4, 20);
}

// ---- the words every card plays ----------------------------------------------------

// Leading edges of channel k's step bit in words[0, n): the steps in them.
std::int64_t steps_in(const PinMap& pins, int k, const std::vector<std::uint32_t>& words,
                      std::size_t n, std::uint32_t before) {
  std::int64_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t m = pins.axes[k].step_mask;
    if ((words[i] & m) && !(before & m)) count += pins.positive(k, words[i]) ? 1 : -1;
    before = words[i];
  }
  return count;
}

// A player that sleeps through runs of alike words (the GPIO card's) gets the same words as
// one that takes every word (the PCI-7200's, the simulated card's), and the steps counted
// in a cushion cut short are those of the words played.
TEST(CushionStream, RunsOfAlikeWordsAndACutShortCushionCountAsEveryWord) {
  const Settings s = default_settings();
  const PinMap pins = PinMap::from(s.pins);
  std::array<ChannelMotion, kAxisCount> motion{};
  motion[0] = {1.0 / 7, true};
  motion[1] = {1.0 / 13, false};
  const std::array<std::int64_t, kAxisCount> since{3, 5, 1 << 30, 1 << 30, 1 << 30, 1 << 30};
  const std::uint32_t word = pins.idle_word() | pins.dir_bits(1, false);
  const std::vector<std::uint32_t> all = cushion_words(pins, word, motion, since, 40, 2);
  ASSERT_GT(all.size(), 40u * 7);
  const CushionStream start(pins, word, motion, since, 40, 2);
  CushionStream stream = start;
  std::size_t i = 0;
  while (!stream.done()) {
    const std::uint64_t n = stream.alike_ahead();
    ASSERT_GE(n, 1u);
    const std::uint32_t w = stream.next();
    for (std::uint64_t k = 0; k < n; ++k) ASSERT_EQ(all.at(i + k), w) << i + k;
    stream.skip(n - 1);
    i += n;
    EXPECT_EQ(stream.given(), i);
  }
  EXPECT_EQ(i, all.size());
  EXPECT_EQ(stream.steps()[0], 40);
  EXPECT_EQ(stream.steps()[0], steps_in(pins, 0, all, all.size(), word));
  EXPECT_EQ(stream.steps()[1], steps_in(pins, 1, all, all.size(), word));
  EXPECT_NEAR(static_cast<double>(stream.steps()[1]), -40.0 * 7 / 13, 1);
  for (const std::size_t cut : {std::size_t{0}, std::size_t{1}, all.size() / 3, all.size() - 1})
    for (int k = 0; k < 2; ++k)
      EXPECT_EQ(start.steps_in(cut)[k], steps_in(pins, k, all, cut, word)) << cut;
  // Nothing moving: nothing to play, a dead stop.
  EXPECT_TRUE(CushionStream(pins, word, {}, since, 40, 2).done());
}

// ---- the simulated card: the reference -----------------------------------------------

std::string trace_path(const char* name) {
  return (fs::temp_directory_path() /
          (std::string("gantry_cushion_cards_") + name + "_" + std::to_string(getpid()) + ".trace"))
      .string();
}

// The move on the simulated card with X's max limit switch closing at tick `at`.
CardRun sim_limit_at(const Settings& s, std::uint64_t at, bool diagonal) {
  SimWorld w;
  w.input_events.push_back({static_cast<double>(at) / s.card.pacer_hz(), s.inputs.max_bit[0],
                            !s.inputs.limits_active_low});
  const std::string path = trace_path("limit");
  CardRun r;
  {
    SimCard card(s, false, w, path);
    card.start(s.card.pacer_hz());
    StepGenerator gen(s, card);
    try {
      gen.segment(the_move(diagonal));
      gen.flush();
    } catch (const GantryError&) {
    }
    r.cushion = card.cushion_played();
    r.fault = card.fault();
    r.reported = gen.played_position();
    r.ticks = card.ticks_played();
  }
  r.trace = test::read_trace(path);
  fs::remove(path);
  return r;
}

// The first `at` of `words` on the simulated card, then the operator's E-stop with `esc`.
CardRun sim_stop_at(const Settings& s, const std::vector<std::uint32_t>& words, std::uint64_t at,
                    int esc) {
  const std::string path = trace_path("esc");
  CardRun r;
  {
    SimCard card(s, false, {}, path);
    card.start(s.card.pacer_hz());
    card.write(std::span(words).first(at));
    card.stop_cushioned(PinMap::from(s.pins).idle_word(), esc);
    r.cushion = card.cushion_played();
    r.ticks = card.ticks_played();
  }
  r.trace = test::read_trace(path);
  fs::remove(path);
  return r;
}

// ---- the emulated PCI-7200 ------------------------------------------------------------

struct PciRig {
  std::shared_ptr<pci7200::EmulatedPci7200> emu;
  std::unique_ptr<pci7200::Pci7200Card> card;
};

PciRig pci_rig(const Settings& s, bool dma) {
  std::string error;
  std::optional<pci7200::Pci7200Options> options =
      pci7200_options_for(s, Pci7200OpenOptions{}, &error);
  EXPECT_TRUE(options) << error;
  options->estop = {};  // the emulated inputs read 0: an active-low E-stop would be pressed
  options->limits = {1u << s.inputs.max_bit[0], 1u << s.inputs.max_bit[0]};
  pci7200::EmulatedPci7200Config config;
  config.stepped = true;
  if (!dma) config.dma_words = 0;  // programmed I/O into the FIFO
  PciRig rig;
  rig.emu = std::make_shared<pci7200::EmulatedPci7200>(config);
  rig.card = std::make_unique<pci7200::Pci7200Card>(rig.emu, *options);
  return rig;
}

// The move on the PCI-7200: X's max limit switch closes once `at` ticks have played (the
// feeder samples it at its next pass), or, with `esc` >= 0 and no switch, the operator's
// E-stop comes then (stop_cushioned from another thread, as the controller's).
CardRun pci_run(const Settings& s, std::uint64_t at, bool diagonal, int esc = -1, bool dma = true) {
  PciRig rig = pci_rig(s, dma);
  WriteAhead card(*rig.card);
  card.start(s.card.pacer_hz());
  StepGenerator gen(s, card);
  gen.segment(the_move(diagonal));
  gen.flush();
  rig.emu->advance(at - rig.emu->played_count());
  std::atomic<bool> stopped{false};
  std::thread stopper;
  if (esc >= 0)
    stopper = std::thread([&] {
      card.stop_cushioned(PinMap::from(s.pins).idle_word(), esc);
      stopped = true;
    });
  else
    rig.emu->set_inputs(1u << s.inputs.max_bit[0]);
  for (int i = 0; i < 100'000 && (esc >= 0 ? !stopped.load() : card.fault() == CardFault::None);
       ++i)
    rig.emu->advance(64);
  if (stopper.joinable()) stopper.join();
  CardRun r;
  r.trace = trace_of_words(rig.emu->played());
  r.cushion = card.cushion_played();
  r.fault = card.fault();
  r.reported = gen.played_position();
  r.ticks = card.ticks_played();
  r.written = card.words();
  EXPECT_EQ(r.ticks, rig.emu->played_count());  // exact: every word the latch took
  EXPECT_FALSE(rig.emu->pacer_running());
  return r;
}

// ---- the GPIO card on fake lines ------------------------------------------------------

// The GPIO card paces at most 50 kHz: a 20 kHz profile (one-tick pulses, 4 in/s is X's step
// every five ticks). The simulated reference runs the same profile.
Settings gpio_settings() {
  Settings s = default_settings();
  s.card.clock_hz = 40'000;
  s.card.pacer_divisor = 2;
  s.card.step_pulse_us = 50;
  s.card.dir_setup_us = 50;
  s.outputs.charge_pump_bit = -1;
  return s;
}

GpioMap gpio_map(const Settings& s) {
  GpioMap map;
  map.chip_path = "/dev/fake";
  for (int k = 0; k < 2; ++k) {  // X's and Y's step and direction lines
    map.outputs.push_back({s.pins[k].step_bit, static_cast<unsigned>(2 * k)});
    map.outputs.push_back({s.pins[k].dir_bit, static_cast<unsigned>(2 * k + 1)});
  }
  map.inputs = {{4, s.inputs.max_bit[0]}};  // X's max limit switch on line 4
  map.realtime = false;
  apply_profile(map, s);
  map.estop_bits = 0;  // no E-stop line on the fake card
  map.limit_bits = 1u << s.inputs.max_bit[0];
  map.active_low_bits = 0;
  map.queue_words = std::size_t{1} << 20;  // the whole move, written before it plays
  map.start_words = map.queue_words;       // plays at drain()
  return map;
}

// The lines' changes as the output word's (every unmapped bit 0).
Trace trace_of_lines(const GpioMap& map, const std::vector<LineChange>& changes) {
  Trace t;
  std::uint32_t word = 0;
  for (const OutputLine& o : map.outputs) word |= map.initial_word & (1u << o.bit);
  t.emplace_back(0, word);
  for (const LineChange& c : changes) {
    for (const OutputLine& o : map.outputs)
      if (o.offset == c.offset) word = c.level ? word | 1u << o.bit : word & ~(1u << o.bit);
    const auto tick = static_cast<std::int64_t>(c.tick);
    if (t.back().first == tick)
      t.back().second = word;
    else
      t.emplace_back(tick, word);
  }
  return t;
}

// The move on the GPIO card: X's max limit switch closes from tick `at` (the player samples
// it every 20 ticks), or, with `esc` >= 0, the operator's E-stop comes once `at` ticks have
// played.
CardRun gpio_run(const Settings& s, std::uint64_t at, bool diagonal, int esc = -1) {
  const GpioMap map = gpio_map(s);
  auto lines = std::make_unique<FakeGpioLines>(map);
  FakeGpioLines& fake = *lines;
  auto clock = std::make_unique<VirtualClock>(esc >= 0 ? VirtualClock::Mode::Gated
                                                       : VirtualClock::Mode::FreeRunning);
  VirtualClock& vclock = *clock;
  GpiodCard gpio(map, std::move(lines), std::move(clock));
  fake.set_tick_source([&] { return gpio.line_tick(); });
  if (esc < 0) fake.set_input(4, 1, at);
  WriteAhead card(gpio);
  card.start(s.card.pacer_hz());
  StepGenerator gen(s, card);
  gen.segment(the_move(diagonal));
  gen.flush();
  if (esc < 0) {
    card.drain();  // plays it all in virtual time, up to the fault
  } else {
    std::thread drainer([&] { card.drain(); });
    auto step = [&] {
      if (const std::optional<std::int64_t> d = vclock.wait_for_sleeper(50ms))
        vclock.advance_to(*d);
    };
    for (int i = 0; i < 1'000'000 && gpio.ticks_played() < at; ++i) step();
    std::atomic<bool> stopped{false};
    std::thread stopper([&] {
      card.stop_cushioned(map.initial_word, esc);
      stopped = true;
    });
    for (int i = 0; i < 1'000'000 && !stopped; ++i) step();
    stopper.join();
    drainer.join();
  }
  CardRun r;
  r.trace = trace_of_lines(map, fake.changes());
  r.cushion = card.cushion_played();
  r.fault = card.fault();
  r.reported = gen.played_position();
  r.ticks = card.ticks_played();
  r.written = card.words();
  return r;
}

// ---- what every cushion must be ---------------------------------------------------------

// `r`'s cushion: X (the fastest) made exactly `steps` steps from its first tick on, each
// interval at least the one before (to rounding), the last several times the cruise's; the
// position the step generator reports is the pulses counted on the trace.
void expect_cushion(const Settings& s, const CardRun& r, int steps, const char* card) {
  ASSERT_TRUE(r.cushion) << card;
  const Pulses p = pulses(s, r.trace);
  EXPECT_EQ(count_from(p.x, r.cushion->from), steps) << card;
  EXPECT_EQ(r.cushion->steps[0], steps) << card;
  EXPECT_EQ(r.reported[0], count(p.x)) << card;
  EXPECT_EQ(r.reported[1], count(p.y)) << card;
  std::size_t at = 0;  // X's first cushion step
  while (at < p.x.size() && p.x[at].tick < static_cast<std::int64_t>(r.cushion->from)) ++at;
  ASSERT_GE(at, 2u) << card;
  ASSERT_EQ(p.x.size() - at, static_cast<std::size_t>(steps)) << card;
  const std::int64_t cruise = p.x[at - 1].tick - p.x[at - 2].tick;
  std::int64_t before = cruise;
  for (std::size_t k = at; k < p.x.size(); ++k) {
    const std::int64_t interval = p.x[k].tick - p.x[k - 1].tick;
    EXPECT_GE(interval, before - 1) << card << ": cushion step " << k - at + 1;
    before = interval;
  }
  EXPECT_GT(before, 5 * cruise) << card;
  std::cout << card << ": " << steps << " cushion steps in " << p.x.back().tick - p.x[at - 1].tick
            << " ticks from tick " << r.cushion->from << "; X's step interval " << cruise
            << " ticks before, " << before << " at the end\n";
}

// Every pulse of `card` is the simulated card's, and both report the same position.
void expect_same_as_sim(const Settings& s, const CardRun& card, const CardRun& sim,
                        const char* name) {
  ASSERT_TRUE(sim.cushion) << name;
  ASSERT_TRUE(card.cushion) << name;
  EXPECT_EQ(card.cushion->from, sim.cushion->from) << name;
  EXPECT_EQ(card.cushion->steps, sim.cushion->steps) << name;
  EXPECT_EQ(card.ticks, sim.ticks) << name;
  const Pulses a = pulses(s, card.trace), b = pulses(s, sim.trace);
  EXPECT_TRUE(same_pulses(a.x, b.x)) << name << ": X " << a.x.size() << " vs " << b.x.size();
  EXPECT_TRUE(same_pulses(a.y, b.y)) << name << ": Y " << a.y.size() << " vs " << b.y.size();
}

// An operator's E-stop on `card`: no fault, `steps` of X's steps of cushion, and the pulses
// the simulated card plays when it is stopped at the same tick after the same words.
void expect_esc_cushion_as_sim(const Settings& s, const CardRun& card, int steps,
                               const char* name) {
  EXPECT_EQ(card.fault, CardFault::None) << name;
  expect_cushion(s, card, steps, name);
  ASSERT_TRUE(card.cushion) << name;
  expect_same_as_sim(s, card, sim_stop_at(s, card.written, card.cushion->from, steps), name);
}

Settings pci_settings(int cushion, int esc) {
  Settings s = default_settings();  // 200 kHz
  s.outputs.charge_pump_bit = -1;
  s.limits.cushion_steps = cushion;
  s.limits.esc_steps = esc;
  return s;
}

constexpr std::uint64_t kPciHit = 30'000;  // 0.15 s in: X near 0.6 in, cruising
constexpr std::uint64_t kGpioHit = 3'000;  // the same at 20 kHz

TEST(CushionedStopOnCards, ThePci7200DeceleratesAfterALimitHitAsTheSimulatedCardDoes) {
  const Settings s = pci_settings(100, 0);
  for (const bool dma : {true, false}) {  // the DMA double buffer, and programmed I/O
    const char* name = dma ? "PCI-7200 (DMA)" : "PCI-7200 (programmed I/O)";
    const CardRun pci = pci_run(s, kPciHit, /*diagonal=*/true, -1, dma);
    EXPECT_EQ(pci.fault, CardFault::Limit) << name;
    expect_cushion(s, pci, 100, name);
    ASSERT_TRUE(pci.cushion) << name;
    // Y, at half X's rate, makes half X's cushion.
    EXPECT_NEAR(static_cast<double>(pci.cushion->steps[1]), 50, 1) << name;
    // The same move on the simulated card, its switch closing at the tick the PCI-7200's
    // cushion began (after the words already in its FIFO).
    EXPECT_GE(pci.cushion->from, kPciHit) << name;
    EXPECT_LE(pci.cushion->from, kPciHit + 64 + 8) << name;  // the pass that saw it, the FIFO
    const CardRun sim = sim_limit_at(s, pci.cushion->from, true);
    EXPECT_EQ(sim.fault, CardFault::Limit);
    expect_same_as_sim(s, pci, sim, name);
    EXPECT_EQ(pci.reported, sim.reported) << name;
  }
}

TEST(CushionedStopOnCards, TheGpioCardDeceleratesAfterALimitHitAsTheSimulatedCardDoes) {
  const Settings s = [] {
    Settings g = gpio_settings();
    g.limits.cushion_steps = 100;
    return g;
  }();
  const CardRun gpio = gpio_run(s, kGpioHit, /*diagonal=*/true);
  EXPECT_EQ(gpio.fault, CardFault::Limit);
  expect_cushion(s, gpio, 100, "GPIO");
  ASSERT_TRUE(gpio.cushion);
  EXPECT_NEAR(static_cast<double>(gpio.cushion->steps[1]), 50, 1);
  // At the first input sample (every 20 ticks) from the switch's closing.
  EXPECT_GE(gpio.cushion->from, kGpioHit);
  EXPECT_LT(gpio.cushion->from, kGpioHit + 20);
  const CardRun sim = sim_limit_at(s, gpio.cushion->from, true);
  expect_same_as_sim(s, gpio, sim, "GPIO");
  EXPECT_EQ(gpio.reported, sim.reported);
}

// limits.esc_steps: the operator's E-stop decelerates for that many of X's steps, counted,
// and the card stops without a fault (as it does for a stop); the words are the simulated
// card's after the same words.
TEST(CushionedStopOnCards, ThePci7200DeceleratesForEscStepsAfterTheOperatorsEStop) {
  const Settings s = pci_settings(0, 200);
  expect_esc_cushion_as_sim(s, pci_run(s, kPciHit, false, 200), 200, "PCI-7200");
}

TEST(CushionedStopOnCards, TheGpioCardDeceleratesForEscStepsAfterTheOperatorsEStop) {
  Settings s = gpio_settings();
  s.limits.esc_steps = 200;
  expect_esc_cushion_as_sim(s, gpio_run(s, kGpioHit, false, 200), 200, "GPIO");
}

// Left out (0): both cards stop dead, as before: no cushion, and no X step after the
// switch's sample beyond the words already in the card; the position is the pulses counted.
TEST(CushionedStopOnCards, WithoutACushionBothCardsStillStopDead) {
  {
    const Settings s = pci_settings(0, 0);
    const CardRun pci = pci_run(s, kPciHit, false);
    EXPECT_EQ(pci.fault, CardFault::Limit);
    EXPECT_FALSE(pci.cushion);
    const Pulses p = pulses(s, pci.trace);
    EXPECT_EQ(pci.reported[0], count(p.x));
    EXPECT_LE(pci.ticks, kPciHit + 64 + 8);
    EXPECT_LE(count_from(p.x, kPciHit), 2);
  }
  {
    const Settings s = gpio_settings();
    const CardRun gpio = gpio_run(s, kGpioHit, false);
    EXPECT_EQ(gpio.fault, CardFault::Limit);
    EXPECT_FALSE(gpio.cushion);
    const Pulses p = pulses(s, gpio.trace);
    EXPECT_EQ(gpio.reported[0], count(p.x));
    EXPECT_LT(gpio.ticks, kGpioHit + 20);
    EXPECT_LE(count_from(p.x, kGpioHit), 4);
  }
}

// The live machine on the GPIO card: a run into X's limit switch ends stopped with the
// switch named and the cushion said, and the position the controller reports is the pulses
// the lines made, the cushion's included.
TEST(CushionedStopOnCards, TheControllerReportsWhereTheGpioCardsCushionLeftTheTool) {
  Settings s = gpio_settings();
  s.limits.cushion_steps = 50;
  // No E-stop or stop switch line on the fake card: they read 0, which is inactive so.
  s.inputs.estop_active_low = false;
  s.switches.stop_normally_open = true;
  const GpioMap map = gpio_map(s);  // the whole run queued, then played at the end (drain)
  auto lines = std::make_unique<FakeGpioLines>(map);
  FakeGpioLines& fake = *lines;
  GpiodCard card(map, std::move(lines), std::make_unique<VirtualClock>());
  fake.set_tick_source([&] { return card.line_tick(); });
  fake.set_input(4, 1, 6'000);  // 0.3 s in
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{s, card, io, store};
  const Outcome o = c.run(Script::from_text("MX, 3\n", "part.sbp"));
  ASSERT_TRUE(o) << o.reason;
  c.wait();
  const ControllerStatus st = c.status();
  EXPECT_NE(st.state, MachineState::Idle);
  EXPECT_NE(st.message.find("X high limit switch"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("cushioned: 50 more steps"), std::string::npos) << st.message;
  // The switch closes at an input sample (every 20 ticks from the stream's first): the
  // cushion's steps are X's last.
  const Pulses p = pulses(s, trace_of_lines(map, fake.changes()));
  EXPECT_EQ(count_from(p.x, 6'000), 50);
  EXPECT_EQ(st.steps[0], count(p.x));
  EXPECT_GT(st.steps[0], 50);
}

}  // namespace
}  // namespace gantry
