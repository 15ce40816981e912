// The live machine `gantry console` and `gantry gui` both drive, assembled from their common
// options: the card, the interpreter's options, the values the runs leave in force, the
// state kept across sessions. The command line's flags that fill the options are in src/cli.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gantry/hal/card.hpp"                    // Card
#include "gantry/interp/interpreter_options.hpp"  // InterpreterOptions
#include "gantry/interp/operator_io.hpp"          // OperatorIO
#include "gantry/interp/persistent_store.hpp"     // PersistentStore
#include "gantry/machine/controller.hpp"          // Controller
#include "gantry/session/machine_memory.hpp"      // MachineMemory
#include "gantry/session/machine_profile.hpp"     // MachineProfile
#include "gantry/session/gamepad_service.hpp"     // GamepadService
#include "gantry/session/key_bindings.hpp"        // KeyBindings
#include "gantry/session/pendant_service.hpp"     // PendantService
#include "gantry/session/run_log.hpp"             // RunLogger

namespace gantry::session {

// The options both live front ends take.
struct LiveMachineOptions {
  std::string card;     // empty: the profile's card.type
  std::string profile;  // empty: the built-in default
  std::string values, persistent, macros;
  bool realtime = false;
  bool allow_shell = false;
  std::vector<std::string> allow_paths;  // --allow-path
  std::string tool_table;                // --tool-table
  std::vector<std::string> subroutines;  // --subroutines, before the profile's
};

// The card the options choose (else the profile's card.type), in real time if asked; `type`
// receives the type. Null, with the reason printed on stderr, when it cannot be opened.
std::unique_ptr<Card> open_live_card(const LiveMachineOptions& a, const Settings& settings,
                                     std::string* type);

// The values a live machine's runs leave in force (units, speeds, calibration), for the
// front ends' readouts, saved to the operator's values file whenever they change (as
// `gantry run` saves them).
class ValuesKeeper {
 public:
  ValuesKeeper(const MachineProfile& p, OperatorIO& io) : profile_(p), io_(io), now_(p.settings) {}
  // Job thread: a run ended with `s` in force.
  void ran(const Settings& s);
  Settings settings() const;

 private:
  const MachineProfile& profile_;
  OperatorIO& io_;  // says when the file cannot be written
  mutable std::mutex m_;
  Settings now_;
};

// The interpreter's options on the live machine: the profile and its values file (`values`
// keeps what each run leaves), the macros' folder, whether SHELL may start programs, and
// SW's warning when the card plays in real time.
InterpreterOptions live_interpreter_options(const MachineProfile& p, ValuesKeeper& values,
                                            const LiveMachineOptions& a, bool real_time);

// The live machine both front ends drive, built in the order it needs: the persistent
// store, the values kept, the card, then the controller (last: it starts the threads, and it
// is destroyed first).
struct LiveMachine {
  // Null, with the card's reason printed, when the card cannot be opened.
  static std::unique_ptr<LiveMachine> open(const LiveMachineOptions& a, const MachineProfile& p,
                                           OperatorIO& io);

  PersistentStore store;
  ValuesKeeper values;
  std::string card_type;  // "sim", "pci7200", ...
  std::unique_ptr<Card> card;
  bool real_time = false;
  // The state kept across sessions and the part-file log (docs/machine_state.md); `restored`:
  // what load said (the operator is told it at start).
  std::unique_ptr<MachineMemory> memory;
  std::unique_ptr<RunLogger> part_log;
  std::string restored;
  std::unique_ptr<Controller> controller;
  // The pendants (the XHC USB pendant, whenever plugged in): both front ends get them.
  std::unique_ptr<PendantService> pendant;
  std::unique_ptr<GamepadService> gamepad;  // the profile's [pendant] gamepad, into `pendant`
  KeyBindings keys;  // the profile's [pendant] keys: the front ends' keys into `pendant`

  ~LiveMachine();  // the pendants, the controller, then the state saved at exit

  bool sim() const { return card_type == "sim"; }
};

}  // namespace gantry::session
