// A bounded single-producer single-consumer queue: no lock, no allocation after construction.
#pragma once

#include <atomic>
#include <cstddef>
#include <utility>
#include <vector>

namespace gantry {

// One thread pushes, one pops. The slots are allocated once; push and pop move an item in
// or out and publish the new end with one release store. Waiting uses C++20 atomic waits
// (a futex on Linux), so a full or empty queue costs no CPU.
template <class T>
class SpscQueue {
 public:
  explicit SpscQueue(std::size_t capacity) : slots_(capacity) {}

  std::size_t capacity() const { return slots_.size(); }
  bool empty() const {
    return head_.load(std::memory_order_acquire) == tail_.load(std::memory_order_acquire);
  }

  bool try_push(T&& item) {
    const std::size_t t = tail_.load(std::memory_order_relaxed);
    if (t - head_.load(std::memory_order_acquire) == slots_.size()) return false;
    slots_[t % slots_.size()] = std::move(item);
    tail_.store(t + 1, std::memory_order_release);
    tail_.notify_one();
    return true;
  }
  bool try_pop(T& out) {
    const std::size_t h = head_.load(std::memory_order_relaxed);
    if (h == tail_.load(std::memory_order_acquire)) return false;
    out = std::move(slots_[h % slots_.size()]);
    head_.store(h + 1, std::memory_order_release);
    head_.notify_one();
    return true;
  }
  // Producer: blocks while full, until the consumer pops.
  void wait_for_room() const {
    const std::size_t h = head_.load(std::memory_order_acquire);
    if (tail_.load(std::memory_order_relaxed) - h < slots_.size()) return;
    head_.wait(h, std::memory_order_acquire);
  }

 private:
  std::vector<T> slots_;
  alignas(64) std::atomic<std::size_t> head_{0};  // next to pop
  alignas(64) std::atomic<std::size_t> tail_{0};  // next to push
};

}  // namespace gantry
