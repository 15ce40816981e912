// The settings schema table: each numeric setting's key, member, range, unit kind and help.
#include "gantry/settings/settings_schema.hpp"

#include <fmt/format.h>  // describe, docs

#include <algorithm>  // find_if
#include <stdexcept>  // out_of_range

#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

// VR's ramp rates: one range for the profile, the values file and VR (issue 24 resolved the
// drift between the profile's (0, 1e6] and VR's [1e-6, 1e6] to VR's closed range, which the
// command table's inclusive ParamSpec ranges can state).
constexpr SettingRange kRampRate{1e-6, 1e6};

#define GANTRY_MEMBER(expr) [](Settings& s) -> double& { return s.expr; }

// clang-format off
const SettingRow kRows[] = {
  {"ramps", "move_ramp_rate", GANTRY_MEMBER(ramps.move_ramp_rate), kRampRate, SettingUnit::Length,
   "VR move ramp rate: distance over which the speed changes by 2 units/s (a length)"},
  {"ramps", "jog_ramp_rate", GANTRY_MEMBER(ramps.jog_ramp_rate), kRampRate, SettingUnit::Length,
   "VR jog ramp rate, as the move ramp rate (a length)"},
  {"ramps", "threshold_3d", GANTRY_MEMBER(ramps.threshold_3d), {0, 1000}, SettingUnit::None,
   "VR 3D ramp threshold, percent"},
  {"ramps", "min_distance", GANTRY_MEMBER(ramps.min_distance), {0, 1e3}, SettingUnit::Length,
   "VR minimum distance to check (a length)"},
  {"ramps", "slow_corner", GANTRY_MEMBER(ramps.slow_corner), {0, 100}, SettingUnit::None,
   "VR slow corner speed, percent"},
  {"ramps", "keypad_ramp_rate", GANTRY_MEMBER(ramps.keypad_ramp_rate), kRampRate,
   SettingUnit::Length, "VR keypad ramp rate (a length)"},
  {"ramps", "small_circle", GANTRY_MEMBER(ramps.small_circle), {0, 1e3}, SettingUnit::Length,
   "VR small-circle diameter (a length)"},
  {"tabs", "pull_up", GANTRY_MEMBER(tabs.pull_up), {0, 1e4}, SettingUnit::Length,
   "VB tab height: how far the cutter lifts for a tab (a length)"},
  {"tabs", "spacing", GANTRY_MEMBER(tabs.spacing), {0, 1e6, true}, SettingUnit::Length,
   "VB distance from one tab to the next (a length)"},
  {"tabs", "size", GANTRY_MEMBER(tabs.size), {0, 1e6}, SettingUnit::Length,
   "VB tab length along the path (a length)"},
  {"tabs", "leads", GANTRY_MEMBER(tabs.leads), {0, 1e6}, SettingUnit::Length,
   "VB length of the incline up to and down from a tab (a length)"},
};
// clang-format on

#undef GANTRY_MEMBER

}  // namespace

std::string SettingRange::describe() const {
  return fmt::format("{} {} and <= {}", lo_open ? ">" : ">=", lo, hi);
}

std::string SettingRange::docs() const {
  return lo_open ? fmt::format("> {}, <= {}", lo, hi) : fmt::format("{} to {}", lo, hi);
}

std::string SettingRow::path() const {
  return fmt::format("{}.{}", section, key);
}

double SettingRow::fallback() const {
  static const Settings defaults;
  return get(defaults);
}

std::span<const SettingRow> settings_schema() {
  return kRows;
}

std::span<const SettingRow> settings_schema(std::string_view section) {
  const SettingRow* begin = std::find_if(std::begin(kRows), std::end(kRows),
                                         [&](const SettingRow& r) { return r.section == section; });
  const SettingRow* end = std::find_if(begin, std::end(kRows),
                                       [&](const SettingRow& r) { return r.section != section; });
  return {begin, end};
}

const SettingRow& setting_row(std::string_view path) {
  for (const SettingRow& r : kRows)
    if (r.path() == path) return r;
  throw std::out_of_range(fmt::format("no setting {}", path));
}

bool set_setting(Settings& s, const SettingRow& row, double v) {
  if (!row.range.contains(v)) return false;
  row.member(s) = v;
  return true;
}

}  // namespace gantry
