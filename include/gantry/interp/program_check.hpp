// A program checked, or interpreted into canonical moves, without a machine: what `gantry
// check`, `gantry moves`, the preview and the check before every run do (docs/architecture.md).
#pragma once

#include <atomic>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>

#include "gantry/canon/canon_move.hpp"            // MotionSink
#include "gantry/core/diagnostic_log.hpp"         // DiagnosticLog
#include "gantry/interp/interpreter_options.hpp"  // InterpreterOptions
#include "gantry/interp/modal_state.hpp"          // ModalState
#include "gantry/interp/operator_io.hpp"          // OperatorIO
#include "gantry/interp/persistent_store.hpp"     // PersistentStore
#include "gantry/interp/value.hpp"                // Value
#include "gantry/lang/script.hpp"                 // Script
#include "gantry/settings/settings.hpp"           // Settings

namespace gantry {

class CommandRecorder;  // gantry/commands/command_recorder.hpp

struct JobOptions {
  InterpreterOptions interpreter;
  std::map<std::string, std::string> inputs;  // --input answers, for the check as well
  bool yes = false;                           // --yes: PAUSE continues, MSGBOX defaults
  bool input_defaults = false;  // a preview: an unanswered INPUT takes its default, and goes on
  bool operator_present = true;               // a person answers at a terminal
  std::size_t check_budget = 10'000'000;      // statements a check may run (loops end there)
  std::size_t max_errors = 100;  // a check stops after this many errors (0: never); the rest
                                 // are counted by kind (DiagnosticLog::summary)
  double feed_override = 1;                   // 0.1 to 2: the speeds' factor (estimate too)
  // Where the run saves the values it leaves changed (V commands, MS, JS), as the keys that
  // differ from `profile`; empty (or no profile): nothing is saved.
  std::string values_path;
  const Settings* profile = nullptr;
  // Where the check starts (the machine controller's live state); null: a fresh machine.
  const ModalState* start_state = nullptr;
  const std::unordered_map<std::string, Value>* start_variables = nullptr;  // and its &variables
  // The console's command record, for a check of RP, RR and RS; null: an empty one.
  const CommandRecorder* record = nullptr;
  // The check's moves go here as well (a preview draws them); null: nowhere.
  MotionSink* check_moves = nullptr;
  // Set by the operator's stop from another thread: a check ends at its next statement.
  const std::atomic<bool>* stop = nullptr;
};

// Interprets without motion and returns every error and warning (up to options.max_errors
// errors, the rest summarised), in line order, and whether it stopped short: what `gantry
// check` says. `runtime_warnings`: also the warnings statements give as they run (PLAY,
// CLOSE), which a run reports itself.
// A cycle time comes from the check's moves planned (options.check_moves: a CycleTimer).
DiagnosticLog check_program(std::shared_ptr<const Script> script, const Settings& settings,
                            const PersistentStore& store, const JobOptions& options = {},
                            bool runtime_warnings = true);

// Interprets a checked program, handing each canonical move to `sink` (for `gantry moves`).
void interpret(std::shared_ptr<const Script> script, const Settings& settings, MotionSink& sink,
               OperatorIO& io, PersistentStore& store, const JobOptions& options = {});

}  // namespace gantry
