// The machine profile a command runs with: the profile file (or the built-in default) with
// the operator's values file laid over it.
#pragma once

#include <string>
#include <vector>

#include "gantry/settings/settings.hpp"  // Settings

namespace gantry::session {

struct MachineProfile {
  Settings bare;      // the profile alone: the values file holds what differs from it
  Settings settings;  // with the values
  std::string values_path;
  std::string path;  // of the profile; "" the built-in default
  std::string name;  // for messages: the file's name without .toml, or "default"
};

// Loads `profile_path` (a file, a shipped profile's name, or "" the built-in default) and the
// values file (`values_path`, or "" for the profile's file in the config folder, which may not
// exist yet). On an error, prints every error to stderr (naming the file, line and key) and returns
// false.
// `tool_table` (--tool-table): the G-code tool table file, instead of the profile's.
bool load_machine_profile(const std::string& profile_path, const std::string& values_path,
                          MachineProfile& out, const std::string& tool_table = "");

// The folders part files may reach besides their own and the data folder: the profile's
// [files] allow (the profile alone: a values file cannot widen it) and `allow_paths`, with
// `~/` as $HOME (docs/security.md).
std::vector<std::string> allowed_folders(const MachineProfile& p,
                                         const std::vector<std::string>& allow_paths);

}  // namespace gantry::session
