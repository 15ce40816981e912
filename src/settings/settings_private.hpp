// Shared by the profile reader and writer: the TOML form of a profile.
#pragma once

#include <toml++/toml.h>

#include <string>

#include "gantry/settings/settings.hpp"

namespace gantry {

// Reads and validates a parsed profile; errors name each node's own file (its source path),
// or `origin`.
SettingsLoad parse_settings_table(const toml::table& table, const std::string& origin);

// Every key of `s` in the profile's schema (the inverse of parse_settings_table).
toml::table settings_table(const Settings& s);

}  // namespace gantry
