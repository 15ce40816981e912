// The profile's [pendant] section made the live machine's bindings: the macros' lines (a part
// file's path becomes its FP line) and the keys bound as a pendant, with a bad key binding
// told at its file and line and left out.
#pragma once

#include <string>
#include <vector>

#include "gantry/core/diagnostic.hpp"         // Diagnostic
#include "gantry/session/key_bindings.hpp"    // KeyBindings
#include "gantry/session/pendant_input.hpp"   // PendantBindings
#include "gantry/settings/settings.hpp"       // Settings

namespace gantry::session {

// A macro's text as the line it runs: a part file's path (ending .sbp, .nc, .ngc, .gcode, .tap,
// or starting /, ~/, ./) as `FP, <path>` (~ as $HOME, a relative path from `profile_dir`);
// anything else is a line as typed ("C3", "MZ, 1"); "" stays unbound.
std::string macro_line(const std::string& text, const std::string& profile_dir);

struct PendantProfile {
  PendantBindings buttons;  // with the profile's macros
  KeyBindings keys;
};

// `profile_path`: the profile's file ("": the built-in default), where a bad key binding is
// found: each is an error in `problems` at the item's line.
PendantProfile pendant_profile(const Settings& s, const std::string& profile_path,
                               std::vector<Diagnostic>* problems);

}  // namespace gantry::session
