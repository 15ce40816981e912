// The shipped machine profiles: names, lookup and which tables hold a point.
#include "gantry/settings/profiles.hpp"

#include <algorithm>   // sort
#include <filesystem>  // directory_iterator

#include "gantry/core/data_folder.hpp"  // installed or in the source tree

namespace gantry {

namespace fs = std::filesystem;

const std::string& shipped_profiles_dir() {
  static const std::string dir = shipped_data_folder("profiles", GANTRY_PROFILES_DIR);
  return dir;
}

std::vector<std::string> shipped_profile_names() {
  std::vector<std::string> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(shipped_profiles_dir(), ec))
    if (e.path().extension() == ".toml") out.push_back(e.path().stem().string());
  std::sort(out.begin(), out.end());
  return out;
}

std::optional<std::string> resolve_profile(const std::string& name_or_path) {
  std::error_code ec;
  if (fs::is_regular_file(name_or_path, ec)) return name_or_path;
  if (name_or_path.find('/') != std::string::npos) return std::nullopt;
  const fs::path shipped = fs::path(shipped_profiles_dir()) / (name_or_path + ".toml");
  if (fs::is_regular_file(shipped, ec)) return shipped.string();
  return std::nullopt;
}

std::vector<std::string> shipped_profiles_holding(const Vec6& table_point, Units units) {
  std::vector<std::string> out;
  for (const std::string& name : shipped_profile_names()) {
    const SettingsLoad load =
        load_settings_file((fs::path(shipped_profiles_dir()) / (name + ".toml")).string());
    if (!load.ok() || load.settings.units != units) continue;
    bool holds = true;
    for (int i = 0; i < 3; ++i)
      holds = holds && table_point[i] >= load.settings.axes[i].min &&
              table_point[i] <= load.settings.axes[i].max;
    if (holds) out.push_back(name);
  }
  return out;
}

}  // namespace gantry
