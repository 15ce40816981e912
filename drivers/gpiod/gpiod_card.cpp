// The GPIO card's threads: the producer side (write, drain, stop) and the player thread.
#include "gpiod/gpiod_card.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace gantry {
namespace {

using namespace std::chrono_literals;

// Idle, the thread looks for a new stream (and samples the inputs) this often.
constexpr auto kIdlePoll = 500us;
// drain() looks for the end of the stream this often.
constexpr auto kDrainPoll = 250us;
// A stream's first tick is due this long after the thread sees it, so the first deadline is
// not already past when the thread gets to sleep on it.
constexpr std::int64_t kStreamLeadNs = 200'000;

const GpioMap& checked(const GpioMap& map) {
  if (auto problems = validate_gpio_map(map); !problems.empty())
    throw std::invalid_argument(join_lines(problems));
  return map;
}

}  // namespace

GpiodCard::GpiodCard(const GpioMap& map, std::unique_ptr<GpioLines> lines,
                     std::unique_ptr<TickClock> clock)
    : map_(checked(map)),
      lines_(std::move(lines)),
      clock_(std::move(clock)),
      ring_(map_.queue_words),
      player_(map_, *lines_, ring_),
      pacer_hz_(map_.pacer_hz) {
  player_.sample_inputs();
}

GpiodCard::~GpiodCard() {
  halt_player();
}

void GpiodCard::start(double pacer_hz) {
  halt_player();
  {
    std::lock_guard lock(producer_mutex_);
    ring_.clear();
    accepting_ = false;
  }
  {
    std::lock_guard lock(status_mutex_);
    refusal_.clear();
  }
  if (auto problem = pacer_rate_problem(pacer_hz)) {
    player_.reset(map_.pacer_hz);
    player_.fail(CardFault::Hardware);
    std::lock_guard lock(status_mutex_);
    refusal_ = *problem;
    return;
  }
  if (map_.realtime && !memory_locked_) {
    std::lock_guard lock(status_mutex_);
    memory_locked_ = lock_memory(&memory_note_);
  }
  pacer_hz_ = pacer_hz;
  player_.reset(pacer_hz);
  stop_requested_ = false;
  drain_requested_ = false;
  pacing_ = false;
  clock_->clear_interrupt();
  {
    std::lock_guard lock(producer_mutex_);
    accepting_ = true;
    written_ = 0;
  }
  stream_end_.store(0, std::memory_order_release);
  running_ = true;
  thread_ = std::thread([this] { run(); });
}

void GpiodCard::write(std::span<const std::uint32_t> words) {
  // While the queue is full, wait about an eighth of the time it takes to play.
  const auto queue_time = std::chrono::duration<double>(ring_.capacity() / pacer_hz_);
  const auto wait =
      std::clamp(std::chrono::duration_cast<std::chrono::microseconds>(queue_time / 8), 100us,
                 std::chrono::microseconds(10ms));
  while (!words.empty()) {
    std::size_t pushed = 0;
    {
      std::lock_guard lock(producer_mutex_);
      if (!accepting_ || stop_requested_ || player_.fault() != CardFault::None) return;
      pushed = ring_.push(words);
      written_ += pushed;
    }
    words = words.subspan(pushed);
    if (!words.empty()) std::this_thread::sleep_for(wait);
  }
}

void GpiodCard::drain() {
  if (!running_) return;
  drain_requested_ = true;
  while (running_ && !stop_requested_ && player_.fault() == CardFault::None &&
         (ring_.size() > 0 || pacing_))
    std::this_thread::sleep_for(kDrainPoll);
  drain_requested_ = false;
}

void GpiodCard::end_stream() {
  std::lock_guard lock(producer_mutex_);
  stream_end_.store(written_, std::memory_order_release);
}

void GpiodCard::stop(std::uint32_t idle_word) {
  halt_player();
  {
    std::lock_guard lock(producer_mutex_);
    ring_.clear();
    accepting_ = false;
  }
  player_.output(idle_word);  // the thread has ended: the lines are this thread's now
}

void GpiodCard::stop_cushioned(std::uint32_t idle_word, int steps) {
  if (steps > 0 && running_ && pacing_ && player_.fault() == CardFault::None) {
    player_.request_cushion(steps);
    // The player ends the stream once the cushion has played (or at once: nothing moved).
    while (running_ && pacing_ && !stop_requested_ && player_.fault() == CardFault::None)
      std::this_thread::sleep_for(kDrainPoll);
  }
  stop(idle_word);
}

void GpiodCard::halt_player() {
  stop_requested_ = true;
  clock_->interrupt();
  if (thread_.joinable()) thread_.join();
  running_ = false;
  pacing_ = false;
}

void GpiodCard::run() {
  if (map_.realtime) {
    RealtimeResult got;
    make_thread_realtime(map_.rt_priority, map_.cpu, got);
    std::lock_guard lock(status_mutex_);
    got.memory_locked = memory_locked_;
    if (!memory_note_.empty())
      got.notes = memory_note_ + (got.notes.empty() ? "" : "; ") + got.notes;
    realtime_ = got;
  }
  while (!stop_requested_) {
    const std::size_t queued = ring_.available();
    const bool ended = stream_end_.load(std::memory_order_acquire) > player_.ticks_played();
    if (queued >= map_.start_words || (queued > 0 && (drain_requested_ || ended))) {
      if (!play_stream()) return;
      continue;
    }
    // Between streams the inputs stay fresh for inputs(); they fault the card only in one.
    if (!player_.sample_inputs()) return;
    std::this_thread::sleep_for(kIdlePoll);
  }
}

bool GpiodCard::play_stream() {
  pacing_ = true;  // before the first word leaves the queue, so drain() keeps waiting
  player_.begin_stream();
  const std::uint64_t first_tick = player_.ticks_played();
  const PacerSchedule schedule(pacer_hz_, clock_->now_ns() + kStreamLeadNs);
  for (;;) {
    const std::uint64_t tick = player_.next_event_tick();
    const std::int64_t due = schedule.deadline(tick - first_tick);
    clock_->sleep_until_ns(due);
    if (stop_requested_) {
      player_.leave_stream();  // a cushion cut short counts what it played
      break;
    }
    const std::int64_t late_ns = clock_->now_ns() - due;
    // Dry at the end of a stream that ended at rest (end_stream) is no underrun (issue 26: a
    // hold on this card faulted as soon as its queue ran dry at rest).
    const bool at_end = tick == stream_end_.load(std::memory_order_acquire);
    const auto outcome = player_.play_through(tick, late_ns, drain_requested_ || at_end);
    if (outcome == TickPlayer::Outcome::Played) continue;
    pacing_ = false;
    return outcome == TickPlayer::Outcome::StreamEnded;
  }
  pacing_ = false;
  return false;
}

std::string GpiodCard::error() const {
  {
    std::lock_guard lock(status_mutex_);
    if (!refusal_.empty()) return refusal_;
  }
  if (fault() == CardFault::Hardware && player_.failed_errno() != 0)
    return fmt::format("gpiod: GPIO {} failed at tick {}: {}", player_.failed_operation(),
                       ticks_played(), std::strerror(player_.failed_errno()));
  return {};
}

RealtimeResult GpiodCard::realtime() const {
  std::lock_guard lock(status_mutex_);
  return realtime_;
}

}  // namespace gantry
