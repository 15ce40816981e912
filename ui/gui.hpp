// The console window (`gantry gui`): GLFW + Dear ImGui + OpenGL 3 over the machine
// controller. It draws state and sends requests; it never computes motion.
#pragma once

#include <functional>
#include <string>

#include "gantry/machine/controller.hpp"   // Controller
#include "gantry/session/key_bindings.hpp"    // KeyBindings
#include "gantry/session/machine_memory.hpp"  // MachineMemory
#include "gantry/session/pendant_input.hpp"   // PendantInput
#include "gantry/session/operator_io.hpp"  // OperatorMailbox
#include "gantry/settings/settings.hpp"    // Settings

namespace gantry::ui {

struct GuiOptions {
  std::string file;      // previewed (and run by Start) from the start; may be empty
  std::string script;    // scripted actions (test_script.hpp); the window exits at their end
  bool bench = false;    // load `file`, time the first frames, print the figures and exit
  std::string card;      // what the readout says the card is: "sim (virtual time)", "pci7200"
  bool realtime = true;  // the card plays in wall-clock time (continuous jogs need it)
  int width = 1280, height = 800;
  std::string macros;  // --macros: the macro folder (else the operator's, user_macro_folder)
  std::string recent_files;  // where the part files opened last are kept (empty: not kept)
};

// What the window drives. `settings` returns the values in force now (units, calibration,
// the keypad step): they change when a line runs a V command.
struct Machine {
  Controller& controller;
  session::OperatorMailbox& io;  // PRINT to the log; PAUSE, INPUT, MSGBOX as dialogs
  std::function<Settings()> settings;
  // The state kept across sessions (its unconfirmed mark and the operator's confirmation);
  // null when nothing is kept.
  session::MachineMemory* memory = nullptr;
  // The profile's [pendant] keys and the pendant input they go to (null: none bound).
  const session::KeyBindings* keys = nullptr;
  session::PendantInput* pendant = nullptr;
};

// Opens the window and runs it until it is closed (or the script ends). Returns the exit
// status: 0, 1 when the window cannot open, 2 when a script action fails.
int run_gui(const GuiOptions& options, Machine& machine);

}  // namespace gantry::ui
