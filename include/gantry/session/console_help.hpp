// What a console's words HELP and STATUS answer, per front end (the terminal console and the
// window): computed here once, so the front ends only show the text.
#pragma once

#include <string>

#include "gantry/core/axes.hpp"             // Vec6
#include "gantry/interp/interpreter.hpp"    // ModalState
#include "gantry/machine/controller.hpp"    // ControllerStatus
#include "gantry/session/key_bindings.hpp"  // KeyBindings
#include "gantry/settings/settings.hpp"     // Units

namespace gantry::session {

enum class FrontEnd { Terminal, Window };

// HELP alone: the front end's keys and words, then the keys the profile's [pendant] section
// binds (`bound`, when given and not empty), listed from the bindings themselves.
std::string keys_help(FrontEnd f, const KeyBindings* bound = nullptr);
// The profile's bound keys, a line each ("  F5           step x+ 0.25"), sorted by key name,
// under a heading; "" when none is bound.
std::string bound_keys_help(const KeyBindings& bound);

struct HelpAnswer {
  std::string text;
  bool error = false;  // an unknown topic
};
// HELP [argument]: the keys (with the bound ones), the command list (the terminal's HELP
// COMMANDS) or a command.
HelpAnswer help_answer(FrontEnd f, const std::string& arg, const KeyBindings* bound = nullptr);

// The window's STATUS: state, X Y Z at `p` (working coordinates), units and the last stop.
std::string window_status(const ControllerStatus& st, const Vec6& p, Units u);
// The terminal's STATUS: its readout line, the table base position and keypad step, the
// speeds and spindle (`m`: the values in force, read at rest), the last stop and the E-stop.
std::string terminal_status(const std::string& readout, const ControllerStatus& st,
                            const ModalState& m, const Vec6& table_base, double keypad_step,
                            Units u);

}  // namespace gantry::session
