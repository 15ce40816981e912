// The PCI-7200 driver against the register-level emulation: pacer arithmetic and
// programming, exact playback across DMA refills and through programmed I/O, underruns,
// stop, faults, the charge pump, shutdown, and card discovery in a fake sysfs tree.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gantry/hal/pin_map.hpp"
#include "gantry/settings/settings.hpp"
#include "pci7200/emulated_pci7200.hpp"
#include "pci7200/open_pci7200.hpp"
#include "pci7200/pacer_divisor.hpp"
#include "pci7200/pci7200_card.hpp"
#include "pci7200/pci_discovery.hpp"

namespace gantry::pci7200 {
namespace {

namespace fs = std::filesystem;

// Passes when `text` contains `part`; the failure message shows both.
::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

// Distinct, irregular words, so that a dropped, repeated or reordered word shows.
std::vector<std::uint32_t> words(std::size_t n, std::uint32_t seed) {
  std::vector<std::uint32_t> out(n);
  std::uint32_t x = seed * 2654435761u + 1;
  for (std::uint32_t& w : out) {
    x = x * 1664525u + 1013904223u;
    w = x;
  }
  return out;
}

std::vector<std::uint32_t> first(const std::vector<std::uint32_t>& v, std::size_t n) {
  return {v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(n, v.size()))};
}

struct Rig {
  std::shared_ptr<EmulatedPci7200> emu;
  std::unique_ptr<Pci7200Card> card;
};

Rig make_rig(EmulatedPci7200Config config, Pci7200Options options = {}) {
  Rig rig;
  rig.emu = std::make_shared<EmulatedPci7200>(config);
  rig.card = std::make_unique<Pci7200Card>(rig.emu, options);
  return rig;
}

EmulatedPci7200Config stepped(std::size_t dma_words = 2 * 1024) {
  EmulatedPci7200Config config;
  config.stepped = true;
  config.dma_words = dma_words;
  return config;
}

// ---------------------------------------------------------------------------------------
// Pacer.

TEST(Pci7200Pacer, TheDefaultProfileIsDivisor20For200kHz) {
  const Settings settings = default_settings();
  EXPECT_EQ(pacer_divisor(settings.card.clock_hz, settings.card.pacer_hz()).divisor, 20);
  EXPECT_EQ(pacer_divisor(4e6, 200e3).divisor, 20);
  EXPECT_EQ(pacer_divisor(4e6, 2e6).divisor, 2);
  EXPECT_EQ(pacer_divisor(4e6, 4e6 / 65535).divisor, 65535);
}

TEST(Pci7200Pacer, DivisorsOutsideTheCounterAreRejected) {
  const PacerDivisor too_fast = pacer_divisor(4e6, 4e6);  // divisor 1
  EXPECT_FALSE(too_fast.ok());
  EXPECT_TRUE(Contains(too_fast.error, "2..65535"));
  const PacerDivisor too_slow = pacer_divisor(4e6, 4e6 / 65536);
  EXPECT_FALSE(too_slow.ok());
  EXPECT_TRUE(Contains(too_slow.error, "needs divisor 65536"));
  const PacerDivisor fractional = pacer_divisor(4e6, 3e6);
  EXPECT_FALSE(fractional.ok());
  EXPECT_TRUE(Contains(fractional.error, "whole number"));
  EXPECT_FALSE(pacer_divisor(4e6, 0).ok());
  EXPECT_FALSE(pacer_divisor(4e6, -200e3).ok());
  EXPECT_FALSE(pacer_divisor(4e6, std::nan("")).ok());
}

TEST(Pci7200Card, StartProgramsCounter1AndWaitsForWords) {
  Pci7200Options options;
  options.idle_word = 0x00ff0000;
  Rig rig = make_rig(stepped(), options);
  EXPECT_EQ(rig.emu->output_port(), 0x00ff0000u);  // opening rests the outputs
  EXPECT_FALSE(rig.emu->pacer_running());

  rig.card->start(200e3);
  EXPECT_TRUE(rig.emu->pacer_running());
  EXPECT_EQ(rig.emu->pacer_count(), 20u);
  EXPECT_EQ(rig.emu->pacer_mode(), 3);
  EXPECT_EQ(rig.card->pacer_hz(), 200e3);
  // Nothing plays until words are queued.
  rig.emu->advance(100);
  EXPECT_FALSE(rig.emu->output_paced());
  EXPECT_FALSE(rig.emu->dma_reading());
  EXPECT_EQ(rig.emu->played_count(), 0u);
  EXPECT_EQ(rig.card->ticks_played(), 0u);

  EXPECT_THROW(rig.card->start(3e6), std::invalid_argument);
  EXPECT_THROW(rig.card->start(4e6), std::invalid_argument);
  EXPECT_EQ(rig.emu->pacer_count(), 20u);  // a refused pacer changes nothing

  rig.card->start(4e6 / 65535);
  EXPECT_EQ(rig.emu->pacer_count(), 65535u);
  EXPECT_TRUE(rig.card->uses_dma());
}

// ---------------------------------------------------------------------------------------
// Playback.

TEST(Pci7200Card, WordsPlayExactlyAndInOrderAcrossManyDmaRefills) {
  Rig rig = make_rig(stepped(2 * 1024));
  const std::vector<std::uint32_t> all = words(100'000, 1);
  constexpr std::size_t kBlock = 4096;
  rig.card->start(200e3);
  // The producer stays a block ahead of the card, as the job does.
  rig.card->write(std::span(all).subspan(0, kBlock));
  for (std::size_t at = kBlock; at < all.size(); at += kBlock) {
    rig.card->write(std::span(all).subspan(at, std::min(kBlock, all.size() - at)));
    rig.emu->advance(kBlock);
  }
  rig.emu->advance(2 * kBlock);

  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.emu->played(), all);
  EXPECT_EQ(rig.card->ticks_played(), all.size());
  EXPECT_GE(rig.emu->transfers_completed(), all.size() / 1024);
}

TEST(Pci7200Card, ProgrammedIoFallbackPlaysWordsExactly) {
  Rig rig = make_rig(stepped(0));
  EXPECT_FALSE(rig.card->uses_dma());
  const std::vector<std::uint32_t> all = words(20'000, 2);
  constexpr std::size_t kBlock = 1000;
  rig.card->start(200e3);
  rig.card->write(std::span(all).subspan(0, kBlock));
  for (std::size_t at = kBlock; at < all.size(); at += kBlock) {
    rig.card->write(std::span(all).subspan(at, kBlock));
    rig.emu->advance(kBlock);
  }
  rig.emu->advance(2 * kBlock);

  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.emu->played(), all);
  EXPECT_EQ(rig.card->ticks_played(), all.size());
}

TEST(Pci7200Card, DrainThenMoreWordsCarriesOnWithoutAFault) {
  EmulatedPci7200Config config;  // free-running: time passes as the feeder polls
  Rig rig = make_rig(config);
  const std::vector<std::uint32_t> a = words(5000, 3), b = words(3000, 4);
  rig.card->start(200e3);
  rig.card->write(a);
  rig.card->drain();
  EXPECT_EQ(rig.card->ticks_played(), a.size());
  EXPECT_EQ(rig.emu->played_count(), a.size());
  // Fewer words than one DMA half: drain() starts them.
  rig.card->write(b);
  rig.card->drain();
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.card->ticks_played(), a.size() + b.size());
  std::vector<std::uint32_t> both = a;
  both.insert(both.end(), b.begin(), b.end());
  EXPECT_EQ(rig.emu->played(), both);
}

