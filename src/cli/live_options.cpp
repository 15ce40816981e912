// The flags of the live front ends' shared options.
#include "live_options.hpp"

#include "machine_profile.hpp"  // add_profile_option, add_allow_path_option ...

namespace gantry {

void add_live_machine_options(CLI::App* cmd, session::LiveMachineOptions& a,
                              const std::string& realtime_help) {
  cmd->add_option("--card", a.card, "Card to run on (default: the profile's card.type)")
      ->check(CLI::IsMember({"sim", "pci7200", "gpiod"}));
  cmd->add_flag("--realtime", a.realtime, realtime_help);
  add_profile_option(cmd, a.profile);
  cmd->add_option("--values", a.values,
                  "File of the V commands' values (TOML); default: the profile's in "
                  "~/.config/gantry/values");
  cmd->add_option("--persistent", a.persistent, "File of persistent $variables (JSON)");
  cmd->add_option("--macros", a.macros, "Folder of custom cut files C<n>.sbp / macro_<n>.sbp");
  cmd->add_flag("--allow-shell", a.allow_shell, "Let SHELL start programs");
  add_allow_path_option(cmd, a.allow_paths);
  add_tool_table_option(cmd, a.tool_table);
  add_subroutines_option(cmd, a.subroutines);
}

}  // namespace gantry
