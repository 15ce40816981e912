// The bounded lead: block size and the wait after each block (see card_lead.hpp).
#include "gantry/step/card_lead.hpp"

#include <algorithm>  // clamp, max, min
#include <chrono>
#include <cmath>  // llround
#include <thread>

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
  const auto block = std::clamp<std::int64_t>(want / 4, kLeastBlock,
                                              static_cast<std::int64_t>(block_words));
  block_words_ = static_cast<std::size_t>(block);
  lead_ticks_ = std::max(want, static_cast<std::int64_t>(card.start_words()) + block);
}

void CardLead::after_block(std::int64_t sent, const std::function<void()>& poll) {
  if (!bounded()) return;
  const auto block = static_cast<std::int64_t>(block_words_);
  const std::int64_t refill = lead_ticks_ - block;
  auto clock = static_cast<std::int64_t>(card_.clock_tick());
  if (steady_) {  // what the card held when this block came
    const std::int64_t held = sent - block - clock;
    ++stats_.blocks;
    stats_.least_queue_ticks = std::min(stats_.least_queue_ticks, held);
    stats_.worst_late_ticks = std::max(stats_.worst_late_ticks, refill - held);
  }
  steady_ = false;
  std::int64_t last_clock = clock;
  auto still_since = std::chrono::steady_clock::now();
  while (card_.fault() == CardFault::None) {
    const std::int64_t excess = sent - clock - refill;
    if (excess <= 0) break;
    const auto now = std::chrono::steady_clock::now();
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
    std::this_thread::sleep_for(std::clamp<std::chrono::microseconds>(
        due, kShortestSleep, std::chrono::duration_cast<std::chrono::microseconds>(kLongestSleep)));
    if (poll) poll();
    clock = static_cast<std::int64_t>(card_.clock_tick());
  }
}

}  // namespace gantry