// ---------------------------------------------------------------------------------------
// Underrun.

TEST(Pci7200Card, AStalledFeederIsAnUnderrunWithExactTicks) {
  Rig rig = make_rig(stepped(2 * 1024));
  const std::vector<std::uint32_t> all = words(3000, 5);
  rig.card->start(200e3);
  rig.card->write(all);
  rig.emu->advance(4);  // primes: half 0 (1024 words) in flight, half 1 staged
  EXPECT_EQ(rig.emu->played_count(), 4u);

  // The feeder misses the reload deadline: half 0 plays out and the FIFO runs dry.
  rig.emu->advance_without_feeder(2000);
  EXPECT_EQ(rig.emu->played_count(), 1024u);
  EXPECT_GT(rig.emu->underrun_ticks(), 0u);
  rig.emu->advance(8);

  EXPECT_EQ(rig.card->fault(), CardFault::Underrun);
  EXPECT_EQ(rig.card->ticks_played(), 1024u);
  EXPECT_EQ(rig.emu->played(), first(all, 1024));
  EXPECT_FALSE(rig.emu->pacer_running());
  EXPECT_FALSE(rig.emu->dma_reading());

  // After a fault, words are dropped until the next start().
  rig.card->write(words(100, 6));
  rig.emu->advance(200);
  EXPECT_EQ(rig.emu->played_count(), 1024u);
  EXPECT_EQ(rig.card->ticks_played(), 1024u);
}

