// Loading the machine profile and the values file for a command.
#include "gantry/session/machine_profile.hpp"

#include <fmt/format.h>  // errors

#include <cstdio>      // stderr
#include <cstdlib>     // getenv
#include <filesystem>  // exists
#include <optional>

#include "gantry/core/text_file.hpp"        // read_text_file
#include "gantry/settings/profiles.hpp"     // resolve_profile, shipped_profile_names
#include "gantry/settings/values_file.hpp"  // parse_settings with values, default_values_path

namespace gantry::session {

std::vector<std::string> allowed_folders(const MachineProfile& p,
                                         const std::vector<std::string>& allow_paths) {
  std::vector<std::string> out;
  const char* home = std::getenv("HOME");
  for (const auto* list : {&p.bare.files.allow, &allow_paths})
    for (const std::string& folder : *list)
      out.push_back(folder.starts_with("~/") && home ? home + folder.substr(1) : folder);
  return out;
}

namespace {

bool load_profile_and_values(const std::string& profile_arg, const std::string& values_path,
                             MachineProfile& out) {
  auto print_errors = [](const std::vector<Diagnostic>& errors) {
    for (const Diagnostic& d : errors) fmt::print(stderr, "{}\n", format(d));
  };
  std::string profile_path;
  if (!profile_arg.empty()) {
    const std::optional<std::string> found = resolve_profile(profile_arg);
    const bool a_path = profile_arg.find('/') != std::string::npos ||
                        std::filesystem::path(profile_arg).extension() == ".toml";
    if (!found && !a_path) {
      std::string names;
      for (const std::string& n : shipped_profile_names()) names += "\n  " + n;
      fmt::print(stderr,
                 "{}: error: no such profile file, and no shipped profile of that name; give a "
                 "TOML file or one of the shipped profiles (in {}):{}\n",
                 profile_arg, shipped_profiles_dir(), names);
      return false;
    }
    profile_path = found.value_or(profile_arg);  // a missing file: the loader says so
  }
  out.name = profile_path.empty() ? "default" : std::filesystem::path(profile_path).stem().string();
  const std::optional<std::string> text = profile_path.empty()
                                              ? std::optional<std::string>(default_profile_text())
                                              : read_text_file(profile_path);
  const std::string origin = profile_path.empty() ? "settings/default.toml" : profile_path;
  const SettingsLoad bare = text ? parse_settings(*text, origin) : load_settings_file(profile_path);
  if (!bare.ok()) {
    print_errors(bare.errors);
    return false;
  }
  out.bare = out.settings = bare.settings;
  out.path = profile_path;
  out.values_path = values_path.empty() ? default_values_path(bare.settings.name) : values_path;
  if (!std::filesystem::exists(out.values_path)) return true;  // nothing changed yet
  const std::optional<std::string> values_text = read_text_file(out.values_path);
  if (!values_text) {
    fmt::print(stderr, "{}: error: cannot read the values file; check its permissions\n",
               out.values_path);
    return false;
  }
  const SettingsLoad load = parse_settings(*text, origin, values_text, out.values_path);
  if (!load.ok()) {
    print_errors(load.errors);
    fmt::print(stderr,
               "the values file {} holds the V commands' changes; fix the key named above, or "
               "delete the file to return to the profile's values\n",
               out.values_path);
    return false;
  }
  out.settings = load.settings;
  return true;
}

}  // namespace

bool load_machine_profile(const std::string& profile_arg, const std::string& values_path,
                          MachineProfile& out, const std::string& tool_table) {
  const bool loaded = load_profile_and_values(profile_arg, values_path, out);
  // The profile's own: a values file cannot point G10's writes elsewhere.
  out.settings.tool_table = out.bare.tool_table;
  out.settings.tool_table_path = out.bare.tool_table_path;
  out.settings.subroutines = out.bare.subroutines;
  out.settings.subroutine_paths = out.bare.subroutine_paths;
  if (!tool_table.empty())
    out.bare.tool_table = out.settings.tool_table = out.bare.tool_table_path =
        out.settings.tool_table_path = tool_table;
  return loaded;
}

}  // namespace gantry::session
