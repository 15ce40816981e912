// The debounce count of a card's inputs (WinCNC's lim_cnt and g28_lim_cnt): one counter,
// used by the limit rule (LimitFilter) and by the input watch homing stops on (EdgeDetector).
#pragma once

#include <algorithm>  // max
#include <cstdint>
#include <limits>

namespace gantry {

// Inputs that begin counting share one count of samples, from the first of them; the count is
// reached once they have read active in `needed` samples in a row. An input that reads
// inactive before that is forgotten (a spike), and the count starts again with the next.
class Debounce {
 public:
  static constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();

  explicit Debounce(int needed = 1) : needed_(static_cast<std::uint64_t>(std::max(1, needed))) {}

  // One sample, standing for `repeat` consecutive samples alike (a card that skips runs of
  // words with nothing new): `active`, the inputs reading active in it; `fresh`, those that
  // begin counting with it. True: the count is reached.
  bool sample(std::uint32_t active, std::uint32_t fresh, std::uint64_t repeat = 1) {
    pending_ &= active;  // released before the count: forgotten
    if (pending_ == 0)
      count_ = 0;
    else
      count_ += repeat;  // those counting read active again
    fresh &= ~pending_;
    if (fresh != 0) {
      // A later input counts with the first: a second switch closing while the first counts
      // is a hit all the same.
      if (pending_ == 0) count_ = repeat;
      pending_ |= fresh;
    }
    return reached();
  }
  bool reached() const { return pending_ != 0 && count_ >= needed_; }
  // How many more samples alike reach the count; kNone when no input counts.
  std::uint64_t samples_left() const {
    if (pending_ == 0) return kNone;
    return count_ >= needed_ ? 0 : needed_ - count_;
  }
  std::uint32_t pending() const { return pending_; }  // the inputs counting
  int needed() const { return static_cast<int>(needed_); }
  void reset() { pending_ = 0, count_ = 0; }

 private:
  std::uint64_t needed_;
  std::uint32_t pending_ = 0;
  std::uint64_t count_ = 0;
};

}  // namespace gantry
