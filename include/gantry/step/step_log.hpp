// The played-steps log: every step emitted, until the card confirms it played and for about
// a second after, so that the tool's position at any recent tick is exact.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "gantry/core/axes.hpp"  // Steps6

namespace gantry {

// A ring of steps: [begin_, played_) played (kept as history), [played_, end_) not yet
// confirmed played. `confirmed_` is the count at played_; a position at a tick is found
// from it, back over the history or on over the steps not confirmed.
class StepLog {
 public:
  // History is kept for `history_ticks` (about a second of the card's ticks).
  explicit StepLog(std::int64_t history_ticks);

  // A step of `delta` (+1 or -1) on `axis` goes out at `tick`, after every step logged so far.
  void record(std::int64_t tick, int axis, int delta) {
    if ((end_ + 1) % log_.size() == begin_) grow();
    log_[end_] = {tick, axis, delta};
    end_ = (end_ + 1) % log_.size();
  }
  // The card has played the ticks before `played`: steps before it are confirmed, and those
  // older than the history kept are forgotten.
  void confirm(std::uint64_t played);
  // The steps the words before `tick` make: where the tool was then. Exact for ticks not
  // yet played and for about the last second played; nullopt when older.
  std::optional<Steps6> position_at(std::uint64_t tick) const;
  // Starts again from `played` (the count the card played up to `tick`), with no history.
  void restart(const Steps6& played, std::int64_t tick);

 private:
  struct StepRecord {
    std::int64_t tick;
    int axis;
    int delta;
  };
  void grow();

  std::vector<StepRecord> log_;
  std::size_t begin_ = 0, played_ = 0, end_ = 0;
  Steps6 confirmed_{};  // steps known played: the count at played_
  std::int64_t history_ticks_ = 0;
  std::int64_t history_from_ = 0;  // steps before this tick are no longer kept
};

}  // namespace gantry
