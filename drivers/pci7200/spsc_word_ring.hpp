// A fixed-capacity single-producer/single-consumer ring of output words between write() and
// the feeder thread. Memory is allocated once, in the constructor: neither side allocates or
// takes a lock, so the real-time consumer never waits on the producer.
#pragma once

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace gantry::pci7200 {

class SpscWordRing {
 public:
  // Capacity is rounded up to a power of two so that positions map to slots with a mask.
  explicit SpscWordRing(std::size_t capacity_words)
      : slots_(std::bit_ceil(std::max<std::size_t>(capacity_words, 2))), mask_(slots_.size() - 1) {}

  std::size_t capacity() const { return slots_.size(); }

  // Producer: copies as many words as fit; returns how many.
  std::size_t push(std::span<const std::uint32_t> words) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    const std::uint64_t tail = tail_.load(std::memory_order_acquire);
    const std::size_t n = std::min<std::size_t>(words.size(), capacity() - (head - tail));
    copy_in(head, words.first(n));
    head_.store(head + n, std::memory_order_release);
    return n;
  }

  // Consumer: words published and not yet taken.
  std::size_t readable() const {
    return static_cast<std::size_t>(head_.load(std::memory_order_acquire) -
                                    tail_.load(std::memory_order_relaxed));
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

  // Consumer: drops every word published so far.
  void discard_readable() {
    tail_.store(head_.load(std::memory_order_acquire), std::memory_order_release);
  }

 private:
  void copy_in(std::uint64_t pos, std::span<const std::uint32_t> words) {
    const std::size_t at = pos & mask_;
    const std::size_t first = std::min(words.size(), capacity() - at);
    if (first > 0) std::memcpy(&slots_[at], words.data(), first * sizeof(std::uint32_t));
    if (words.size() > first)
      std::memcpy(slots_.data(), words.data() + first, (words.size() - first) * 4);
  }
  void copy_out(std::uint64_t pos, std::span<std::uint32_t> out) {
    const std::size_t at = pos & mask_;
    const std::size_t first = std::min(out.size(), capacity() - at);
    if (first > 0) std::memcpy(out.data(), &slots_[at], first * sizeof(std::uint32_t));
    if (out.size() > first)
      std::memcpy(out.data() + first, slots_.data(), (out.size() - first) * 4);
  }

  std::vector<std::uint32_t> slots_;
  std::size_t mask_;
  alignas(64) std::atomic<std::uint64_t> head_{0};  // next position the producer writes
  alignas(64) std::atomic<std::uint64_t> tail_{0};  // next position the consumer reads
};

}  // namespace gantry::pci7200
