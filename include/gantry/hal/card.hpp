// The only interface to step hardware: a paced 32-bit output port fed with one word per tick.
#pragma once

#include <cstdint>
#include <span>

namespace gantry {

class Card {
 public:
  virtual ~Card() = default;
  // Starts the pacer; words written afterwards play one per tick at `pacer_hz`.
  virtual void start(double pacer_hz) = 0;
  // Queues words for output, in order, one per tick.
  virtual void write(std::span<const std::uint32_t> words) = 0;
  // Returns when every queued word has played.
  virtual void drain() = 0;
  virtual std::uint64_t ticks_played() const = 0;
};

}  // namespace gantry
