// What a bare value command (VS, VC, VR ... typed alone at a console) shows: the values in
// force, each read through its settings-schema row.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandCall, ParamSpec
#include "gantry/interp/command_context.hpp"   // CommandContext

namespace gantry {

struct SettingRow;

// A value command with no parameter at all, typed at a console (or played as typed): it
// shows the values. In a part file a bare one changes nothing and shows nothing, as before.
inline bool shows_values(const CommandContext& ctx, const CommandCall& call) {
  return call.args.empty() && !ctx.in_file();
}

// One parameter shown: its number (1-based), the sheet's name and unit, and its value.
struct ShownValue {
  std::size_t number = 0;
  const ParamSpec* param = nullptr;
  std::string value;
  std::string unit = {};  // empty: the parameter's, "units" read as in or mm
};

// Setting `row` (family index or list item `i`) as the command takes it back: numbers as
// written, a choice by its name ("mm", "-"), a channel by its axis letter.
std::string setting_value_text(const SettingRow& row, const Settings& s, int i);

// "VS, values for speeds (in force):" and a line per parameter: "   1  XY move speed   2 in/s"
// (the sheet's "units" read as in or mm).
std::string values_listing(const CommandSpec& spec, const std::vector<ShownValue>& values,
                           const Settings& s);

}  // namespace gantry
