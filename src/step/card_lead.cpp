// The bounded lead: block size and the wait after each block (see card_lead.hpp).
#include "gantry/step/card_lead.hpp"

#include <algorithm>  // clamp, max, min
#include <chrono>
#include <cmath>  // llround
#include <thread>

#include <fmt/format.h>  // the note when the lead grows

#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {
namespace {

using namespace std::chrono_literals;

// A card whose clock stands this long with words queued is not playing (stopped, faulted
// from another thread, or below its start threshold): the generator goes on, and the card
// blocks or drops the words as it did before the lead.
constexpr auto kStalled = 2s;
// Sleeps are at least this (a shorter one costs more than it saves) and at most this (the
// card's inputs and faults are looked at this often while waiting).
constexpr auto kShortestSleep = 50us;
constexpr auto kLongestSleep = 5ms;
// The smallest block: below it the per-block cost (a sleep, a check of the card) dominates.
constexpr std::int64_t kLeastBlock = 16;

}  // namespace

CardLead::CardLead(const Settings& settings, const Card& card, std::size_t block_words)
    : card_(card), tick_s_(1.0 / settings.card.pacer_hz()), block_words_(block_words) {
  if (!card.queues_words()) return;
  const std::int64_t want = std::llround(settings.card.lead_ms * 1e-3 * settings.card.pacer_hz());
  const auto block =
      std::clamp<std::int64_t>(want / 4, kLeastBlock, static_cast<std::int64_t>(block_words));
  block_words_ = static_cast<std::size_t>(block);
  lead_ticks_ = std::max(want, static_cast<std::int64_t>(card.start_words()) + block);
  cap_ticks_ = std::max<std::int64_t>(lead_ticks_,
                                      std::llround(Card::kMostLeadS * settings.card.pacer_hz()));
}

std::int64_t CardLead::queued(std::int64_t sent) const {
  return sent - static_cast<std::int64_t>(card_.clock_tick());
}

void CardLead::sleep_at_most(std::int64_t ticks, std::chrono::microseconds most) const {
  const auto due =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::duration<double>(
          static_cast<double>(std::max<std::int64_t>(ticks, 0)) * tick_s_));
  std::this_thread::sleep_for(std::clamp<std::chrono::microseconds>(due, kShortestSleep, most));
}

void CardLead::after_block(std::int64_t sent, const std::function<void()>& poll) {
  if (!bounded()) return;
  using Clock = std::chrono::steady_clock;
  const auto block = static_cast<std::int64_t>(block_words_);
  // The block came `late` ticks late, the card holding `held`: when that is more than half
  // the margin, the lead grows to twice the lateness (or the latest wake-up of the lead's
  // sleeps, if longer: what the next block may meet) plus a block, at least by half.
  const auto grow = [&](std::int64_t late, std::int64_t held, bool woke_late) {
    if (2 * late <= lead_ticks_ - block || lead_ticks_ >= cap_ticks_) return;
    const std::int64_t was = lead_ticks_;
    const std::int64_t woke = std::llround(stats_.most_woke_late_s / tick_s_);
    lead_ticks_ = std::min(
        cap_ticks_, std::max({lead_ticks_ + lead_ticks_ / 2, 2 * late + block, 2 * woke + block}));
    if (stats_.grown++ == 0 && on_grow_)
      on_grow_(fmt::format(
          "the feeder {} {:.1f} ms late (the card's queue held {:.1f} ms): the lead grows from "
          "{:.0f} ms to {:.0f} ms (at most {:.0f} ms), and a hold now begins within it",
          woke_late ? "was woken" : "came", static_cast<double>(late) * tick_s_ * 1e3,
          static_cast<double>(held) * tick_s_ * 1e3, static_cast<double>(was) * tick_s_ * 1e3,
          static_cast<double>(lead_ticks_) * tick_s_ * 1e3,
          static_cast<double>(cap_ticks_) * tick_s_ * 1e3));
  };
  auto clock = static_cast<std::int64_t>(card_.clock_tick());
  if (steady_) {  // what the card held when this block came
    const std::int64_t refill = lead_ticks_ - block;
    const std::int64_t held = sent - block - clock;
    const std::int64_t late = refill - held;
    ++stats_.blocks;
    stats_.least_queue_ticks = std::min(stats_.least_queue_ticks, held);
    if (late > stats_.worst_late_ticks) {
      stats_.worst_late_ticks = late;
      const auto since = Clock::now() - resumed_;
      stats_.worst_woke_late_s = std::chrono::duration<double>(woke_late_).count();
      stats_.worst_starved_s = std::chrono::duration<double>(starved_).count();
      stats_.worst_work_s = std::chrono::duration<double>(since - starved_).count();
    }
    // Grown on lateness seen on the wall clock as well as the card's: a card whose clock is
    // not the wall's (a test's stepped one) runs behind the words by design, and a card not
    // playing (held 0: stopped, at rest) says nothing of the feeder.
    const auto wall = std::chrono::duration<double>(woke_late_ + (Clock::now() - resumed_));
    if (held > 0)
      grow(std::min<std::int64_t>(late, std::llround(wall.count() / tick_s_)), held, false);
  }
  steady_ = false;
  woke_late_ = {};
  std::int64_t last_clock = clock;
  auto still_since = Clock::now();
  while (card_.fault() == CardFault::None) {
    const std::int64_t excess = sent - clock - (lead_ticks_ - block);
    if (excess <= 0) break;
    const auto now = Clock::now();
    if (clock != last_clock) {
      last_clock = clock;
      still_since = now;
    } else if (now - still_since > kStalled) {
      break;
    }
    steady_ = true;
    ++stats_.waits;
    const auto due = std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::duration<double>(static_cast<double>(excess) * tick_s_));
    const auto asked = std::clamp<std::chrono::microseconds>(
        due, kShortestSleep, std::chrono::duration_cast<std::chrono::microseconds>(kLongestSleep));
    std::this_thread::sleep_for(asked);
    const auto slept = Clock::now() - now;
    woke_late_ = std::max(Clock::duration{}, slept - asked);
    stats_.most_woke_late_s =
        std::max(stats_.most_woke_late_s, std::chrono::duration<double>(woke_late_).count());
    if (poll) poll();
    const std::int64_t before = clock;
    clock = static_cast<std::int64_t>(card_.clock_tick());
    // A sleep the kernel ended late says what the next block may meet, even when this one
    // had time to spare: the lead grows before a block comes late (a computer that wakes a
    // thread 60 ms late now and then does so 10-30 ms late far more often).
    // Only on a card whose clock followed the wall's over the sleep (within a quarter): a
    // test's stepped clock says nothing of the kernel's wake-ups. And late on the card's
    // clock too: below the refill point now.
    const double card_s = static_cast<double>(clock - before) * tick_s_;
    const double wall_s = std::chrono::duration<double>(slept).count();
    if (const std::int64_t held = sent - clock;
        held > 0 && card_s > 0.75 * wall_s && card_s < 1.25 * wall_s)
      grow(std::min<std::int64_t>(
               std::llround(std::chrono::duration<double>(woke_late_).count() / tick_s_),
               lead_ticks_ - block - held),
           held, true);
  }
  resumed_ = Clock::now();
  starved_ = {};
}

}  // namespace gantry
