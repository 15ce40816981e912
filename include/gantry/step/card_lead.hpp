// The bounded lead into a card that queues words: at most the profile's card.lead_ms of words
// generated ahead of the card's clock, so that a hold begins within it (issue 26).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>

#include "gantry/hal/card.hpp"  // Card

namespace gantry {

struct Settings;

// How the feeder kept up with the card under the lead, in ticks. Counted only for blocks
// written in a steady stream (the block before had to wait for the lead), so the start of a
// stream, which fills an empty queue, is not counted as late.
struct LeadStats {
  std::uint64_t blocks = 0;  // blocks handed over in a steady stream
  std::uint64_t waits = 0;   // sleeps while the lead was full
  // The feeder's worst lateness: how far below its refill point (lead less one block) the
  // card's queue had fallen when the next block reached it (the wake-up's lateness plus the
  // time to generate the block). An underrun needs more than lead - block.
  std::int64_t worst_late_ticks = 0;
  // The least the card still held when a block reached it (0 or less: it ran dry).
  std::int64_t least_queue_ticks = std::numeric_limits<std::int64_t>::max();
  // Where the worst lateness came from (wall clock, s): the feeder's last sleep ending later
  // than asked (the kernel woke it late: descheduled), waiting for the job thread's moves
  // (the queue empty), and the rest (generating the block, writing it, preempted meanwhile).
  double worst_woke_late_s = 0, worst_starved_s = 0, worst_work_s = 0;
  double most_woke_late_s = 0;  // the latest wake-up of any of the lead's sleeps
  std::uint64_t grown = 0;      // times the lead grew (the feeder's lateness ate into it)
};

// A card that plays words as they are written (Card::queues_words() false: the simulator in
// virtual time) has no lead: blocks stay as large as asked and nothing waits. Otherwise the
// block is a quarter of the lead (so a hold's latency is the lead, not a large block), and
// after each block the generator sleeps until the card's clock is within lead - block of the
// words sent. The lead is never below the card's start threshold plus one block, or the
// card would wait for words the generator holds back.
//
// The lead adapts: when a block reaches the card later than half the margin the lead leaves
// (lead less one block), the lead grows to twice that lateness plus the block (at least by
// half), up to 200 ms (or the lead as set, if longer), and `on_grow` is told (once: the controller logs it). A
// longer lead rides out the stalls this computer has; a hold then begins within the longer
// lead. It never shrinks within a run.
class CardLead {
 public:
  CardLead(const Settings& settings, const Card& card, std::size_t block_words);

  bool bounded() const { return lead_ticks_ > 0; }
  std::size_t block_words() const { return block_words_; }
  std::int64_t lead_ticks() const { return lead_ticks_; }  // 0: not bounded
  double lead_s() const { return static_cast<double>(lead_ticks_) * tick_s_; }

  // After a full block whose words end at tick `sent` went to the card: waits, sleeping,
  // while the card's clock is more than lead - block behind `sent`, calling `poll` after each
  // sleep (the card's faults, input edges and the readout are looked at meanwhile; it may
  // throw). Returns at once when the card faulted, or when its clock stands still for long
  // (stopped, or not yet started): then there is nothing to wait for.
  void after_block(std::int64_t sent, const std::function<void()>& poll);
  // A stream came to rest (a flush): the next block starts a new one.
  void rest() { steady_ = false; }
  // Told the first time the lead grows, with what happened (for the log).
  void on_grow(std::function<void(const std::string&)> f) { on_grow_ = std::move(f); }
  // Time the feeder waited for the job thread's moves since the last block (the breakdown).
  void starved_for(std::chrono::steady_clock::duration d) { starved_ += d; }
  // Ticks the card holds of the words sent up to `sent` (0 or less: none, or not playing).
  std::int64_t queued(std::int64_t sent) const;
  // Ticks until the card's queue is down to where the next block is due (lead less one
  // block): 0 or less, due now.
  std::int64_t slack(std::int64_t sent) const { return queued(sent) - refill_ticks(); }
  std::int64_t refill_ticks() const {
    return lead_ticks_ - static_cast<std::int64_t>(block_words_);
  }
  // Sleeps for `ticks` of the card's clock, at most `most` (and at least the shortest sleep).
  void sleep_at_most(std::int64_t ticks, std::chrono::microseconds most) const;

  const LeadStats& stats() const { return stats_; }
  double tick_s() const { return tick_s_; }

 private:
  const Card& card_;
  double tick_s_;
  std::size_t block_words_;
  std::int64_t lead_ticks_ = 0;
  std::int64_t cap_ticks_ = 0;  // the most it grows to
  bool steady_ = false;  // the last block waited: the queue was full
  LeadStats stats_;
  std::function<void(const std::string&)> on_grow_;
  // The breakdown of the next block's lateness: since the lead last let the generator go.
  std::chrono::steady_clock::time_point resumed_{};
  std::chrono::steady_clock::duration starved_{}, woke_late_{};
};

}  // namespace gantry
