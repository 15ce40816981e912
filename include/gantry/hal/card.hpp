// The only interface to step hardware: a paced 32-bit output port fed with one word per tick,
// and a 32-bit input port (limits, home switches, probe, E-stop) sampled by the card.
#pragma once

#include <cstdint>
#include <span>

namespace gantry {

struct Settings;

// Why a card stopped playing by itself. After a fault the card plays nothing more until it
// is started again; ticks_played() says exactly how far it got.
enum class CardFault {
  None,
  Underrun,  // the queue ran dry while words were still due (the producer fell behind)
  EStop,     // the E-stop input went active
  Limit,     // a limit switch input went active
  Hardware,  // the card or its driver failed (lost device, DMA error)
};

const char* fault_name(CardFault f);

// The input port as sampled, and the tick of the sample.
struct InputSample {
  std::uint64_t tick = 0;
  std::uint32_t bits = 0;
};

class Card {
 public:
  virtual ~Card() = default;
  // Starts the pacer; words written afterwards play one per tick at `pacer_hz`.
  virtual void start(double pacer_hz) = 0;
  // Queues words for output, in order, one per tick. After a fault they are dropped.
  virtual void write(std::span<const std::uint32_t> words) = 0;
  // Returns when every queued word has played, or the card has faulted.
  virtual void drain() = 0;
  // Stops the pacer at once (stop, E-stop, end of job): queued words that have not played
  // are dropped, and the output word returns to `idle_word`.
  virtual void stop(std::uint32_t idle_word) = 0;
  // Words played since start(): the tick the card has reached.
  virtual std::uint64_t ticks_played() const = 0;
  // The input port's 32 bits as last sampled, raw (polarity is the profile's business).
  virtual std::uint32_t inputs() const = 0;
  // The same with its tick. Exact on the simulated card (virtual time); a card that samples
  // in its own thread may lag by its sampling interval.
  virtual InputSample sample_inputs() const { return {ticks_played(), inputs()}; }
  // Why the card stopped by itself; None while it plays or after a clean stop.
  virtual CardFault fault() const = 0;
  // The calibration changed (VU, VD's units) for the words written from now on. A real card
  // plays words and cares not; the simulator, which checks the machine's limits, follows.
  virtual void calibration_changed(const Settings&) {}
};

}  // namespace gantry