TEST(Pci7200Card, AMissedReloadIsCaughtEvenWithoutTheCardsUnderrunFlag) {
  EmulatedPci7200Config config = stepped(2 * 1024);
  config.flags_underrun = false;  // the flag's read-back is not settled by public sources
  Rig rig = make_rig(config);
  const std::vector<std::uint32_t> all = words(3000, 17);
  rig.card->start(200e3);
  rig.card->write(all);
  rig.emu->advance(4);
  rig.emu->advance_without_feeder(1100);
  rig.emu->advance(8);
  EXPECT_EQ(rig.card->fault(), CardFault::Underrun);
  EXPECT_EQ(rig.card->ticks_played(), 1024u);
  EXPECT_EQ(rig.emu->played(), first(all, 1024));
}

TEST(Pci7200Card, WordsWrittenAfterTheCardRanDryAreAnUnderrun) {
  Rig rig = make_rig(stepped(2 * 1024));
  const std::vector<std::uint32_t> all = words(1500, 7);
  rig.card->start(200e3);
  rig.card->write(all);
  rig.emu->advance(1600);
  EXPECT_EQ(rig.card->fault(), CardFault::None);  // running out is not a fault by itself
  EXPECT_EQ(rig.card->ticks_played(), 1500u);

  rig.card->write(words(10, 8));  // too late: the card has already missed ticks
  rig.emu->advance(8);
  EXPECT_EQ(rig.card->fault(), CardFault::Underrun);
  EXPECT_EQ(rig.card->ticks_played(), 1500u);
  EXPECT_EQ(rig.emu->played(), all);
}

// Issue 26: a hold comes to rest and the stream ends there (Card::end_stream); the card runs
// dry and the pacer ticks on an empty FIFO for as long as the operator waits. That was
// taken for an underrun: the card faulted at the resume's first word.
TEST(Pci7200Card, AStreamEndedAtRestRunsDryWithoutAFaultAndTheNextWordsStartAnew) {
  Pci7200Options options;
  options.prime_words = 64;
  Rig rig = make_rig(stepped(2 * 1024), options);
  const std::vector<std::uint32_t> a = words(1500, 21), b = words(300, 22), c = words(10, 23);
  rig.card->start(200e3);
  rig.card->write(a);
  rig.card->end_stream();  // at rest after these
  rig.emu->advance(1600);  // played out, then 100 ticks on an empty FIFO
  EXPECT_GT(rig.emu->underrun_ticks(), 0u);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.card->ticks_played(), a.size());

  rig.card->write(b);  // the resume: a new stretch of output
  rig.card->end_stream();
  rig.emu->advance(400);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  EXPECT_EQ(rig.card->ticks_played(), a.size() + b.size());

  rig.card->write(c);  // fewer than prime_words: the end starts them
  rig.card->end_stream();
  rig.emu->advance(40);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  std::vector<std::uint32_t> all = a;
  all.insert(all.end(), b.begin(), b.end());
  all.insert(all.end(), c.begin(), c.end());
  EXPECT_EQ(rig.emu->played(), all);
  EXPECT_EQ(rig.card->ticks_played(), all.size());

  // Dry before the end of what was written is still an underrun.
  rig.card->write(words(1500, 24));
  rig.emu->advance(4);
  rig.emu->advance_without_feeder(2000);
  rig.emu->advance(8);
  EXPECT_EQ(rig.card->fault(), CardFault::Underrun);
}

// ---------------------------------------------------------------------------------------
// Stop, faults, shutdown.

TEST(Pci7200Card, StopDropsQueuedWordsAndRestsAtTheIdleWord) {
  Rig rig = make_rig(stepped(2 * 1024));
  const std::vector<std::uint32_t> all = words(5000, 9);
  rig.card->start(200e3);
  rig.card->write(all);
  rig.emu->advance(1000);
  EXPECT_EQ(rig.emu->played_count(), 1000u);

  rig.card->stop(0x0000a5a5);
  // The 8 words already in the card's FIFO play out, then the pacer halts.
  EXPECT_EQ(rig.emu->played_count(), 1008u);
  EXPECT_EQ(rig.card->ticks_played(), 1008u);
  EXPECT_EQ(rig.emu->played(), first(all, 1008));
  EXPECT_EQ(rig.emu->output_port(), 0x0000a5a5u);
  EXPECT_FALSE(rig.emu->pacer_running());
  EXPECT_FALSE(rig.emu->output_paced());
  EXPECT_FALSE(rig.emu->dma_reading());
  EXPECT_EQ(rig.card->fault(), CardFault::None);

  rig.card->write(words(100, 10));
  rig.emu->advance(500);
  EXPECT_EQ(rig.emu->played_count(), 1008u);
  EXPECT_EQ(rig.emu->output_port(), 0x0000a5a5u);

  // A new start() plays again from tick 0.
  rig.card->start(200e3);
  const std::vector<std::uint32_t> again = words(2000, 11);
  rig.card->write(again);
  rig.emu->advance(2100);
  EXPECT_EQ(rig.card->ticks_played(), again.size());
  std::vector<std::uint32_t> expected = first(all, 1008);
  expected.insert(expected.end(), again.begin(), again.end());
  EXPECT_EQ(rig.emu->played(), expected);
}

