// `gantry console`: the live machine at a terminal. A prompt that runs each line on the
// controller, the position readout, the stop keys and the keypad (docs/console.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "gantry/session/live_machine.hpp"  // LiveMachineOptions

namespace gantry {

struct ConsoleArgs : session::LiveMachineOptions {
  bool yes = false;
  std::vector<std::string> inputs;  // NAME=VALUE
  // Keypad (KeyTaps): a key repeating within `release_ms` is held (a continuous jog, released
  // when the repeats stop); a press is one step; `repeat_delay_ms` is the terminal's delay
  // before it repeats a held key (the same key later than that is a new press).
  int release_ms = 150;
  int repeat_delay_ms = 600;
};

// Adds the `console` subcommand, its options filling `args`.
CLI::App* add_console_command(CLI::App& app, ConsoleArgs& args);

// Runs the console until quit (interactive, at a terminal) or until standard input ends.
// The exit status: 0, or 1 when a line failed (non-interactive) or the machine could not
// be opened.
int run_console(const ConsoleArgs& args);

}  // namespace gantry
