// The command line's options that choose the machine profile and what part files may reach;
// the profile itself is loaded by the session (gantry/session/machine_profile.hpp).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "gantry/session/machine_profile.hpp"  // MachineProfile, load_machine_profile

namespace gantry {

using session::allowed_folders;
using session::load_machine_profile;
using session::MachineProfile;

// --profile NAME|PATH (--settings, its older name, too): a shipped profile's name
// (settings/profiles/, found from any directory) or a profile file; default: built in.
void add_profile_option(CLI::App* cmd, std::string& profile);

// --tool-table FILE: G-code's tool table (docs/gcode.md, "Tool table").
void add_tool_table_option(CLI::App* cmd, std::string& file);

// --subroutines DIR (repeatable): where G-code's o<name> call finds name.ngc, before the
// profile's `subroutines` folders.
void add_subroutines_option(CLI::App* cmd, std::vector<std::string>& folders);

// --allow-path DIR (repeatable): a folder part files may read and write in, besides theirs.
void add_allow_path_option(CLI::App* cmd, std::vector<std::string>& folders);

}  // namespace gantry
