// The queue from write() to the player thread: one producer, one consumer, no locks, no
// allocation after construction.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gantry {

class WordRing {
 public:
  // `capacity` must be a power of two (the map's validation sees to it).
  explicit WordRing(std::size_t capacity) : words_(capacity), mask_(capacity - 1) {}

  std::size_t capacity() const { return words_.size(); }
  std::size_t size() const {
    return static_cast<std::size_t>(head_.load(std::memory_order_acquire) -
                                    tail_.load(std::memory_order_acquire));
  }

  // Producer: queues as many of `words` as fit and returns how many. They become visible to
  // the consumer together, so a block written at once starts (or ends) playing whole.
  std::size_t push(std::span<const std::uint32_t> words) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    const std::uint64_t tail = tail_.load(std::memory_order_acquire);
    const std::size_t n =
        std::min(words.size(), capacity() - static_cast<std::size_t>(head - tail));
    for (std::size_t i = 0; i < n; ++i) words_[(head + i) & mask_] = words[i];
    head_.store(head + n, std::memory_order_release);
    return n;
  }

  // Consumer: words queued and not yet popped, read without popping.
  std::size_t available() const {
    return static_cast<std::size_t>(head_.load(std::memory_order_acquire) -
                                    tail_.load(std::memory_order_relaxed));
  }
  // Consumer: the i-th queued word; i < available().
  std::uint32_t peek(std::size_t i) const {
    return words_[(tail_.load(std::memory_order_relaxed) + i) & mask_];
  }
  // Consumer: drops the first `n` queued words; n <= available().
  void pop(std::size_t n) {
    tail_.store(tail_.load(std::memory_order_relaxed) + n, std::memory_order_release);
  }
  // Drops every queued word; only while no consumer runs (the player thread has stopped).
  void clear() { tail_.store(head_.load(std::memory_order_acquire), std::memory_order_release); }

 private:
  std::vector<std::uint32_t> words_;
  const std::size_t mask_;
  // Positions count words ever pushed/popped; they never wrap in practice (2^64 words).
  alignas(64) std::atomic<std::uint64_t> head_{0};
  alignas(64) std::atomic<std::uint64_t> tail_{0};
};

}  // namespace gantry
