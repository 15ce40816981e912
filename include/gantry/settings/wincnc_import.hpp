// `gantry import-wincnc`: a WinCNC set-up (WINCNC.INI, CNCSCRN.INI, CNC.MAC) as a Gantry
// profile. Every keyword the WinCNC manual documents is known here: those Gantry has a key
// for are carried into the profile's Settings (written by the settings schema's writer,
// settings_text), the others are listed with their file and line and why (docs/hardware.md,
// "Importing a WinCNC set-up").
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"    // Diagnostic, SourceLoc
#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

// One input file: its path (as messages name it) and its text.
struct WincncFile {
  std::string path;
  std::string text;
};

struct WincncSources {
  WincncFile ini;                    // WINCNC.INI
  std::optional<WincncFile> screen;  // CNCSCRN.INI
  std::optional<WincncFile> macros;  // CNC.MAC
  std::string name = "wincnc";       // the profile's name
};

// A documented keyword (or one parameter of it) the profile does not carry.
struct WincncUnmapped {
  SourceLoc loc;        // its file and line
  std::string keyword;  // "lim_step", "axisvel S", "\"Viewer\""
  std::string why;      // why, and what to do instead
};

// A CNC.MAC macro, as the custom cut `C<cut>` that runs its command.
struct WincncMacro {
  SourceLoc loc;
  std::string name;     // "M3"
  std::string command;  // "M98 SPIN.MAC"
  std::string comment;  // "SPINDLE ON"
  int cut = 0;          // C<cut>
  std::string file;     // a subprogram the command calls (M98 FILE), "" none
};

struct WincncImport {
  Settings settings;                     // the profile; complete when `errors` is empty
  std::vector<Diagnostic> errors;        // malformed lines, unknown keywords, bad values
  std::vector<WincncUnmapped> unmapped;  // in file and line order
  std::vector<WincncMacro> macros;
  std::vector<std::string> mapped;  // "WINCNC.INI:12: axisspec R -> axes.x.steps_per_unit"
  bool ok() const { return errors.empty(); }
};

// Reads the files into a profile, starting from the built-in default profile.
WincncImport import_wincnc(const WincncSources& in);

// The profile's text: a header naming the sources and what was not mapped, then every key
// (settings_text).
std::string wincnc_profile_text(const WincncImport& r, const WincncSources& in);
// The report `gantry import-wincnc` prints: what was not mapped, and why.
std::string wincnc_report(const WincncImport& r);
// A macro's custom cut file (C<cut>.sbp).
std::string wincnc_macro_cut(const WincncMacro& m);

}  // namespace gantry
