// The lock-free queue of output words from a card's write() to its real-time thread: one
// producer, one consumer, no locks, no allocation after construction (pci7200, gpiod).
#pragma once

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace gantry {

// Memory is allocated once, in the constructor: neither side allocates or takes a lock, so
// the real-time consumer never waits on the producer. The consumer either copies words out
// (pop) or reads them in place and then drops them (available, peek, drop).
class WordRing {
 public:
  // Capacity is rounded up to a power of two (at least 2) so that positions map to slots
  // with a mask.
  explicit WordRing(std::size_t capacity_words)
      : slots_(std::bit_ceil(std::max<std::size_t>(capacity_words, 2))), mask_(slots_.size() - 1) {}

  std::size_t capacity() const { return slots_.size(); }
  // Any thread: words queued and not yet taken (a snapshot).
  std::size_t size() const {
    return static_cast<std::size_t>(head_.load(std::memory_order_acquire) -
                                    tail_.load(std::memory_order_acquire));
  }

  // Producer: queues as many of `words` as fit and returns how many. They become visible to
  // the consumer together, so a block written at once starts (or ends) playing whole.
  std::size_t push(std::span<const std::uint32_t> words) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    const std::uint64_t tail = tail_.load(std::memory_order_acquire);
    const std::size_t n = std::min<std::size_t>(words.size(), capacity() - (head - tail));
    copy_in(head, words.first(n));
    head_.store(head + n, std::memory_order_release);
    return n;
  }

  // Consumer: words published and not yet taken.
  std::size_t available() const {
    return static_cast<std::size_t>(head_.load(std::memory_order_acquire) -
                                    tail_.load(std::memory_order_relaxed));
  }
  // Consumer: the i-th queued word, read without taking it; i < available().
  std::uint32_t peek(std::size_t i) const {
    return slots_[(tail_.load(std::memory_order_relaxed) + i) & mask_];
  }
  // Consumer: drops the first `n` queued words; n <= available().
  void drop(std::size_t n) {
    tail_.store(tail_.load(std::memory_order_relaxed) + n, std::memory_order_release);
  }
  // Consumer: fills `out` from the front; returns how many words it took.
  std::size_t pop(std::span<std::uint32_t> out) {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    const std::uint64_t head = head_.load(std::memory_order_acquire);
    const std::size_t n = std::min<std::size_t>(out.size(), head - tail);
    copy_out(tail, out.first(n));
    tail_.store(tail + n, std::memory_order_release);
    return n;
  }
  // Consumer, or any thread while no consumer runs: drops every word published so far.
  void clear() { tail_.store(head_.load(std::memory_order_acquire), std::memory_order_release); }

 private:
  void copy_in(std::uint64_t pos, std::span<const std::uint32_t> words) {
    const std::size_t at = pos & mask_;
    const std::size_t first = std::min(words.size(), capacity() - at);
    if (first > 0) std::memcpy(&slots_[at], words.data(), first * sizeof(std::uint32_t));
    if (words.size() > first)
      std::memcpy(slots_.data(), words.data() + first, (words.size() - first) * 4);
  }
  void copy_out(std::uint64_t pos, std::span<std::uint32_t> out) const {
    const std::size_t at = pos & mask_;
    const std::size_t first = std::min(out.size(), capacity() - at);
    if (first > 0) std::memcpy(out.data(), &slots_[at], first * sizeof(std::uint32_t));
    if (out.size() > first)
      std::memcpy(out.data() + first, slots_.data(), (out.size() - first) * 4);
  }

  std::vector<std::uint32_t> slots_;
  const std::size_t mask_;
  // Positions count words ever pushed/taken; they never wrap in practice (2^64 words).
  alignas(64) std::atomic<std::uint64_t> head_{0};  // next position the producer writes
  alignas(64) std::atomic<std::uint64_t> tail_{0};  // next position the consumer reads
};

}  // namespace gantry
