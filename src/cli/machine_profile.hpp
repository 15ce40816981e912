// The machine profile a command runs with: the profile file (or the built-in default) with
// the operator's values file laid over it.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

struct MachineProfile {
  Settings bare;      // the profile alone: the values file holds what differs from it
  Settings settings;  // with the values
  std::string values_path;
  std::string path;  // of the profile; "" the built-in default
  std::string name;  // for messages: the file's name without .toml, or "default"
};

// --profile NAME|PATH (--settings, its older name, too): a shipped profile's name
// (settings/profiles/, found from any directory) or a profile file; default: built in.
void add_profile_option(CLI::App* cmd, std::string& profile);

// Loads `profile_path` (a file, a shipped profile's name, or "" the built-in default) and the
// values file (`values_path`, or "" for the profile's file in the config folder, which may not
// exist yet). On an error, prints every error to stderr (naming the file, line and key) and returns
// false.
// `tool_table` (--tool-table): the G-code tool table file, instead of the profile's.
bool load_machine_profile(const std::string& profile_path, const std::string& values_path,
                          MachineProfile& out, const std::string& tool_table = "");

// --tool-table FILE: G-code's tool table (docs/gcode.md, "Tool table").
void add_tool_table_option(CLI::App* cmd, std::string& file);

// --subroutines DIR (repeatable): where G-code's o<name> call finds name.ngc, before the
// profile's `subroutines` folders.
void add_subroutines_option(CLI::App* cmd, std::vector<std::string>& folders);

// --allow-path DIR (repeatable): a folder part files may read and write in, besides theirs.
void add_allow_path_option(CLI::App* cmd, std::vector<std::string>& folders);
// The folders part files may reach besides their own and the data folder: the profile's
// [files] allow (the profile alone: a values file cannot widen it) and `allow_paths`, with
// `~/` as $HOME (docs/security.md).
std::vector<std::string> allowed_folders(const MachineProfile& p,
                                         const std::vector<std::string>& allow_paths);

}  // namespace gantry
