// `gantry gui [FILE]`: the console window on the live machine (docs/console.md, "Console
// window"). Compiled into gantry when the window is built (GANTRY_GUI).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "gantry/session/live_machine.hpp"  // LiveMachineOptions

namespace gantry {

struct GuiArgs : session::LiveMachineOptions {
  std::string file;
  std::string script;  // scripted actions; the window exits at their end
  bool bench = false;
  std::string size = "1280x800";  // --size: WIDTH (16:10) or WIDTHxHEIGHT
};

CLI::App* add_gui_command(CLI::App& app, GuiArgs& args);
int run_gui_command(const GuiArgs& args);

}  // namespace gantry
