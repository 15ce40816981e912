// The played-steps log: confirming steps as the card plays them, and positions at a tick.
#include "gantry/step/step_log.hpp"

#include <utility>  // move

namespace gantry {

StepLog::StepLog(std::int64_t history_ticks) : log_(4096), history_ticks_(history_ticks) {}

// Confirmed steps stay as history for about a second of ticks: an input edge found late (a
// card that samples its inputs in its own thread) is still placed exactly.
void StepLog::confirm(std::uint64_t played) {
  const std::size_t n = log_.size();
  while (played_ != end_ && static_cast<std::uint64_t>(log_[played_].tick) < played) {
    confirmed_[log_[played_].axis] += log_[played_].delta;
    played_ = (played_ + 1) % n;
  }
  const auto keep_from = static_cast<std::int64_t>(played) - history_ticks_;
  while (begin_ != played_ && log_[begin_].tick < keep_from) {
    begin_ = (begin_ + 1) % n;
    history_from_ = keep_from;
  }
}

// From the confirmed counts: back over the history kept, or on over the steps not confirmed.
std::optional<Steps6> StepLog::position_at(std::uint64_t tick) const {
  const auto t = static_cast<std::int64_t>(tick);
  if (t < history_from_) return std::nullopt;  // older than the history kept
  Steps6 p = confirmed_;
  const std::size_t n = log_.size();
  std::size_t k = played_;
  while (k != begin_) {
    const StepRecord& r = log_[(k + n - 1) % n];
    if (r.tick < t) break;
    p[r.axis] -= r.delta;
    k = (k + n - 1) % n;
  }
  for (k = played_; k != end_; k = (k + 1) % n) {
    const StepRecord& r = log_[k];
    if (r.tick >= t) break;
    p[r.axis] += r.delta;
  }
  return p;
}

void StepLog::restart(const Steps6& played, std::int64_t tick) {
  confirmed_ = played;
  begin_ = played_ = end_ = 0;
  history_from_ = tick;
}

// Full: the card's queue and the history hold more steps than ever before. Grow (doubling,
// so this happens a few times per job at most), keeping the ring's order.
void StepLog::grow() {
  std::vector<StepRecord> bigger;
  bigger.reserve(log_.size() * 2);
  std::size_t played = 0;
  for (std::size_t k = begin_; k != end_; k = (k + 1) % log_.size()) {
    if (k == played_) played = bigger.size();
    bigger.push_back(log_[k]);
  }
  if (played_ == end_) played = bigger.size();
  begin_ = 0;
  played_ = played;
  end_ = bigger.size();
  bigger.resize(log_.size() * 2);
  log_ = std::move(bigger);
}

}  // namespace gantry
