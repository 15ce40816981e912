// The command line's options that choose the machine profile and what part files may reach.
#include "machine_profile.hpp"

#include "gantry/settings/profiles.hpp"  // shipped_profile_names

namespace gantry {

void add_profile_option(CLI::App* cmd, std::string& profile) {
  std::string names;
  for (const std::string& n : shipped_profile_names()) names += (names.empty() ? "" : ", ") + n;
  cmd->add_option("--profile,--settings", profile,
                  "Machine profile: a shipped one by name (" + names +
                      "; docs/settings.md) or a TOML file; default: built in");
}

void add_allow_path_option(CLI::App* cmd, std::vector<std::string>& folders) {
  cmd->add_option("--allow-path", folders,
                  "A folder part files may read and write in besides their own and Gantry's "
                  "data folder (repeatable; docs/security.md)");
}

void add_tool_table_option(CLI::App* cmd, std::string& file) {
  cmd->add_option("--tool-table", file,
                  "G-code's tool table (LinuxCNC's format: T1 P1 D0.25 Z+1.5), instead of the "
                  "profile's tool_table; G10 L1/L10/L11 write it back (docs/gcode.md)");
}

void add_subroutines_option(CLI::App* cmd, std::vector<std::string>& folders) {
  cmd->add_option("--subroutines", folders,
                  "Folder where G-code's o<name> call finds name.ngc after the calling file's "
                  "folder, before the profile's subroutines folders (may be given again)");
}

}  // namespace gantry
