// The only interface to step hardware: a paced 32-bit output port fed with one word per tick,
// and a 32-bit input port (limits, home switches, probe, E-stop) sampled by the card.
#pragma once

#include <bit>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "gantry/core/axes.hpp"        // Steps6
#include "gantry/hal/debounce.hpp"     // Debounce
#include "gantry/hal/input_roles.hpp"  // InputTrip

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

// Input edges to watch for while the card plays (ON INPUT handlers, probes, homing): bit b of
// `mask` fires when it changes to its level in `levels`. An edge, not a level: a bit already at
// its level when armed must first leave it. A bit also in `stop` stops the card at the word
// where it fired (an instant stop: the words after it are dropped, and no fault is raised).
// `debounce`: the bit fires once it has read its level in that many of the card's input
// samples in a row (homing.debounce, WinCNC's g28_lim_cnt); a shorter visit is forgotten.
struct InputWatch {
  std::uint32_t mask = 0, levels = 0, stop = 0;
  int debounce = 1;
};

// Where a watch fired: the words before `tick` had played when the edge was seen (the tool
// was where they left it), the bit, and all 32 bits.
struct InputEdge {
  std::uint64_t tick = 0;
  int bit = 0;
  std::uint32_t bits = 0;
};

// The edge logic of InputWatch over successive samples; fires once until armed again. With a
// debounce, the edge it gives is the first sample of the run that reached the count (where
// the switch closed), whatever the count: the tool's place there does not depend on it.
class EdgeDetector {
 public:
  static constexpr std::uint64_t kNone = Debounce::kNone;
  void arm(const InputWatch& w, std::uint32_t bits_now) {
    w_ = w;
    armed_ = (bits_now ^ w.levels) & w.mask;  // bits away from their level may fire
    count_ = Debounce(w.debounce);
    fired_ = false;
  }
  // The edge that fired at this sample (taken at `tick`, standing for `repeat` samples
  // alike), if one did.
  std::optional<InputEdge> sample(std::uint32_t bits, std::uint64_t tick = 0,
                                  std::uint64_t repeat = 1) {
    if (fired_ || w_.mask == 0) return std::nullopt;
    const std::uint32_t away = (bits ^ w_.levels) & w_.mask;
    const std::uint32_t at = armed_ & ~away & w_.mask;  // armed bits at their level
    const std::uint32_t fresh = at & ~count_.pending();
    if (fresh != 0 && (count_.pending() & at) == 0) first_ = {tick, 0, bits};  // a new count
    armed_ |= away;
    if (!count_.sample(at, fresh, repeat)) return std::nullopt;
    fired_ = true;
    first_.bit = std::countr_zero(count_.pending());
    return first_;
  }
  // More samples alike that make it fire (kNone: none would).
  std::uint64_t samples_left() const { return fired_ ? Debounce::kNone : count_.samples_left(); }
  const InputWatch& watch() const { return w_; }

 private:
  InputWatch w_;
  std::uint32_t armed_ = 0;
  Debounce count_;
  InputEdge first_;
  bool fired_ = false;
};

// A cushioned stop the card played by itself (limits.cushion_steps after a limit switch,
// limits.esc_steps after the operator's E-stop; docs/hardware.md, "Cushioned stop"): the
// words from tick `from` on were its own deceleration, not the ones written, and each driver
// channel made `steps` in them (signed). ticks_played() counts them.
struct CushionPlayed {
  std::uint64_t from = 0;
  Steps6 steps{};
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
  // The words written so far end at rest (a hold, new values, the end of the motion): the
  // queue may run dry after them without an underrun, and the next word starts a new stretch
  // of output. Never blocks. drain() implies it.
  virtual void end_stream() {}
  // Stops the pacer at once (stop, E-stop, end of job): queued words that have not played
  // are dropped, and the output word returns to `idle_word`.
  virtual void stop(std::uint32_t idle_word) = 0;
  // Stops as stop() does, after a cushion of `steps` (limits.esc_steps): every channel still
  // moving decelerates to rest within that many steps (cushion_words). A card that cannot
  // stops at once.
  virtual void stop_cushioned(std::uint32_t idle_word, int /*steps*/) { stop(idle_word); }
  // The cushion played since start(), if one was (a limit's or stop_cushioned's).
  virtual std::optional<CushionPlayed> cushion_played() const { return std::nullopt; }
  // Words played since start(): the tick the card has reached.
  virtual std::uint64_t ticks_played() const = 0;
  // The input port's 32 bits as last sampled, raw (polarity is the profile's business).
  virtual std::uint32_t inputs() const = 0;
  // The same with its tick. Exact on the simulated card (virtual time); a card that samples
  // in its own thread may lag by its sampling interval.
  virtual InputSample sample_inputs() const { return {ticks_played(), inputs()}; }
  // The bounded lead (docs/controller.md): whether words written wait in a queue and play in
  // real time, one per tick (a real card; the simulator with --realtime). Then the step
  // generator keeps at most the profile's card.lead_ms of words over clock_tick(), so that a
  // hold begins within that lead. false: words play as they are written (the simulator in
  // virtual time), and the generator writes as far ahead as it goes.
  virtual bool queues_words() const { return false; }
  // The most the lead grows to when the feeder is late (or card.lead_ms, when longer): a
  // card's queue must hold at least this (docs/hardware.md, "The lead adapts").
  static constexpr double kMostLeadS = 0.2;
  // The tick the card's clock has reached: ticks_played(), except on a card that plays (and
  // counts) a word when it is written but times it by the wall clock (the simulator in real
  // time), where it is the tick now due.
  virtual std::uint64_t clock_tick() const { return ticks_played(); }
  // The words a stream needs queued before it starts playing (the card's start threshold, 0:
  // the first word starts it): the lead is never below it (plus one block).
  virtual std::uint64_t start_words() const { return 0; }
  // Why the card stopped by itself; None while it plays or after a clean stop.
  virtual CardFault fault() const = 0;
  // More about the fault where the card knows it ("the producer was 12.3 ms late"), or "".
  virtual std::string fault_detail() const { return {}; }
  // The calibration changed (VU, VD's units) for the words written from now on. A real card
  // plays words and cares not; the simulator, which checks the machine's limits, follows.
  virtual void calibration_changed(const Settings&) {}
  // The inputs on which the card stops by itself, as a real card's driver latches them: the
  // E-stop (CardFault::EStop) and limit switches (CardFault::Limit). Set from the profile
  // and VN (input_roles) at rest, and without the bits a homing or probing move runs onto.
  // A card without inputs ignores them.
  virtual void set_trips(const InputTrip& /*estop*/, const InputTrip& /*limits*/) {}
  // Arms (replaces) the input watch; an empty mask disarms it.
  virtual void watch(const InputWatch& w) {
    watcher_.arm(w, inputs());
    fired_.reset();
  }
  // The edge the watch fired on, once it has. This default compares the inputs each time it
  // is asked (the feeder asks after every block): a card that samples its inputs itself
  // overrides it with the exact tick, and stops on `stop` bits in hardware.
  virtual std::optional<InputEdge> watch_fired() {
    if (!fired_) {
      const InputSample s = sample_inputs();
      fired_ = watcher_.sample(s.bits, s.tick);
    }
    return fired_;
  }

 private:
  EdgeDetector watcher_;
  std::optional<InputEdge> fired_;
};

}  // namespace gantry
