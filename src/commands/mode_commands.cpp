// Modal commands: distance mode (SA, SR) and speeds (MS, JS, VS).
#include <fmt/format.h>  // messages

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"
#include "gantry/interp/value.hpp"              // format_number
#include "gantry/settings/settings_schema.hpp"  // the speeds' rows: their range; a bare VS
#include "values_display.hpp"                   // a bare VS

namespace gantry {
namespace {

void set_absolute(CommandContext& ctx, const CommandCall&) {
  ctx.state().absolute = true;
}
void set_relative(CommandContext& ctx, const CommandCall&) {
  ctx.state().absolute = false;
}

// The five speed groups in parameter order, with the axis limit each must respect.
struct GroupRef {
  double GroupSpeeds::*field;
  const char* name;
};
constexpr GroupRef kGroups[] = {{&GroupSpeeds::xy, "XY"},
                                {&GroupSpeeds::z, "Z"},
                                {&GroupSpeeds::a, "A"},
                                {&GroupSpeeds::b, "B"},
                                {&GroupSpeeds::c, "C"}};

// Applies values[first .. first+count) to `speeds`, group by group; blanks keep the old speed.
void apply_speeds(CommandContext& ctx, const CommandCall& call, size_t first, size_t count,
                  GroupSpeeds& speeds, SpeedClass cls, bool by_values) {
  const Settings& s = ctx.settings();
  const SettingRow& row =
      settings_schema(cls == SpeedClass::Move ? "speeds.move" : "speeds.jog").front();
  for (size_t g = 0; g < count; ++g) {
    const std::optional<double> v = call.number(first + g);
    if (!v) continue;
    const SettingRange range = row.range_in(s, static_cast<int>(g));  // (0, axis max_speed]
    if (!range.contains(*v))
      fail(call.param_loc(first + g),
           fmt::format("{} speed {} is out of range; allowed: above 0 and up to {} {}/s (the "
                       "axis max_speed in the profile)",
                       kGroups[g].name, *v, range.hi, units_name(s.units)));
  }
  for (size_t g = 0; g < count; ++g)
    if (const std::optional<double> v = call.number(first + g)) {
      speeds.*kGroups[g].field = *v;
      ctx.speed_set(cls, static_cast<int>(g), by_values);
    }
}

// MS and JS punctuate the moves around them: the machine ramps down to rest before the new
// speed and up again after it (SB3's rule; VS changes speed without stopping).
void set_move_speed(CommandContext& ctx, const CommandCall& call) {
  apply_speeds(ctx, call, 0, 5, ctx.state().speeds.move, SpeedClass::Move, false);
  ctx.come_to_rest(call.loc);
}
void set_jog_speed(CommandContext& ctx, const CommandCall& call) {
  apply_speeds(ctx, call, 0, 5, ctx.state().speeds.jog, SpeedClass::Jog, false);
  ctx.come_to_rest(call.loc);
}
// VS: move XY, Z, A, B, then jog XY, Z, A, B (SB3); FabMo adds C to each group.
void set_speeds(CommandContext& ctx, const CommandCall& call) {
  const size_t groups = ctx.settings().dialect == Dialect::FabMo ? 5 : 4;
  if (shows_values(ctx, call)) {
    // The speeds in force (a file's VS, MS or JS changed them), read through the schema's
    // speeds.move and speeds.jog rows, in VS's order: move XY, Z, A, B, then jog.
    Settings now = ctx.settings();
    now.speeds = ctx.state().speeds;
    const std::vector<ParamSpec>& params = call.spec.params_for(ctx.settings().dialect);
    std::vector<ShownValue> shown;
    for (std::string_view section : {"speeds.move", "speeds.jog"})
      for_each_setting([&](const SettingRow& row, int g) {
        if (row.section != section || static_cast<size_t>(g) >= groups) return true;
        const int axis = setting_axis(row.family, g);
        const bool deg = axis >= 3 && now.display.rotary_units[axis - 3] == AxisUnit::Degrees;
        shown.push_back({shown.size() + 1, &params[shown.size()],
                         format_number(row.get(now, g)), deg ? "deg/s" : ""});
        return true;
      });
    return ctx.print(values_listing(call.spec, shown, now));
  }
  // Validate every value before changing any: a bad VS changes nothing.
  SpeedSettings next = ctx.state().speeds;
  apply_speeds(ctx, call, 0, groups, next.move, SpeedClass::Move, true);
  apply_speeds(ctx, call, groups, groups, next.jog, SpeedClass::Jog, true);
  ctx.state().speeds = next;
}

// Speed parameters for the groups XY, Z, A, B (and C), named for `suffix` ("", "move" or "jog").
std::vector<ParamSpec> speed_params(std::string_view suffix, int groups) {
  static constexpr std::string_view help[] = {"Vector speed of the cutter tip in XY.",
                                              "Speed of the Z axis.", "Speed of the A axis.",
                                              "Speed of the B axis.", "Speed of the C axis."};
  static const std::string names[2][5] = {
      {"XY speed", "Z speed", "A speed", "B speed", "C speed"},
      {"XY move speed", "Z move speed", "A move speed", "B move speed", "C move speed"}};
  static const std::string jog_names[] = {"XY jog speed", "Z jog speed", "A jog speed",
                                          "B jog speed", "C jog speed"};
  const std::string* row = suffix == "" ? names[0] : suffix == "move" ? names[1] : jog_names;
  std::vector<ParamSpec> out;
  for (int g = 0; g < groups; ++g) out.push_back({row[g], "units/s", false, std::nullopt, help[g]});
  return out;
}

}  // namespace

void add_mode_commands(std::vector<CommandSpec>& out) {
  const auto S = CommandGroup::Settings;
  out.push_back({"SA",
                 "Set to absolute distances",
                 S,
                 "Locations in move commands are measured from the 0,0 point.",
                 {},
                 set_absolute});
  out.push_back({"SR",
                 "Set to relative distances",
                 S,
                 "Locations in move commands are distances from the current position.",
                 {},
                 set_relative});
  out.push_back({"MS", "Move speed", CommandGroup::Move,
                 "Sets the move (cutting) speeds; a blank keeps that speed. In a file it ends "
                 "the current run of moves (the tool slows to change speed); VS does not.",
                 speed_params("", 5), set_move_speed});
  out.push_back({"JS", "Jog speed", CommandGroup::Jog,
                 "Sets the jog (rapid) speeds; a blank keeps that speed.", speed_params("", 5),
                 set_jog_speed});
  auto vs = [](int groups) {
    std::vector<ParamSpec> out = speed_params("move", groups);
    for (ParamSpec& p : speed_params("jog", groups)) out.push_back(p);
    return out;
  };
  out.push_back({"VS", "Values for speeds", CommandGroup::Values,
                 "Sets move and jog speeds together without interrupting motion. In a part "
                 "file they last until the file ends, unless SV.",
                 vs(4), set_speeds, "", vs(5)});
}

}  // namespace gantry
