// Straight moves at move speed (M…) and jog speed (J…) on one to six axes.
#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

namespace gantry {
namespace {

// One handler per axis list: parameter i is the location (SA) or distance (SR) of the i-th
// axis. A blank parameter leaves that axis where it is.
template <SpeedClass Class, Axis... Axes>
void move_axes(CommandContext& ctx, const CommandCall& call) {
  const Vec6 here = ctx.position();
  const bool absolute = ctx.state().absolute;
  Vec6 target = here;
  size_t i = 0;
  for (Axis a : {Axes...}) {
    if (const std::optional<double> v = call.number(i++)) {
      target[index(a)] = absolute ? *v : here[index(a)] + *v;
    }
  }
  ctx.line_to(target, Class, call.loc);
}

// MH / JH: up to Safe-Z first when the tool is below it, then to working X 0, Y 0 (SA or SR
// alike). SB3 does not say how fast the Z leg goes (AMB-9): both legs use the command's class.
template <SpeedClass Class>
void go_home(CommandContext& ctx, const CommandCall& call) {
  Vec6 at = ctx.position();
  const double safe_z = ctx.settings().cutter.safe_z;
  if (at[2] < safe_z) {
    at[2] = safe_z;
    ctx.line_to(at, Class, call.loc);
  }
  at[0] = at[1] = 0;
  ctx.line_to(at, Class, call.loc);
}

// Parameters named after each letter of `axes` ("XYZ"), in part-file order.
std::vector<ParamSpec> axis_params(std::string_view axes, bool required) {
  static const std::string names[] = {"X location", "Y location", "Z location",
                                      "A location", "B location", "C location"};
  static constexpr std::string_view letters = "XYZABC";
  std::vector<ParamSpec> out;
  for (char a : axes)
    out.push_back({names[letters.find(a)], "units", required, std::nullopt,
                   "Where the axis goes (SA), or how far it moves (SR)."});
  return out;
}

}  // namespace

void add_move_commands(std::vector<CommandSpec>& out) {
  using enum SpeedClass;
  using enum Axis;
  const auto M = CommandGroup::Move;
  const auto J = CommandGroup::Jog;
  const char* single_move = "Moves one axis at move (cutting) speed.";
  const char* single_jog = "Moves one axis at jog (rapid) speed.";
  const char* multi_move =
      "Moves several axes together in a straight line at move speed; a blank parameter "
      "keeps that axis where it is.";
  const char* multi_jog =
      "Moves several axes together in a straight line at jog speed; a blank parameter keeps "
      "that axis where it is.";
  out.push_back({"MX", "Move X axis", M, single_move, axis_params("X", true), move_axes<Move, X>});
  out.push_back({"MY", "Move Y axis", M, single_move, axis_params("Y", true), move_axes<Move, Y>});
  out.push_back({"MZ", "Move Z axis", M, single_move, axis_params("Z", true), move_axes<Move, Z>});
  out.push_back({"MA", "Move A axis", M, single_move, axis_params("A", true), move_axes<Move, A>});
  out.push_back({"MB", "Move B axis", M, single_move, axis_params("B", true), move_axes<Move, B>});
  out.push_back(
      {"M2", "Move 2 dimensions", M, multi_move, axis_params("XY", false), move_axes<Move, X, Y>});
  out.push_back({"M3", "Move 3 dimensions", M, multi_move, axis_params("XYZ", false),
                 move_axes<Move, X, Y, Z>});
  out.push_back({"M4", "Move 4 dimensions", M, multi_move, axis_params("XYZA", false),
                 move_axes<Move, X, Y, Z, A>});
  out.push_back({"M5", "Move 5 dimensions", M, multi_move, axis_params("XYZAB", false),
                 move_axes<Move, X, Y, Z, A, B>});
  out.push_back({"M6", "Move 6 dimensions", M, multi_move, axis_params("XYZABC", false),
                 move_axes<Move, X, Y, Z, A, B, C>});
  out.push_back({"MC", "Move C axis", M, single_move, axis_params("C", true), move_axes<Move, C>});
  out.push_back({"JX", "Jog X axis", J, single_jog, axis_params("X", true), move_axes<Jog, X>});
  out.push_back({"JY", "Jog Y axis", J, single_jog, axis_params("Y", true), move_axes<Jog, Y>});
  out.push_back({"JZ", "Jog Z axis", J, single_jog, axis_params("Z", true), move_axes<Jog, Z>});
  out.push_back({"JA", "Jog A axis", J, single_jog, axis_params("A", true), move_axes<Jog, A>});
  out.push_back({"JB", "Jog B axis", J, single_jog, axis_params("B", true), move_axes<Jog, B>});
  out.push_back(
      {"J2", "Jog 2 dimensions", J, multi_jog, axis_params("XY", false), move_axes<Jog, X, Y>});
  out.push_back(
      {"J3", "Jog 3 dimensions", J, multi_jog, axis_params("XYZ", false), move_axes<Jog, X, Y, Z>});
  out.push_back({"J4", "Jog 4 dimensions", J, multi_jog, axis_params("XYZA", false),
                 move_axes<Jog, X, Y, Z, A>});
  out.push_back({"J5", "Jog 5 dimensions", J, multi_jog, axis_params("XYZAB", false),
                 move_axes<Jog, X, Y, Z, A, B>});
  out.push_back({"J6", "Jog 6 dimensions", J, multi_jog, axis_params("XYZABC", false),
                 move_axes<Jog, X, Y, Z, A, B, C>});
  out.push_back({"JC", "Jog C axis", J, single_jog, axis_params("C", true), move_axes<Jog, C>});
  out.push_back({"MH",
                 "Move home",
                 M,
                 "Raises Z to Safe-Z ([cutter] safe_z, VC) if it is below it, then moves to X 0, "
                 "Y 0; both at move speed. SR does not apply.",
                 {},
                 go_home<Move>});
  out.push_back({"JH",
                 "Jog home",
                 J,
                 "Raises Z to Safe-Z ([cutter] safe_z, VC) if it is below it, then jogs to X 0, "
                 "Y 0; both at jog speed. SR does not apply.",
                 {},
                 go_home<Jog>});
}

}  // namespace gantry
