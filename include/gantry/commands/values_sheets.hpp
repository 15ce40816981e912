// Where each setting of the profile is shown to the operator (docs/values.md, "What the
// sheets show"): as a parameter of a V command (its fill-in sheet, and the values a bare one
// lists), among the profile's rows a bare V command lists after its parameters, or only in
// the profile, for the tables that describe the machine's wiring and set-up.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace gantry {

struct Settings;
struct SettingRow;

// A bare V command (`code`) lists, after its parameters, the profile's rows whose path starts
// with `prefix` ("limits.", "axes.<x..c>.backlash"), read only: they are set in the profile.
struct SheetRows {
  std::string_view code;
  std::string_view prefix;
};
std::span<const SheetRows> sheet_profile_rows();

// The tables shown in no sheet: the machine's wiring and set-up, read from the profile only
// ("card", "pins.<x..c>", ...; "" is the top-level keys).
std::span<const std::string_view> profile_only_tables();

// Where `row` is shown: the V command whose parameter sets it (`as_parameter` true), or whose
// bare listing shows it after its parameters (false); "" when no sheet shows it.
std::string_view sheet_of(const SettingRow& row, bool* as_parameter = nullptr);

// The lines a bare `code` prints after its parameters: each of its sheet_profile_rows, one line
// a key (a family's axes in use on one line), "" when it has none.
std::string sheet_profile_lines(std::string_view code, const Settings& s);

}  // namespace gantry
