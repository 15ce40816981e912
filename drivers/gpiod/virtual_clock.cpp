// The tests' clock: virtual time, free-running or stepped by the test.
#include "gpiod/virtual_clock.hpp"

#include <algorithm>

namespace gantry {

std::int64_t VirtualClock::now_ns() {
  std::lock_guard lock(mutex_);
  return now_;
}

void VirtualClock::sleep_until_ns(std::int64_t deadline_ns) {
  std::unique_lock lock(mutex_);
  ++sleep_count_;
  if (interrupted_) return;
  if (mode_ == Mode::Gated) {
    sleeping_ = true;
    sleep_deadline_ = deadline_ns;
    changed_.notify_all();
    changed_.wait(lock, [&] { return interrupted_ || now_ >= deadline_ns; });
    sleeping_ = false;
    if (interrupted_) return;
  }
  now_ = std::max(now_, deadline_ns);
  if (late_count_ > 0) {
    --late_count_;
    now_ += late_ns_;
  }
}

void VirtualClock::interrupt() {
  std::lock_guard lock(mutex_);
  interrupted_ = true;
  changed_.notify_all();
}

void VirtualClock::clear_interrupt() {
  std::lock_guard lock(mutex_);
  interrupted_ = false;
}

void VirtualClock::make_late(std::int64_t late_ns, int count) {
  std::lock_guard lock(mutex_);
  late_ns_ = late_ns;
  late_count_ = count;
}

std::optional<std::int64_t> VirtualClock::wait_for_sleeper(std::chrono::milliseconds limit) {
  std::unique_lock lock(mutex_);
  const bool slept =
      changed_.wait_for(lock, limit, [&] { return sleeping_ && sleep_count_ != reported_sleep_; });
  if (!slept) return std::nullopt;
  reported_sleep_ = sleep_count_;
  return sleep_deadline_;
}

void VirtualClock::advance_to(std::int64_t t_ns) {
  std::lock_guard lock(mutex_);
  now_ = std::max(now_, t_ns);
  changed_.notify_all();
}

std::uint64_t VirtualClock::sleeps() const {
  std::lock_guard lock(mutex_);
  return sleep_count_;
}

}  // namespace gantry