TEST(Pci7200Card, CloseJoinsTheFeederAndLeavesTheCardQuiet) {
  Pci7200Options options;
  options.idle_word = 0x1234;
  Rig rig = make_rig(EmulatedPci7200Config{}, options);
  EXPECT_TRUE(rig.card->feeder_running());
  EXPECT_TRUE(rig.emu->feeder_attached());
  rig.card->start(200e3);
  rig.card->write(words(2000, 12));
  rig.card->drain();
  EXPECT_EQ(rig.card->ticks_played(), 2000u);

  rig.card.reset();  // the destructor stops the output and joins the thread
  EXPECT_FALSE(rig.emu->feeder_attached());
  const std::uint64_t pauses = rig.emu->feeder_pauses();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(rig.emu->feeder_pauses(), pauses);  // nobody is polling any more
  EXPECT_FALSE(rig.emu->pacer_running());
  EXPECT_FALSE(rig.emu->dma_reading());
  EXPECT_FALSE(rig.emu->output_paced());
  EXPECT_EQ(rig.emu->output_port(), 0x1234u);
}

TEST(Pci7200Card, SamplesTheInputPortEvenWhenIdle) {
  Rig rig = make_rig(stepped());
  rig.emu->set_inputs(0xdeadbeef);
  rig.emu->advance(1);
  EXPECT_EQ(rig.card->inputs(), 0xdeadbeefu);
  rig.card->start(200e3);
  rig.emu->set_inputs(0x0000ffff);
  rig.emu->advance(1);
  EXPECT_EQ(rig.card->inputs(), 0x0000ffffu);
}

TEST(Pci7200Card, AnActiveEStopInputTripsTheCard) {
  Pci7200Options options;
  options.estop = {1u << 4, 0};  // active low
  Rig rig = make_rig(stepped(), options);
  rig.emu->set_inputs(0xffffffff);
  rig.card->start(200e3);
  rig.card->write(words(3000, 13));
  rig.emu->advance(100);
  EXPECT_EQ(rig.card->fault(), CardFault::None);

  rig.emu->set_inputs(~(1u << 4));
  rig.emu->advance(4);
  EXPECT_EQ(rig.card->fault(), CardFault::EStop);
  EXPECT_EQ(rig.card->ticks_played(), rig.emu->played_count());
  EXPECT_EQ(rig.emu->played_count(), 100u + 8u);  // the FIFO's 8 words played out
  EXPECT_FALSE(rig.emu->pacer_running());
}

TEST(Pci7200Card, SetTripsReplacesTheInputsThatStopIt) {
  Pci7200Options options;
  options.limits = {1u << 5, 1u << 5};  // active high
  Rig rig = make_rig(stepped(), options);
  rig.card->set_trips({}, {});  // VN: limit switches off
  rig.card->start(200e3);
  rig.card->write(words(3000, 15));
  rig.emu->advance(100);
  rig.emu->set_inputs(1u << 5);
  rig.emu->advance(50);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  rig.emu->set_inputs(0);
  rig.card->set_trips({}, {1u << 5, 1u << 5});  // on again
  rig.emu->advance(50);
  rig.emu->set_inputs(1u << 5);
  rig.emu->advance(4);
  EXPECT_EQ(rig.card->fault(), CardFault::Limit);
  EXPECT_EQ(rig.emu->played_count(), 200u + 8u);
}

TEST(Pci7200Card, ALimitSwitchTripsAsItClosesSoTheToolCanMoveOffIt) {
  Pci7200Options options;
  options.limits = {1u << 5, 1u << 5};
  Rig rig = make_rig(stepped(), options);
  rig.emu->set_inputs(1u << 5);  // the tool stopped on the switch
  rig.emu->advance(4);
  rig.card->start(200e3);
  rig.card->write(words(300, 18));  // the jog off it
  rig.emu->advance(100);
  EXPECT_EQ(rig.card->fault(), CardFault::None);
  rig.emu->set_inputs(0);  // off it
  rig.emu->advance(50);
  rig.emu->set_inputs(1u << 5);  // and onto it again
  rig.emu->advance(4);
  EXPECT_EQ(rig.card->fault(), CardFault::Limit);
}

