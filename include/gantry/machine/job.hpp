// A part-file job: checks the whole file, then runs it through planner, steps and card.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "gantry/core/diagnostic_log.hpp"      // DiagnosticLog
#include "gantry/hal/card.hpp"                 // Card
#include "gantry/interp/operator_io.hpp"       // OperatorIO
#include "gantry/interp/persistent_store.hpp"  // PersistentStore
#include "gantry/interp/program_check.hpp"     // JobOptions, check_program
#include "gantry/lang/script.hpp"              // Script
#include "gantry/settings/settings.hpp"        // Settings
#include "gantry/step/card_lead.hpp"             // LeadStats

namespace gantry {

class Controller;
struct ControllerStatus;

// The operator's stop and E-stop for a run, from another thread (gantry run's Ctrl-C).
class RunControl {
 public:
  // A stop: the running file ramps down and ends, the position known; asked before the run
  // starts (while the file is checked, say), the run never starts and the check ends at its
  // next statement. Again: an E-stop. True for a stop, false for an E-stop.
  bool stop();
  // Set by the first stop: what a check polls (InterpreterOptions::stop_check).
  const std::atomic<bool>& stopped() const { return stopped_; }
  // What the operator asked for: 0 nothing, 1 a stop, 2 or more an E-stop.
  int stops() const {
    std::lock_guard lock(m_);
    return stops_;
  }
  // run_job: starts the run with `start` unless a stop came first (false), and keeps the
  // machine until detach(). A stop waits while the run starts, so it always reaches it.
  bool start(Controller& machine, const std::function<void()>& start);
  void detach();

 private:
  mutable std::mutex m_;
  Controller* machine_ = nullptr;
  int stops_ = 0;
  std::atomic<bool> stopped_{false};
};

struct JobResult {
  std::vector<Diagnostic> errors;     // empty when the job ran to its end
  std::string error_summary;          // the check's errors beyond its cap, in one line
  // Where and why the check stopped before the end of the file (an INPUT the operator
  // answered in the run, the statement budget): the run went on past it unchecked.
  std::optional<Diagnostic> check_stopped;
  std::vector<Diagnostic> warnings;   // from the check and the run
  std::size_t lines = 0;              // statements executed
  std::size_t moves = 0;              // canonical moves issued
  bool cut = false;  // the motion was cut short: lines and moves count what reached the card
  Steps6 commanded_steps{};           // steps the generator emitted
  Steps6 played_steps{};              // steps the card played: where the tool is
  CardFault fault = CardFault::None;  // why the card stopped by itself, if it did
  double planned_time_s = 0;          // the planner's sum of segment durations
  // A card that queues words: how the feeder kept up (Controller::Summary's).
  LeadStats lead;
  double lead_s = 0;
  std::uint64_t starved_releases = 0;
  bool feeder_realtime = false;
  double estimated_time_s = 0;        // the cycle time the check predicted before the run
  Settings settings;                  // as the run left them (the values it changed)
  bool ok() const { return errors.empty(); }
};

// Checks every statement first (collecting all errors) without writing a file or touching
// the persistent store; only a clean file reaches the card, so a bad file never moves the
// machine. Then runs it, asking `io` for operator answers.
// `control`: stops the check and the run from another thread (null: nothing does).
// `watch`: called with the controller's status about four times a second while the run
// plays (gantry run's progress line).
// `prepare`: called with the machine before it runs (the state kept across sessions).
JobResult run_job(std::shared_ptr<const Script> script, const Settings& settings, Card& card,
                  OperatorIO& io, PersistentStore& store, const JobOptions& options = {},
                  RunControl* control = nullptr,
                  const std::function<void(const ControllerStatus&)>& watch = {},
                  const std::function<void(Controller&)>& prepare = {});

}  // namespace gantry
