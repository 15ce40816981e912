// The operator's values: what the V commands change, saved apart from the machine profile.
//
// A profile (settings/*.toml) describes the machine and is edited by hand; the values file
// holds only the keys whose value the operator changed with a V command (or MS/JS), in the
// profile's own key names. Loading reads the profile, then lays the values file over it, and
// validates the result: an error names the file and line that holds the bad key.
#pragma once

#include <optional>
#include <string>

#include "gantry/settings/settings.hpp"  // Settings, SettingsLoad

namespace gantry {

// The profile `profile_text` with the values file `values_text` (if any) laid over it.
SettingsLoad parse_settings(const std::string& profile_text, const std::string& profile_origin,
                            const std::optional<std::string>& values_text,
                            const std::string& values_origin);

// Every key of `s`, as a complete profile (US saves one; parse_settings reads it back).
std::string settings_text(const Settings& s);
// The keys of `current` whose values differ from `profile`: the values file's text.
std::string values_text(const Settings& current, const Settings& profile);

// Where the values for a profile named `profile_name` live:
// user_config_dir()/values/<name as a file name>.toml.
std::string default_values_path(const std::string& profile_name);

// The first key describing the machine itself (not an operator's value) that differs between
// `now` and `next`: the card, its wiring, the axes' hardware limits, the planner; "" when none
// does (UR refuses to change these from a values file).
std::string machine_key_changed(const Settings& now, const Settings& next);

}  // namespace gantry