// limits.travel_only on the PCI-7200's input path (LimitFilter, every card's rule): X's min
// switch (bit 2) trips the card while X steps towards minus, not while it steps towards plus;
// the steps are read from the words the feeder hands to the card.
TEST(Pci7200Card, TravelOnlyTripsOnlyWhileTheAxisStepsTowardsTheSwitch) {
  for (const bool towards_minus : {true, false}) {
    Settings s = default_settings();
    s.limits.travel_only = true;
    Pci7200Options options;
    options.limits = {1u << 2, 1u << 2};  // active high
    options.limit_rule = LimitFilter(s, 200e3);
    Rig rig = make_rig(stepped(), options);
    rig.card->start(200e3);
    const std::uint32_t dir = towards_minus ? 1u << s.pins[0].dir_bit : 0;  // high: minus
    std::vector<std::uint32_t> w(3000, dir);
    for (std::size_t i = 0; i < w.size(); i += 20) w[i] |= 1u << s.pins[0].step_bit;
    rig.card->write(w);
    rig.emu->advance(100);
    rig.emu->set_inputs(1u << 2);
    rig.emu->advance(50);
    EXPECT_EQ(rig.card->fault(), towards_minus ? CardFault::Limit : CardFault::None)
        << towards_minus;
  }
}

TEST(Pci7200Card, TheWatchSeesAnEdgeAtItsSampleAndAStopBitHaltsThePacer) {
  Rig rig = make_rig(stepped());
  rig.card->start(200e3);
  rig.card->watch({1u << 6, 1u << 6, 1u << 6});  // closing, an instant stop
  rig.card->write(words(3000, 16));
  rig.emu->advance(100);
  EXPECT_FALSE(rig.card->watch_fired());
  rig.emu->set_inputs(1u << 6);
  rig.emu->advance(4);
  const std::optional<InputEdge> e = rig.card->watch_fired();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->bit, 6);
  EXPECT_EQ(e->bits, 1u << 6);
  // The sample's tick: the words played when the feeder read the inputs, at most the FIFO's
  // eight behind the edge.
  EXPECT_GE(e->tick, 100u - 8u);
  EXPECT_LE(e->tick, 100u);
  EXPECT_EQ(rig.card->fault(), CardFault::None);  // a stop, not a fault
  EXPECT_FALSE(rig.emu->pacer_running());
  EXPECT_EQ(rig.card->ticks_played(), rig.emu->played_count());
  EXPECT_EQ(rig.emu->played_count(), 100u + 8u);
  rig.card->write(words(10, 17));  // dropped until started again
  rig.emu->advance(20);
  EXPECT_EQ(rig.emu->played_count(), 108u);
}

TEST(Pci7200Card, ABridgeAbortIsAHardwareFault) {
  Rig rig = make_rig(stepped());
  rig.card->start(200e3);
  rig.card->write(words(3000, 14));
  rig.emu->advance(100);
  rig.emu->inject_dma_abort();
  rig.emu->advance(4);
  EXPECT_EQ(rig.card->fault(), CardFault::Hardware);
  EXPECT_FALSE(rig.emu->pacer_running());
}

TEST(Pci7200Card, ALostDeviceIsAHardwareFault) {
  Rig rig = make_rig(stepped());
  rig.card->start(200e3);
  rig.card->write(words(3000, 15));
  rig.emu->advance(100);
  rig.emu->remove_device();
  rig.emu->advance(4);
  EXPECT_EQ(rig.card->fault(), CardFault::Hardware);
}

TEST(Pci7200Card, TheChargePumpTogglesWhilePlayingAndRestsLow) {
  Pci7200Options options;
  options.charge_pump_bit = 31;
  options.charge_pump_hz = 12'500;  // 8 ticks high, 8 low at 200 kHz
  Rig rig = make_rig(stepped(), options);
  const std::vector<std::uint32_t> all = words(3000, 16);
  rig.card->start(200e3);
  rig.card->write(all);
  rig.emu->advance(3100);
  const std::vector<std::uint32_t> played = rig.emu->played();
  ASSERT_EQ(played.size(), all.size());
  for (std::size_t i = 0; i < played.size(); ++i) {
    ASSERT_EQ(played[i] & 0x7fffffffu, all[i] & 0x7fffffffu) << "word " << i;
    ASSERT_EQ((played[i] >> 31) != 0, (i / 8) % 2 == 0) << "word " << i;
  }
  rig.card->stop(0xffffffff);
  EXPECT_EQ(rig.emu->output_port(), 0x7fffffffu);
}

