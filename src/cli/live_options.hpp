// The command-line flags of the options `gantry console` and `gantry gui` share; the live
// machine they open is assembled by the session (gantry/session/live_machine.hpp).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "gantry/session/live_machine.hpp"  // LiveMachineOptions, LiveMachine

namespace gantry {

// Adds them to `cmd` (`realtime_help`: what real time is needed for there).
void add_live_machine_options(CLI::App* cmd, session::LiveMachineOptions& a,
                              const std::string& realtime_help);

}  // namespace gantry
