// The machine profiles shipped with Gantry (settings/profiles/, docs/settings.md): found by
// name from any working directory, the folder's path compiled in.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gantry/core/vec6.hpp"          // Vec6
#include "gantry/settings/settings.hpp"  // Units

namespace gantry {

// The folder of the shipped profiles.
const std::string& shipped_profiles_dir();

// Their names (file names without .toml), sorted.
std::vector<std::string> shipped_profile_names();

// --profile NAME|PATH: an existing file is itself; otherwise a shipped profile's name gives its
// file. nullopt when it is neither.
std::optional<std::string> resolve_profile(const std::string& name_or_path);

// The shipped profiles in `units` whose soft limits hold `table_point`'s X, Y and Z (table base
// coordinates), by name. A profile that does not load is left out (a test loads every one).
std::vector<std::string> shipped_profiles_holding(const Vec6& table_point, Units units);

}  // namespace gantry