// ---------------------------------------------------------------------------------------
// The emulation's model, on its own.

TEST(EmulatedPci7200, TheFifoHoldsEightWordsAndAnEmptyTickIsFlagged) {
  EmulatedPci7200 emu;
  const DmaBuffer dma = emu.dma_buffer();
  for (std::uint32_t i = 0; i < 16; ++i) dma.words[i] = 100 + i;
  emu.write32(Bar::Card, card::kCounterControl, i8254::control_word(1, 3));
  emu.write32(Bar::Card, card::kCounter1, 20);
  EXPECT_FALSE(emu.pacer_running());  // the MSB is still to come
  emu.write32(Bar::Card, card::kCounter1, 0);
  EXPECT_TRUE(emu.pacer_running());
  emu.write32(Bar::Amcc, amcc::kMrar, dma.bus_address);
  emu.write32(Bar::Amcc, amcc::kMrtc, 16 * 4);
  emu.write32(Bar::Amcc, amcc::kMcsr, amcc::kMcsrReadEnable);
  EXPECT_EQ(emu.fifo_fill(), 8u);
  EXPECT_TRUE(emu.read32(Bar::Amcc, amcc::kMcsr) & amcc::kMcsrP2aFifoFull);
  EXPECT_EQ(emu.read32(Bar::Amcc, amcc::kMrtc), 8u * 4);

  emu.write32(Bar::Card, card::kDioCsr, card::kDioDoTimerPaced);
  emu.advance_without_feeder(16);
  std::vector<std::uint32_t> expected;
  for (std::uint32_t i = 0; i < 16; ++i) expected.push_back(100 + i);
  EXPECT_EQ(emu.played(), expected);
  EXPECT_EQ(emu.read32(Bar::Amcc, amcc::kMrtc), 0u);
  EXPECT_TRUE(emu.read32(Bar::Amcc, amcc::kIntcsr) & amcc::kIntcsrReadComplete);
  EXPECT_EQ(emu.underrun_ticks(), 0u);
  EXPECT_FALSE(emu.read32(Bar::Card, card::kDioCsr) & card::kDioDoUnderrun);

  emu.advance_without_feeder(1);
  EXPECT_EQ(emu.underrun_ticks(), 1u);
  EXPECT_EQ(emu.output_port(), 115u);  // the latch holds the last word
  EXPECT_TRUE(emu.read32(Bar::Card, card::kDioCsr) & card::kDioDoUnderrun);
  emu.write32(Bar::Card, card::kDioCsr, card::kDioDoTimerPaced | card::kDioDoUnderrun);
  EXPECT_FALSE(emu.read32(Bar::Card, card::kDioCsr) & card::kDioDoUnderrun);

  // A control word alone halts the counter.
  emu.write32(Bar::Card, card::kCounterControl, i8254::control_word(1, 3));
  EXPECT_FALSE(emu.pacer_running());
}

TEST(EmulatedPci7200, CascadingCounter2DividesThePacerFurther) {
  EmulatedPci7200 emu;
  for (int counter : {1, 2}) {
    emu.write32(Bar::Card, card::kCounterControl, i8254::control_word(counter, 3));
    emu.write32(Bar::Card, i8254::counter_offset(counter), 10);
    emu.write32(Bar::Card, i8254::counter_offset(counter), 0);
  }
  emu.write32(Bar::Card, card::kIntCsr, card::kIntT1T2Cascade);
  for (std::uint32_t i = 0; i < 8; ++i) emu.write32(Bar::Amcc, amcc::kFifo, i);
  emu.write32(Bar::Card, card::kDioCsr, card::kDioDoTimerPaced);
  emu.sleep_for(std::chrono::microseconds(25 * 3));  // 3 periods of 100 clocks
  EXPECT_EQ(emu.played_count(), 3u);
}

// ---------------------------------------------------------------------------------------
// Discovery in a fake sysfs tree.

