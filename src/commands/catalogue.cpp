// Every other code of the SB3 and FabMo references (shared/spec/commands.md §1), so that a
// part file using one is told by name that Gantry cannot honour it yet, and nothing runs.
#include <fmt/format.h>  // messages

#include <algorithm>  // find
#include <cctype>     // tolower
#include <deque>
#include <string>

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/interpreter.hpp"

namespace gantry {
namespace {

// A catalogued code: what the references say it is, and what to do instead in Gantry.
struct Entry {
  std::string_view code;
  std::string_view name;
  CommandGroup group;
  std::string_view help;
  std::vector<ParamSpec> params;
  std::string_view instead;  // appended to the message; "" when there is nothing to suggest
  std::string_view coverage = "not implemented";
};

ParamSpec num(std::string_view name, std::string_view unit, std::optional<double> def,
              std::string_view help) {
  return {name, unit, false, def, help};
}
ParamSpec text(std::string_view name, std::string_view help) {
  return {name, "", false, std::nullopt, help, ParamKind::Text};
}

// `count` free-form parameters, for codes whose references give no fixed list.
std::vector<ParamSpec> free_params(std::string_view name, int count, std::string_view help) {
  static const std::string names[] = {" 1", " 2", " 3", " 4", " 5", " 6", " 7", " 8"};
  static std::deque<std::string> store;  // the names must outlive the table (deque: stable)
  std::vector<ParamSpec> out;
  for (int i = 0; i < count; ++i) {
    store.push_back(std::string(name) + names[i]);
    out.push_back(text(store.back(), help));
  }
  return out;
}

const std::vector<Entry>& catalogue() {
  using G = CommandGroup;
  static const std::vector<Entry> entries = [] {
    std::vector<Entry> e;
    // Cuts
    e.push_back({"C3",
                 "Homing macro (FabMo)",
                 G::Cuts,
                 "FabMo's shortcut for macro 3, the homing macro. Gantry reads C3 as custom cut 3: "
                 "it runs C3.sbp or macro_3.sbp, or without them the built-in homing on the "
                 "proximity switches; this entry is never dispatched.",
                 {},
                 "",
                 ""});
    // Values
    {
      std::vector<ParamSpec> vn = {
          num("limits on", "", 1.0, "1 limit switches stop the tool."),
          num("stop switch 4 mode", "", 0.0, "0 normally closed."),
          num("accessory enable", "", 0.0, "Enables VH (torch, laser, analog).")};
      for (ParamSpec& p : free_params("input mode", 8, "Mode of an input (SB3 positions unclear)."))
        vn.push_back(p);
      for (ParamSpec& p :
           free_params("output mode", 8, "Mode of an output (SB3 positions unclear)."))
        vn.push_back(p);
    }
    {
      std::vector<ParamSpec> vr;
      for (const char* n :
           {"XY move ramp speed", "Z move ramp speed", "A move ramp speed", "B move ramp speed",
            "XY jog ramp speed", "Z jog ramp speed", "A jog ramp speed", "B jog ramp speed"})
        vr.push_back(num(n, "units/s", 0.4, "Start and end speed of a ramp."));
      vr.push_back(num("move ramp rate", "units", 0.2, "Distance to change move speed by 2."));
      vr.push_back(num("jog ramp rate", "units", 0.2, "Distance to change jog speed by 2."));
      vr.push_back(num("3D threshold", "%", 100.0, "3D ramping sensitivity."));
      vr.push_back(num("minimum distance", "units", 0.15, "Shortest move considered."));
      vr.push_back(num("slow corner", "%", 65.0, "Speed cut at a slight corner."));
      vr.push_back(num("obsolete", "", std::nullopt, "Leave blank."));
      vr.push_back(num("obsolete", "", std::nullopt, "Leave blank."));
      vr.push_back(num("keypad ramp rate", "units", 0.2, "Ramp rate of the keypad."));
      vr.push_back(num("small circle", "units", 0.25, "Circles below this run at ramp speed."));
    }
    // Zero
    return e;
  }();
  return entries;
}

// Says which code cannot run, by name, and what to do instead; nothing else happens.
void not_implemented(CommandContext&, const CommandCall& call) {
  const Entry* entry = nullptr;
  for (const Entry& e : catalogue())
    if (e.code == call.spec.code) entry = &e;
  std::string name(call.spec.name);
  if (!name.empty()) name[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(name[0])));
  std::string message =
      fmt::format("{} ({}) is not implemented yet in Gantry", call.spec.code, name);
  if (entry && !entry->instead.empty()) message += fmt::format("; {}", entry->instead);
  fail(call.loc, message);
}

}  // namespace

void add_catalogue_commands(std::vector<CommandSpec>& out,
                            const std::vector<CommandSpec>& implemented) {
  // Copied first: `implemented` may be `out` itself, which push_back may reallocate.
  std::vector<std::string_view> have;
  for (const CommandSpec& s : implemented) have.push_back(s.code);
  for (const Entry& e : catalogue()) {
    if (std::find(have.begin(), have.end(), e.code) != have.end()) continue;
    out.push_back({e.code, e.name, e.group, e.help, e.params, not_implemented, e.coverage});
  }
}

}  // namespace gantry
