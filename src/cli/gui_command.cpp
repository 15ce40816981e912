// `gantry gui`: the profile, the card and the controller, as `gantry console` makes them,
// handed to the window.
#include "gui_command.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "gantry/interp/persistent_store.hpp"  // PersistentStore
#include "gantry/machine/controller.hpp"       // Controller
#include "gantry/session/operator_io.hpp"      // OperatorMailbox
#include "gui.hpp"                             // run_gui (ui/)
#include "live_machine.hpp"                    // ValuesKeeper, open_live_card
#include "machine_profile.hpp"                 // load_machine_profile
#include "open_card.hpp"                       // plays_in_real_time

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
  cmd->add_option("--size", a.width, "Window width in pixels (the height follows, 16:10)")
      ->check(CLI::Range(800, 4096));
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
  const Settings& settings = profile.settings;
  PersistentStore store(a.persistent.empty() ? PersistentStore::default_path() : a.persistent);
  session::OperatorMailbox io(false, {});
  ValuesKeeper values(profile, io);

  std::string type;
  const std::unique_ptr<Card> card = open_live_card(a, settings, &type);
  if (!card) return 1;
  const bool sim = type == "sim";
  const bool real_time = plays_in_real_time(type, a.realtime);
  Controller controller(settings, *card, io, store,
                        live_interpreter_options(profile, values, a, real_time));
  ui::GuiOptions o;
  o.file = a.file;
  o.script = a.script;
  o.bench = a.bench;
  o.realtime = real_time;
  o.card = sim ? (a.realtime ? "sim (real time)" : "sim (virtual time)") : type;
  o.width = a.width;
  o.height = a.width * 10 / 16;
  ui::Machine m{controller, io, [&values] { return values.settings(); }};
  return ui::run_gui(o, m);
}

}  // namespace gantry