class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "gantry_pci7200_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// A device directory as sysfs shows it: IDs, and links to its driver and IOMMU group.
void add_device(const fs::path& devices, const std::string& address, const std::string& vendor,
                const std::string& device, const std::string& driver = "", int iommu_group = -1) {
  const fs::path dir = devices / address;
  write_file(dir / "vendor", vendor + "\n");
  write_file(dir / "device", device + "\n");
  if (!driver.empty())
    fs::create_directory_symlink("../../../bus/pci/drivers/" + driver, dir / "driver");
  if (iommu_group >= 0)
    fs::create_directory_symlink("../../../kernel/iommu_groups/" + std::to_string(iommu_group),
                                 dir / "iommu_group");
}

TEST(Pci7200Discovery, NoCardGivesTheIdsWhereItLookedAndTheQuestion) {
  TempDir tmp;
  const fs::path devices = tmp.path() / "devices";
  add_device(devices, "0000:00:02.0", "0x8086", "0x1234");
  const PciDiscovery found = find_pci7200(devices.string());
  EXPECT_TRUE(found.cards.empty());
  EXPECT_EQ(found.error,
            "no PCI-7200 found (vendor 144a device 7200, or vendor 10e8 device "
            "80d8 on AMCC-based cards) in " +
                devices.string() + "; is the card fitted?");

  Pci7200OpenOptions options;
  options.sysfs_devices = devices.string();
  std::string error;
  EXPECT_EQ(open_pci7200(default_settings(), options, &error), nullptr);
  EXPECT_EQ(error, found.error);

  EXPECT_TRUE(Contains(find_pci7200((tmp.path() / "missing").string()).error, "is sysfs mounted?"));
}

TEST(Pci7200Discovery, FindsBothIdsWithTheirDriverAndGroup) {
  TempDir tmp;
  const fs::path devices = tmp.path() / "devices";
  add_device(devices, "0000:05:01.0", "0x10e8", "0x80d8");
  add_device(devices, "0000:03:00.0", "0x144a", "0x7200", "vfio-pci", 12);
  add_device(devices, "0000:00:1f.0", "0x144a", "0x7250", "p7250");
  const PciDiscovery found = find_pci7200(devices.string());
  ASSERT_EQ(found.cards.size(), 2u);
  EXPECT_EQ(found.cards[0].address, "0000:03:00.0");
  EXPECT_EQ(found.cards[0].id.vendor, 0x144a);
  EXPECT_EQ(found.cards[0].id.device, 0x7200);
  EXPECT_EQ(found.cards[0].driver, "vfio-pci");
  EXPECT_EQ(found.cards[0].iommu_group, 12);
  EXPECT_EQ(found.cards[1].address, "0000:05:01.0");
  EXPECT_EQ(found.cards[1].id.vendor, 0x10e8);
  EXPECT_EQ(found.cards[1].driver, "");
  EXPECT_EQ(found.cards[1].iommu_group, -1);

  EXPECT_EQ(choose_transport(found.cards[0]).transport, Transport::Vfio);
  const TransportChoice unbound = choose_transport(found.cards[1]);
  EXPECT_EQ(unbound.transport, Transport::None);
  EXPECT_TRUE(Contains(unbound.error, "0000:05:01.0 is bound to no driver"));
  EXPECT_TRUE(Contains(unbound.error, "bind it to vfio-pci"));
  EXPECT_TRUE(Contains(unbound.error, "no IOMMU group"));
}

TEST(Pci7200Discovery, EachDriverStateNamesItsFix) {
  PciDeviceLocation card;
  card.address = "0000:03:00.0";
  card.driver = "uio_pci_generic";
  EXPECT_EQ(choose_transport(card).transport, Transport::ProgrammedIo);
  card.driver = "vfio-pci";
  const TransportChoice no_group = choose_transport(card);
  EXPECT_EQ(no_group.transport, Transport::None);
  EXPECT_TRUE(Contains(no_group.error, "no IOMMU group"));
  EXPECT_TRUE(Contains(no_group.error, "intel_iommu=on"));
  EXPECT_TRUE(Contains(no_group.error, "uio_pci_generic"));
  card.driver = "p7200";
  EXPECT_TRUE(Contains(choose_transport(card).error, "is bound to p7200; unbind it"));
}

