// Move commands that are not plain moves: MN (nudge the tool, keeping its location) and MI
// (an axis turning or oscillating on its own beside the path).
#include <fmt/format.h>  // messages

#include <algorithm>  // find, min
#include <cctype>     // tolower, toupper
#include <cmath>      // sqrt, M_PI

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

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

// MI: one axis turns (a rotary speed) or oscillates (a frequency and a distance) on its own
// while the part file's moves run; with neither it stops. AMB-30 and the rest of the
// decisions: docs/commands.md, "MI".
void independent_axis(CommandContext& ctx, const CommandCall& call) {
  const std::string word = call.text(0).value_or("B");
  const char letter = static_cast<char>(std::tolower(static_cast<unsigned char>(word[0])));
  const int axis = static_cast<int>(std::find(kAxisLetters.begin(), kAxisLetters.end(), letter) -
                                    kAxisLetters.begin());
  const char name = static_cast<char>(std::toupper(kAxisLetters[axis]));
  const double sign = call.number(1).value_or(1) > 0 ? 1 : -1;
  const double speed = call.number(2).value_or(0), frequency = call.number(3).value_or(0);
  const double travel = call.number(4).value_or(0);
  const ModalState& st = ctx.state();
  if (speed == 0 && frequency == 0) {
    if (st.independent && st.independent->axis == axis) return ctx.end_independent(call.loc);
    ctx.print(fmt::format("MI: {} is not moving on its own; nothing to stop\n", name));
    return;
  }
  if (!ctx.in_file())
    fail(call.loc,
         "MI moves an axis beside the moves of a part file and stops when the file ends: typed "
         "alone it would stop again at once, so nothing was done. Put MI in the part file, "
         "before the moves it goes with");
  if (st.independent && st.independent->axis != axis)
    fail(call.param_loc(0),
         fmt::format("{} moves on its own already (line {}), and MI moves one axis at a time; "
                     "stop it first with MI, {}",
                     static_cast<char>(std::toupper(kAxisLetters[st.independent->axis])),
                     st.independent_loc.line,
                     static_cast<char>(std::toupper(kAxisLetters[st.independent->axis]))));
  if (speed > 0 && frequency > 0)
    fail(call.param_loc(3),
         "give a rotary speed to turn the axis, or a frequency and a distance to oscillate it, "
         "not both");
  const AxisSettings& ax = ctx.settings().axes[axis];
  const char* unit = units_name(ctx.settings().units);
  IndependentMotion m;
  m.axis = axis;
  if (speed > 0) {
    if (axis < 3)
      fail(call.param_loc(0),
           fmt::format("{} is a linear axis: turning on its own it would run into its end; MI "
                       "turns A, B or C, and oscillates any axis",
                       name));
    if (speed > ax.max_speed)
      fail(call.param_loc(2),
           fmt::format("rotary speed {} is above {}'s limit of {} per second (axes.{}.max_speed)",
                       speed, name, ax.max_speed, kAxisLetters[axis]));
    m.speed = sign * speed;
    m.accel = ax.max_accel;
  } else {
    if (!(travel * ax.steps_per_unit >= 1))
      fail(call.param_loc(4),
           fmt::format("an oscillation needs a distance of at least one step ({:.6f} {})",
                       1 / ax.steps_per_unit, unit));
    // Peak speed pi f d and acceleration 2 pi^2 f^2 d (see IndependentAxis).
    const double most = std::min(ax.max_speed / (M_PI * travel),
                                 std::sqrt(ax.max_accel / (2 * M_PI * M_PI * travel)));
    if (frequency > most)
      fail(call.param_loc(3),
           fmt::format("{} Hz over {} {} is beyond {}'s speed or acceleration limit "
                       "(axes.{}.max_speed, max_accel); at most {:.2f} Hz for that distance",
                       frequency, travel, unit, name, kAxisLetters[axis], most));
    Vec6 far = ctx.transform().to_machine(ctx.position());
    far[axis] += sign * travel;
    ctx.check_reach(ctx.transform().to_file(far), call.loc);
    m.frequency = frequency;
    m.travel = sign * travel;
  }
  ctx.end_independent(call.loc);  // a new motion of the same axis replaces the old one
  ctx.start_independent(m, call.loc);
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
       "Starts one axis moving on its own while the part file's moves run: turning at a "
       "rotary speed (A, B or C: an indexer) or oscillating out by a distance and back at a "
       "frequency (any axis). MI with no speed and no frequency stops it; the file's end "
       "stops it too. While it runs no move may move that axis. It rests whenever the "
       "machine does to wait (a pause, SK, a probe, an input read) and starts again with the "
       "next move.",
       {ParamSpec{"axis", "", false, std::nullopt, "Axis letter; blank is B (SB3's default).",
                  ParamKind::Text}
            .one_of("X Y Z A B C"),
        ParamSpec{"direction", "", false, 1.0,
                  "1 (SB3: clockwise) turns the positive way, 0 or -1 the other; an "
                  "oscillation swings to that side of where it starts."}
            .integer(-1, 1),
        ParamSpec{"rotary speed", "units/s", false, std::nullopt,
                  "How fast the axis turns; at most its max_speed. Blank to oscillate."}
            .at_least(0),
        ParamSpec{"frequency", "Hz", false, std::nullopt, "Oscillations per second; blank to turn."}
            .at_least(0),
        ParamSpec{"distance", "units", false, std::nullopt,
                  "How far the oscillation swings out from where it starts."}
            .at_least(0)},
       independent_axis,
       "runs within a part file only (typed alone it is refused: it would stop with the "
       "line); it rests while the machine waits and at the file's end, rather than running "
       "on until turned off"});
}

}  // namespace gantry
