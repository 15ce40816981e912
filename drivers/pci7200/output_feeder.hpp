// Moves words from the ring into the card: by bus-master DMA from two halves of the DMA
// buffer (the bridge reads one while the other is filled), or, with no DMA, by programmed I/O
// into the bridge's FIFO. Knows exactly how many words have entered the card.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "pci7200/pci7200_bus.hpp"  // Pci7200Bus, DmaBuffer

namespace gantry::pci7200 {

class WordSource {
 public:
  virtual ~WordSource() = default;
  // Fills `out` from the front with the next words of the stream; returns how many.
  virtual std::size_t take(std::span<std::uint32_t> out) = 0;
};

// The card as a pass found it, before the pass started anything new.
struct FeederSnapshot {
  bool fifo_empty = false;
  bool in_flight = false;     // the bridge is still reading a transfer into the FIFO
  bool words_staged = false;  // words in the DMA buffer not yet handed to the bridge
  bool dma_error = false;     // the bridge reported a master or target abort
  bool device_lost = false;   // status read as all ones, or the bus failed
};

class OutputFeeder {
 public:
  explicit OutputFeeder(Pci7200Bus& bus);

  bool uses_dma() const { return half_words_ > 0; }
  std::size_t half_words() const { return half_words_; }

  // Transfers off, FIFO emptied, nothing staged, counts back to zero.
  void reset();
  // Books a finished transfer and reads the FIFO state.
  FeederSnapshot poll();
  // Reloads the DMA first (that is the deadline), then stages more words.
  void feed(WordSource& source);
  // No further word enters the FIFO; staged words are dropped.
  void stop_transfers();
  bool fifo_empty();

  // Words that have entered the card's FIFO. Read before the FIFO state, so against an empty
  // FIFO it is exactly the words played.
  std::uint64_t words_into_card() const { return completed_ + in_flight_fetched_; }

 private:
  void start_staged_transfer();
  void stage(WordSource& source);
  void write_fifo_directly(WordSource& source);

  Pci7200Bus& bus_;
  DmaBuffer dma_;
  std::size_t half_words_ = 0;
  std::size_t staged_[2] = {0, 0};  // words in each half not yet handed to the bridge
  int in_flight_ = -1;              // the half the bridge is reading, or -1
  std::size_t in_flight_words_ = 0;
  int stage_half_ = 0;  // the half being filled; never the one in flight
  bool read_enabled_ = false;
  std::uint64_t completed_ = 0;  // words of finished transfers, or of FIFO writes
  std::uint64_t in_flight_fetched_ = 0;
};

}  // namespace gantry::pci7200
