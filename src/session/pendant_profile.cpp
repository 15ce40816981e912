// The [pendant] section's macros and key bindings for the live machine.
#include "gantry/session/pendant_profile.hpp"

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "gantry/core/text.hpp"  // ascii::lower

namespace gantry::session {
namespace {

bool part_file(const std::string& t) {
  const std::string low = ascii::lower(t);
  for (const char* ext : {".sbp", ".nc", ".ngc", ".gcode", ".tap"})
    if (low.ends_with(ext)) return true;
  return t.starts_with("/") || t.starts_with("~/") || t.starts_with("./");
}

// The line of the profile's pendant.keys item `i` (0: not found).
int item_line(const std::string& profile_path, std::size_t i) {
  if (profile_path.empty()) return 0;
  try {
    const toml::table t = toml::parse_file(profile_path);
    const toml::array* a = t.at_path("pendant.keys").as_array();
    if (!a || i >= a->size()) return 0;
    return static_cast<int>((*a)[i].source().begin.line);
  } catch (const toml::parse_error&) {
    return 0;
  }
}

}  // namespace

std::string macro_line(const std::string& text, const std::string& profile_dir) {
  const std::string t(ascii::trim(text));
  if (t.empty() || !part_file(t)) return t;
  std::filesystem::path p = t;
  if (t.starts_with("~/")) {
    const char* home = std::getenv("HOME");
    p = std::filesystem::path(home ? home : "") / t.substr(2);
  } else if (p.is_relative() && !profile_dir.empty()) {
    p = std::filesystem::path(profile_dir) / p;
  }
  return "FP, " + p.lexically_normal().string();
}

PendantProfile pendant_profile(const Settings& s, const std::string& profile_path,
                               std::vector<Diagnostic>* problems) {
  PendantProfile out;
  const std::string dir =
      profile_path.empty() ? "" : std::filesystem::path(profile_path).parent_path().string();
  for (std::size_t i = 0; i < out.buttons.macros.size(); ++i)
    out.buttons.macros[i] = macro_line(s.pendant.macros[i], dir);
  std::vector<KeyBindings::Problem> bad;
  out.keys = KeyBindings::parse(s.pendant.keys, &bad);
  const std::string file = profile_path.empty() ? "settings/default.toml" : profile_path;
  for (const KeyBindings::Problem& p : bad)
    if (problems)
      problems->push_back({file_loc(file, item_line(profile_path, p.item)), Severity::Error,
                           fmt::format("pendant.keys: {}; that key is left unbound", p.message)});
  return out;
}

}  // namespace gantry::session
