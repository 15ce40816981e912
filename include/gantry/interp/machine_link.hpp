// The live machine's answers to the interpreter: where the tool is, its inputs, the keypad.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "gantry/canon/canon_move.hpp"  // InputTrigger
#include "gantry/core/vec6.hpp"         // Vec6
#include "gantry/core/diagnostic.hpp"   // SourceLoc

namespace gantry {

// What the live machine reports once the motion has played out (MachineLink::sync).
struct MotionReport {
  Vec6 machine = Vec6::Zero();  // where the tool is, machine frame, from the pulses played
  // A watched edge cut the motion: which, and where the tool was at that instant (the
  // motion after it was dropped; the tool came to rest at `machine`).
  std::optional<InputTrigger> fired;
  Vec6 latched = Vec6::Zero();
  // The machine's clock: seconds of pulses (and dwells) played since the run began, on the
  // card's pacer (virtual time on the simulated card, %(130)).
  double elapsed_s = 0;
};

// The calls that carry the machine's answers back up to the interpreter, beside the moves
// that go down its MotionSink. Only the live machine has one (Controller); a check, a
// preview or a list of moves runs without (the Interpreter then flushes where it would sync,
// reports nothing, and takes every probe to reach its target).
class MachineLink {
 public:
  virtual ~MachineLink() = default;
  // Plays out every move sent so far and reports where the tool is and whether a watched
  // input cut the motion.
  virtual MotionReport sync() = 0;
  // Replaces the edges watched from the next move on (the machine is at rest: after sync),
  // for ON INPUT handlers, a probe or homing (what the machine's state shows).
  enum class Watching { Handlers, Probe, Home };
  virtual void watch_inputs(std::span<const InputTrigger>, Watching) = 0;
  // The input switches 1-12 now: closed (true) or open.
  virtual std::array<bool, 12> input_switches() const = 0;
  // SK: plays out the moves sent so far, then the operator jogs the machine with the keypad
  // until they close it; reports where the tool is then.
  virtual MotionReport keypad(const SourceLoc&) = 0;
  // The axes (bit i: axis i) that must be homed before they move again (homing.require: an
  // E-stop or a card fault stopped a motion), and the news that one was (C3, G28).
  virtual std::uint32_t axes_to_home() const { return 0; }
  virtual void homed(int /*axis*/) {}
};

}  // namespace gantry
