// `gantry gui`: the profile, the card and the controller, as `gantry console` makes them,
// handed to the window.
#include "gui_command.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "gantry/machine/controller.hpp"   // Controller
#include "gantry/session/operator_io.hpp"  // OperatorMailbox
#include "gantry/session/recent_files.hpp"  // recent_files_path
#include "gui.hpp"                         // run_gui (ui/)
#include "live_options.hpp"                // add_live_machine_options, LiveMachine
#include "window_size.hpp"                 // parse_window_size (ui/)
#include "machine_profile.hpp"             // load_machine_profile

namespace gantry {

CLI::App* add_gui_command(CLI::App& app, GuiArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "gui", "The console window: command line, readout, keypad, 3D preview (docs/console.md)");
  cmd->add_option("file", a.file, "Part file to preview and run");
  add_live_machine_options(
      cmd, a, "Play the simulated card in real time (continuous jogs and pausing a move need it)");
  cmd->add_option("--script", a.script,
                  "Play scripted actions (type, key, click, wait, screenshot, dump) and exit");
  cmd->add_flag("--bench", a.bench,
                "Load FILE, print the time to the first frames and the steady frame time, exit");
  cmd->add_option("--size", a.size,
                  "Window size in pixels: WIDTHxHEIGHT (1024x600 to 3840x2160 and beyond), or a "
                  "width alone (the height follows, 16:10)")
      ->check([](const std::string& text) {
        std::string why;
        return ui::parse_window_size(text, &why) ? std::string() : why;
      });
  return cmd;
}

int run_gui_command(const GuiArgs& a) {
  if (a.bench && a.file.empty()) {
    std::fprintf(stderr, "error: --bench needs a part file to load\n");
    return 1;
  }
  if (!a.file.empty() && !std::filesystem::exists(a.file)) {
    std::fprintf(stderr, "error: %s: no such file\n", a.file.c_str());
    return 1;
  }
  MachineProfile profile;
  if (!load_machine_profile(a.profile, a.values, profile, a.tool_table)) return 1;
  session::OperatorMailbox io(false, {});
  const std::unique_ptr<session::LiveMachine> live = session::LiveMachine::open(a, profile, io);
  if (!live) return 1;
  ui::GuiOptions o;
  o.file = a.file;
  o.script = a.script;
  o.bench = a.bench;
  o.macros = a.macros;
  o.realtime = live->real_time;
  o.card = live->sim() ? (a.realtime ? "sim (real time)" : "sim (virtual time)") : live->card_type;
  const std::optional<ui::WindowSize> size = ui::parse_window_size(a.size, nullptr);
  o.width = size ? size->width : 1280;
  o.height = size ? size->height : 800;
  o.recent_files = session::recent_files_path(profile.values_path);  // beside the machine state
  ui::Machine m{*live->controller, io, [&live] { return live->values.settings(); }};
  m.memory = live->memory.get();
  m.keys = &live->keys;
  m.pendant = &live->pendant->input();
  return ui::run_gui(o, m);
}

}  // namespace gantry
