// `gantry import-wincnc`: the files read, the profile and the custom cuts written.
#include "import_wincnc.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>

#include "gantry/core/text.hpp"               // ascii::lower
#include "gantry/core/text_file.hpp"          // read_text_file, write_file_atomically
#include "gantry/session/key_bindings.hpp"    // the keys bound must be keys
#include "gantry/settings/settings.hpp"       // load_settings_file
#include "gantry/settings/wincnc_import.hpp"  // import_wincnc

namespace gantry {
namespace {

namespace fs = std::filesystem;

// A file beside `dir` whose name is `name` in any case (WinCNC's files come from Windows).
std::optional<fs::path> beside(const fs::path& dir, std::string_view name) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir.empty() ? "." : dir, ec))
    if (e.is_regular_file(ec) && ascii::lower(e.path().filename().string()) == ascii::lower(name))
      return e.path();
  return std::nullopt;
}

std::optional<WincncFile> read(const std::string& path) {
  const std::optional<std::string> text = read_text_file(path);
  if (!text) {
    fmt::print(stderr, "{}: error: cannot open the file; check the path and its permissions\n",
               path);
    return std::nullopt;
  }
  return WincncFile{path, *text};
}

}  // namespace

CLI::App* add_import_wincnc_command(CLI::App& app, ImportWincncArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "import-wincnc",
      "Write a profile from a WinCNC set-up (WINCNC.INI, CNCSCRN.INI, CNC.MAC beside them), "
      "listing what it could not map");
  cmd->add_option("ini", a.ini, "WinCNC's WINCNC.INI")->required();
  cmd->add_option("screen", a.screen, "WinCNC's CNCSCRN.INI (its keypad and pendant keys)");
  cmd->add_option("-o,--output", a.output, "The profile to write (.toml)")->required();
  cmd->add_option("--name", a.name, "The profile's name (default: the output file's stem)");
  cmd->add_option("--macros", a.macros,
                  "Where CNC.MAC's macros go as custom cuts C100, C101... (default: the folder "
                  "'macros' beside the profile)");
  return cmd;
}

int run_import_wincnc(const ImportWincncArgs& a) {
  WincncSources in;
  std::optional<WincncFile> ini = read(a.ini);
  if (!ini) return 1;
  in.ini = *ini;
  if (!a.screen.empty()) {
    in.screen = read(a.screen);
    if (!in.screen) return 1;
  }
  // CNC.MAC must exist beside WINCNC.INI in a WinCNC installation (the manual, "Macro File
  // Configuration"); one that is not there has no macros to carry.
  const fs::path ini_dir = fs::path(a.ini).parent_path();
  if (const std::optional<fs::path> mac = beside(ini_dir, "CNC.MAC")) {
    in.macros = read(mac->string());
    if (!in.macros) return 1;
  }
  const fs::path out(a.output);
  in.name = a.name.empty() ? out.stem().string() : a.name;

  WincncImport r = import_wincnc(in);
  // The keys bound are checked as the live machine will read them.
  std::vector<session::KeyBindings::Problem> problems;
  session::KeyBindings::parse(r.settings.pendant.keys, &problems);
  for (const auto& p : problems)
    r.errors.push_back({file_loc(in.ini.path), Severity::Error,
                        fmt::format("the key binding \"{}\" it makes is not valid: {}",
                                    r.settings.pendant.keys[p.item], p.message)});
  if (!r.ok()) {
    for (const Diagnostic& d : r.errors) fmt::print(stderr, "{}\n", format(d));
    fmt::print(stderr, "gantry: {} error{}; nothing was written\n", r.errors.size(),
               r.errors.size() == 1 ? "" : "s");
    return 1;
  }
  std::string why;
  if (!write_file_atomically(a.output, wincnc_profile_text(r, in), &why)) {
    fmt::print(stderr, "{}: error: cannot write the profile: {}\n", a.output, why);
    return 1;
  }
  // The profile is read back as `--profile` will read it.
  const SettingsLoad back = load_settings_file(a.output);
  for (const Diagnostic& d : back.errors) fmt::print(stderr, "{}\n", format(d));
  if (!back.ok()) return 1;
  fmt::print("wrote {}: profile \"{}\", {} axes ({}), {} units\n", a.output, r.settings.name,
             r.settings.display.axes, axis_names(r.settings).substr(0, r.settings.display.axes),
             units_name(r.settings.units));
  if (!r.macros.empty()) {
    const fs::path dir = a.macros.empty() ? out.parent_path() / "macros" : fs::path(a.macros);
    std::error_code ec;
    fs::create_directories(dir, ec);
    for (const WincncMacro& m : r.macros) {
      const fs::path cut = dir / fmt::format("C{}.sbp", m.cut);
      if (!write_file_atomically(cut.string(), wincnc_macro_cut(m), &why)) {
        fmt::print(stderr, "{}: error: cannot write the custom cut: {}\n", cut.string(), why);
        return 1;
      }
      fmt::print("wrote {}: {} = {}\n", cut.string(), m.name, m.command);
      // The subprogram an M98 macro calls goes beside it, where M98 looks.
      if (!m.file.empty()) {
        if (const std::optional<fs::path> sub = beside(ini_dir, m.file)) {
          const std::optional<std::string> text = read_text_file(sub->string());
          if (text && write_file_atomically((dir / sub->filename()).string(), *text, &why))
            fmt::print("copied {} to {}\n", sub->string(), dir.string());
        } else {
          fmt::print("note: {} calls {}, which is not beside {}: copy it into {}\n", m.name, m.file,
                     a.ini, dir.string());
        }
      }
    }
    fmt::print("C{} ... run from part files and the console with --macros {}\n",
               r.macros.front().cut, dir.string());
  }
  fmt::print("{}", wincnc_report(r));
  return 0;
}

}  // namespace gantry
