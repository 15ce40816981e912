// HELP and STATUS per front end: the keys each front end has, the command table's help.
#include "gantry/session/console_help.hpp"

#include <algorithm>  // max

#include <fmt/format.h>

#include "gantry/commands/command_docs.hpp"   // command_help, command_list
#include "gantry/commands/command_table.hpp"  // CommandTable
#include "gantry/interp/interpreter.hpp"      // InterpreterOptions: the macro folders
#include "gantry/lang/scan.hpp"               // upper
#include "gantry/session/live_position.hpp"   // shown
#include "gantry/session/pendant_action.hpp"  // pendant_action_text
#include "gantry/session/readout_lines.hpp"   // speeds_text, spindle_text
#include "gantry/session/source_place.hpp"    // where

namespace gantry::session {
namespace {

const char* const kTerminalHelp =
    "Type a line and Enter: it runs on the machine, e.g.  MX, 5   J2, 1, 1   VS, 2   &D = 0.5\n"
    "  FP, part.sbp   (a file runs from the current folder).\n"
    "Editing: Left/Right, Home/End (Ctrl-A/Ctrl-E), Backspace/Delete, Ctrl-K/Ctrl-U, Up/Down\n"
    "  recall earlier lines, Tab completes a two-letter code or lists the matches.\n"
    "Words: help [CODE]   help commands   status   ack (after an E-stop)   K (keypad)   quit\n"
    "  step [on|off] (single step: each statement holds once its motion has played)\n"
    "  confirm (the position restored from the last session is right: no need to home)\n"
    "  teach FILE | teach off (Friendly Motion's teach log: Alt-F1 the place, F7-F10 M100-M103)\n"
    "Alt-F1...Alt-F10 during a Friendly Motion run: its subroutines N10001...N10010, then STEP.\n"
    "While a line runs: space pauses (then space or Enter resumes, Esc or q quits the file),\n"
    "  Esc stops, ! or Ctrl-C is the E-stop. Other lines wait until the machine is at rest.\n"
    "Keypad (K or SK): arrows X and Y, PageUp/PageDown Z, / and \\ diagonals, Ctrl+key fast;\n"
    "  S (or D) fixed steps or continuous, F fast or slow, space stops a jog, Esc leaves.\n"
    "  SK in a file opens it too: Esc goes on with the file, q stops it.\n"
    "  A continuous jog runs while the key repeats and slows to rest once the repeats stop.\n";

const char* const kWindowHelp =
    "Command line\n"
    "  two letters        a command; the parameter line below shows what it takes\n"
    "  Tab                completes the code (or lists the matches)\n"
    "  Up / Down          the lines entered before\n"
    "  Enter              runs the line; a code alone opens its fill-in sheet\n"
    "  Alt + letter       the menu of that group (M Move, J Jog, Z Zero, V Values ...)\n"
    "  help [CODE], status, ack, K (keypad), confirm (the restored position), quit\n"
    "  teach FILE / teach off   Friendly Motion's teach log (Alt-F1, Alt-F7-F10 at rest)\n"
    "  Alt + F1...F10     a Friendly Motion run's subroutines N10001...N10010, then STEP\n"
    "While a file or line runs\n"
    "  Space              pause, and resume\n"
    "  Esc                stop (the tool slows to rest on the path)\n"
    "  F12                E-stop (the pulses stop at once; ack to go on)\n"
    "Keypad (K, or click the keypad window)\n"
    "  Left / Right       X - / +          Up / Down   Y + / -\n"
    "  PageUp / PageDown  Z + / -\n"
    "  S                  fixed steps or continuous    F  fast or slow\n"
    "  Space              stops the jog                Esc leaves the keypad\n"
    "Fill-in sheets and dialogs: Enter runs (or answers), Esc closes (cancels).\n"
    "Preview: left drag rotates, right drag pans, the wheel zooms; the pointer shows the line.\n";

}  // namespace

std::string bound_keys_help(const KeyBindings& bound) {
  if (bound.empty()) return {};
  std::size_t width = 0;
  for (const auto& [key, event] : bound.all()) width = std::max(width, key.size());
  std::string out = "Keys bound in the profile's [pendant] keys (they act in every mode):\n";
  for (const auto& [key, event] : bound.all())
    out += fmt::format("  {:<{}}  {}\n", key, width, pendant_action_text(event));
  return out;
}

std::string keys_help(FrontEnd f, const KeyBindings* bound) {
  std::string out = f == FrontEnd::Terminal ? kTerminalHelp : kWindowHelp;
  if (bound) out += bound_keys_help(*bound);
  return out;
}

HelpAnswer help_answer(FrontEnd f, const std::string& arg, const KeyBindings* bound) {
  if (arg.empty()) return {keys_help(f, bound)};
  const CommandTable& table = CommandTable::standard();
  const std::string code = scan::upper(arg);
  if (f == FrontEnd::Terminal && code == "COMMANDS") return {command_list(table)};
  // A command, a statement (PAUSE, IF ...) or a custom cut (C2 ...), as `gantry help` answers:
  // from the tables the parser reads, and the macro folders a part file's C<n> looks in.
  const InterpreterOptions defaults;
  if (const std::optional<std::string> topic =
          help_topic(code, {defaults.user_macro_dir, defaults.shipped_macro_dir}))
    return {*topic};
  if (f == FrontEnd::Terminal)
    return {fmt::format("error: unknown command '{}'; help commands lists them all\n", arg), true};
  return {fmt::format("unknown command '{}'", arg), true};
}

std::string window_status(const ControllerStatus& st, const Vec6& p, Units u) {
  return fmt::format("{}  X {:.4f}  Y {:.4f}  Z {:.4f}  {}{}", state_name(st.state), shown(p[0]),
                     shown(p[1]), shown(p[2]), units_name(u),
                     st.message.empty() ? "" : "; last stop: " + st.message);
}

std::string terminal_status(const std::string& readout, const ControllerStatus& st,
                            const ModalState& m, const Vec6& table_base, double keypad_step,
                            Units u) {
  std::string out = readout + "\n";
  out += fmt::format("table base X {:.4f}  Y {:.4f}  Z {:.4f}; keypad step {:.4f} {}\n",
                     shown(table_base[0]), shown(table_base[1]), shown(table_base[2]), keypad_step,
                     units_name(u));
  out += speeds_text(m.speeds, u, st.feed_override) + "; " + spindle_text(st, m.spindle_rpm) + "\n";
  if (!st.message.empty())
    out += fmt::format("last stop: {}{}\n", st.message,
                       st.stopped_at.file ? " at " + where(st.stopped_at) : "");
  if (st.state == MachineState::EStop) out += "E-stop: nothing moves until you type ack\n";
  return out;
}

}  // namespace gantry::session
