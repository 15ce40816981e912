// Move commands that are not plain moves: MN (nudge the tool, keeping its location) and MI
// (an axis turning or oscillating on its own), which this machine cannot honour.
#include <fmt/format.h>  // messages

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/interpreter.hpp"

namespace gantry {
namespace {

// MN: the tool moves by the given distances while its working location stays what it was:
// the working zero moves with it, so what follows (the rest of a stopped part file, say) is
// shifted by the nudge. Table base coordinates follow the tool, so ST gives back the true
// location. SB3's panel of nudge buttons becomes one distance per axis.
void nudge(CommandContext& ctx, const CommandCall& call) {
  Vec6 by = Vec6::Zero();
  for (int i = 0; i < kAxisCount; ++i) by[i] = call.number(static_cast<size_t>(i)).value_or(0.0);
  if (by.isZero(0)) {
    ctx.print(
        "MN: no distance given, nothing moved; MN, 0.01 nudges the tool 0.01 along X and "
        "keeps its X location\n");
    return;
  }
  ModalState& st = ctx.state();
  const ModalState before = st;
  const Vec6 here = ctx.position();  // the location to keep, in the file's coordinates
  st.zero += by;
  st.position -= by;
  try {
    ctx.line_to(here, SpeedClass::Move, call.loc);
  } catch (const GantryError&) {
    st = before;  // outside the soft limits: nothing moved, nothing changed
    throw;
  }
  st.last_xy_move = before.last_xy_move;  // MD's heading is the last real move's
}

// MI: refused by name, with the reason; nothing else happens.
void independent_axis(CommandContext&, const CommandCall& call) {
  fail(call.loc,
       "MI (move indexer or oscillate) cannot run on this machine: it keeps one axis turning "
       "or oscillating on its own while other commands move the rest, and Gantry plans every "
       "axis along one path, with no second motion stream beside it; nothing was done. Put "
       "the rotary turns into the moves themselves (M4, M5), or write the oscillation as Z "
       "moves");
}

ParamSpec distance(std::string_view name, std::string_view help) {
  return {name, "units", false, 0.0, help};
}

}  // namespace

void add_nudge_commands(std::vector<CommandSpec>& out) {
  const auto M = CommandGroup::Move;
  std::vector<ParamSpec> by;
  for (std::string_view n : {"X nudge", "Y nudge", "Z nudge", "A nudge", "B nudge", "C nudge"})
    by.push_back(distance(n, "How far the tool moves along the axis; its location stays."));
  out.push_back({"MN",
                 "Move nudge",
                 M,
                 "Moves the tool a little at move speed while its location stays the same: the "
                 "working zero moves with the tool, so later moves are shifted by the nudge. "
                 "Table base coordinates follow the tool; ST returns to them. Blank is 0.",
                 by,
                 nudge,
                 "",
                 {},
                 false,
                 "%(6)-%(10)"});
  out.push_back(
      {"MI",
       "Move indexer or oscillate",
       M,
       "SB3 starts an axis turning (indexer) or oscillating on its own, beside the other "
       "moves, until it is turned off. Gantry cannot run an axis outside the planned path: "
       "MI says so and does nothing.",
       {{"axis", "", false, std::nullopt, "Axis letter (SB3: B).", ParamKind::Text},
        {"direction", "", false, std::nullopt, "1 clockwise (SB3's default)."},
        {"rotary speed", "units/s", false, std::nullopt, "How fast the axis turns."},
        {"frequency", "Hz", false, std::nullopt, "Oscillations per second."},
        {"distance", "units", false, std::nullopt, "Oscillation travel."}},
       independent_axis,
       "not implemented"});
}

}  // namespace gantry