TEST(Pci7200Discovery, PermissionDeniedNamesTheUdevRuleAndTheReadme) {
  EXPECT_EQ(open_failure_message("/dev/vfio/12", EACCES),
            "/dev/vfio/12: permission denied; add a udev rule or run as root; see "
            "drivers/pci7200/README.md");
  EXPECT_TRUE(Contains(open_failure_message("/dev/vfio/12", ENOENT), "does not exist"));
  EXPECT_TRUE(Contains(open_failure_message("/dev/vfio/12", EBUSY), "busy"));

  // Through the whole open path, where the file mode can stop us (root is never stopped).
  if (geteuid() == 0) return;
  TempDir tmp;
  add_device(tmp.path() / "devices", "0000:03:00.0", "0x144a", "0x7200", "vfio-pci", 12);
  const fs::path group = tmp.path() / "dev" / "vfio" / "12";
  write_file(group, "");
  chmod(group.c_str(), 0);
  Pci7200OpenOptions options;
  options.sysfs_devices = (tmp.path() / "devices").string();
  options.dev_root = (tmp.path() / "dev").string();
  std::string error;
  EXPECT_EQ(open_pci7200(default_settings(), options, &error), nullptr);
  EXPECT_EQ(error, group.string() +
                       ": permission denied; add a udev rule or run as root; see "
                       "drivers/pci7200/README.md");
}

TEST(Pci7200Discovery, OpeningVfioThroughAFakeTreeStopsWithAMessage) {
  TempDir tmp;
  add_device(tmp.path() / "devices", "0000:03:00.0", "0x144a", "0x7200", "vfio-pci", 12);
  Pci7200OpenOptions options;
  options.sysfs_devices = (tmp.path() / "devices").string();
  options.dev_root = (tmp.path() / "dev").string();
  std::string error;
  EXPECT_EQ(open_pci7200(default_settings(), options, &error), nullptr);
  EXPECT_TRUE(Contains(error, options.dev_root + "/vfio/12: does not exist"));

  write_file(tmp.path() / "dev" / "vfio" / "12", "");  // a file, not a VFIO group
  EXPECT_EQ(open_pci7200(default_settings(), options, &error), nullptr);
  EXPECT_TRUE(Contains(error, options.dev_root + "/vfio/12: not a VFIO group"));
}

TEST(Pci7200Discovery, ProgrammedIoNeedsTheCardsIoPortBars) {
  TempDir tmp;
  const fs::path devices = tmp.path() / "devices";
  add_device(devices, "0000:03:00.0", "0x144a", "0x7200", "uio_pci_generic");
  // A memory BAR where the card has an I/O-port BAR: not this card.
  write_file(devices / "0000:03:00.0" / "resource",
             "0x00000000fe000000 0x00000000fe00003f 0x0000000000040200\n"
             "0x000000000000e000 0x000000000000e01f 0x0000000000040101\n");
  Pci7200OpenOptions options;
  options.sysfs_devices = devices.string();
  std::string error;
  EXPECT_EQ(open_pci7200(default_settings(), options, &error), nullptr);
  EXPECT_TRUE(Contains(error, "BAR0 is not a 64-byte I/O-port BAR"));
}

TEST(Pci7200Open, TheProfilesEStopAndLimitInputsTripTheCard) {
  std::string error;
  const auto options = pci7200_options_for(default_settings(), Pci7200OpenOptions{}, &error);
  ASSERT_TRUE(options) << error;
  EXPECT_EQ(options->estop.mask, 1u);  // bit 0, active low (a normally-closed chain)
  EXPECT_EQ(options->estop.active_high, 0u);
  EXPECT_TRUE(options->estop.tripped(0));
  EXPECT_FALSE(options->estop.tripped(1));
  EXPECT_EQ(options->limits.mask, 0xFCu);  // X, Y, Z min and max: bits 2-7, active high
  EXPECT_EQ(options->limits.active_high, 0xFCu);
  EXPECT_EQ(options->charge_pump_bit, -1);  // the words carry the profile's charge pump
}

TEST(Pci7200Open, ProfilesTheCardCannotRunAreRefused) {
  Pci7200OpenOptions options;
  std::string error;
  Settings settings = default_settings();
  ASSERT_TRUE(pci7200_options_for(settings, options, &error)) << error;
  EXPECT_EQ(pci7200_options_for(settings, options, &error)->idle_word,
            PinMap::from(settings.pins).idle_word());

  options.charge_pump_bit = settings.pins[0].step_bit;
  EXPECT_FALSE(pci7200_options_for(settings, options, &error));
  EXPECT_TRUE(Contains(error, "charge-pump output bit"));

  options = {};
  settings.card.clock_hz = 5e6;
  EXPECT_FALSE(pci7200_options_for(settings, options, &error));
  EXPECT_TRUE(Contains(error, "clock_hz"));

  settings = default_settings();
  settings.card.pacer_divisor = 1;
  EXPECT_FALSE(pci7200_options_for(settings, options, &error));
  EXPECT_TRUE(Contains(error, "2..65535"));
}

}  // namespace
}  // namespace gantry::pci7200
