// `gantry import-wincnc WINCNC.INI [CNCSCRN.INI] -o profile.toml`: a WinCNC set-up as a
// Gantry profile, with CNC.MAC's macros as custom cuts (docs/hardware.md, "Importing a
// WinCNC set-up").
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace gantry {

struct ImportWincncArgs {
  std::string ini, screen, output, name, macros;
};

CLI::App* add_import_wincnc_command(CLI::App& app, ImportWincncArgs& args);

// Reads the files, writes the profile and the custom cuts, prints the report: 0, or 1 (every
// error printed, located; nothing written) when a file is missing or holds a bad line.
int run_import_wincnc(const ImportWincncArgs& args);

}  // namespace gantry
