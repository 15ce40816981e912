// `gantry console`: its options, and the wiring: the profile, the card, the controller, the
// operator's mailbox and the signal watcher, handed to the terminal console.
#include <fmt/format.h>
#include <unistd.h>     // isatty
#include <CLI/CLI.hpp>  // the subcommand

#include <atomic>
#include <map>

#include "console.hpp"
#include "console_terminal.hpp"            // write_out
#include "console_view.hpp"                // Console
#include "gantry/lang/scan.hpp"            // upper
#include "gantry/session/operator_io.hpp"  // OperatorMailbox
#include "live_options.hpp"                // add_live_machine_options, LiveMachine
#include "machine_profile.hpp"             // load_machine_profile
#include "signal_watch.hpp"                // SignalWatch

namespace gantry {

using console::write_out;
using scan::upper;
using session::OperatorMailbox;

CLI::App* add_console_command(CLI::App& app, ConsoleArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "console", "The live machine at a terminal: type lines, pause, stop, jog (docs/console.md)");
  add_live_machine_options(cmd, a,
                           "Play the simulated card in real time (continuous keypad jogs and "
                           "pausing a move need it)");
  cmd->add_flag("--yes", a.yes, "Continue every PAUSE and press each MSGBOX's default button");
  cmd->add_option("--input", a.inputs, "Answer INPUT for a variable: --input '&DEPTH=0.5'");
  cmd->add_option("--key-release-ms", a.release_ms,
                  "Keypad: a continuous jog stops when its key has not repeated for this long")
      ->check(CLI::Range(30, 2000));
  cmd->add_option("--key-repeat-delay-ms", a.repeat_delay_ms,
                  "Keypad: the terminal's delay before a held key repeats; the same key later "
                  "than this is a new press (a step)")
      ->check(CLI::Range(50, 3000));
  return cmd;
}

int run_console(const ConsoleArgs& a) {
  MachineProfile profile;
  if (!load_machine_profile(a.profile, a.values, profile, a.tool_table)) return 1;
  const Settings& settings = profile.settings;
  std::map<std::string, std::string> inputs;
  for (const std::string& kv : a.inputs) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      fmt::print(stderr, "error: --input {} must be NAME=VALUE, e.g. --input '&DEPTH=0.5'\n", kv);
      return 1;
    }
    std::string name = upper(kv.substr(0, eq));
    if (name[0] != '&' && name[0] != '$') name = "&" + name;
    inputs[name] = kv.substr(eq + 1);
  }
  const bool interactive = isatty(STDIN_FILENO) && isatty(STDOUT_FILENO);

  SignalWatch signals;  // before the controller starts its threads: they inherit the mask
  OperatorMailbox io(a.yes, inputs,
                     interactive ? std::function<void(std::string_view)>{}
                                 : std::function<void(std::string_view)>(write_out));
  const std::unique_ptr<session::LiveMachine> live = session::LiveMachine::open(a, profile, io);
  if (!live) return 1;
  Controller& controller = *live->controller;
  std::atomic<int> signal{0};
  signals.start([&](int sig) {
    signal = sig;
    controller.estop();
    io.cancel();
  });
  struct StopFirst {  // the watcher ends before the controller it E-stops
    SignalWatch& w;
    ~StopFirst() { w.stop(); }
  } stop_first{signals};

  console::Console console(controller, io, live->values, a, live->real_time, signal);
  console.keep_state(live->memory.get());
  console.bind_keys(live->keys, live->pendant->input());
  if (!interactive) return console.piped();
  const std::string banner = fmt::format(
      "gantry console: profile \"{}\" on the {}{}\nhelp lists the keys; quit leaves.\n",
      settings.name, live->sim() ? "simulated card" : live->card_type + " card",
      !live->sim() ? ""
      : a.realtime ? " (real time)"
                   : " (virtual time: moves end at once; --realtime plays them in real time)");
  return console.interactive(banner);
}

}  // namespace gantry
