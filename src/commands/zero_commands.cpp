// Zero commands: the current location of some axes becomes working 0 (Z2, Z3, ZX, ...).
#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

namespace gantry {
namespace {

constexpr unsigned kX = 1, kY = 2, kZ = 4, kA = 8, kB = 16, kC = 32;

template <unsigned Axes>
void zero(CommandContext& ctx, const CommandCall&) {
  ctx.zero_axes(Axes);
}

constexpr unsigned kAll = kX | kY | kZ | kA | kB | kC;

// ZT: the tool's position becomes table base 0; working values keep their numbers.
void zero_table_base(CommandContext& ctx, const CommandCall&) {
  ctx.set_table_base(kAll, Vec6::Zero());
}

// UZ: working locations and table base both 0 here.
void zero_everything(CommandContext& ctx, const CommandCall&) {
  ctx.set_table_base(kAll, Vec6::Zero());
  ctx.zero_axes(kAll);
}

// ST: working coordinates become table base coordinates again (offsets removed).
void to_table_base(CommandContext& ctx, const CommandCall&) {
  ModalState& st = ctx.state();
  st.position += st.zero;
  st.zero = Vec6::Zero();
}

}  // namespace

// SB3 documents ZX ZY ZZ ZA ZB and Z2-Z5 (AMB-28: Z3 = X, Y, Z; Z4 adds A); FabMo adds ZC
// and Z6. The table base location does not change: only where working 0 is.
void add_zero_commands(std::vector<CommandSpec>& out) {
  const auto Z = CommandGroup::Zero;
  out.push_back({"ZX", "Zero X axis", Z, "The current X location becomes X 0.", {}, zero<kX>});
  out.push_back({"ZY", "Zero Y axis", Z, "The current Y location becomes Y 0.", {}, zero<kY>});
  out.push_back({"ZZ", "Zero Z axis", Z, "The current Z location becomes Z 0.", {}, zero<kZ>});
  out.push_back({"ZA", "Zero A axis", Z, "The current A location becomes A 0.", {}, zero<kA>});
  out.push_back({"ZB", "Zero B axis", Z, "The current B location becomes B 0.", {}, zero<kB>});
  out.push_back({"ZC", "Zero C axis", Z, "The current C location becomes C 0.", {}, zero<kC>});
  out.push_back(
      {"Z2", "Zero X and Y", Z, "The current X and Y locations become 0.", {}, zero<kX | kY>});
  out.push_back({"Z3",
                 "Zero X, Y and Z",
                 Z,
                 "The current X, Y and Z locations become 0.",
                 {},
                 zero<kX | kY | kZ>});
  out.push_back({"Z4",
                 "Zero X, Y, Z and A",
                 Z,
                 "The current X, Y, Z and A locations become 0.",
                 {},
                 zero<kX | kY | kZ | kA>});
  out.push_back({"Z5",
                 "Zero X, Y, Z, A and B",
                 Z,
                 "The current X, Y, Z, A and B locations become 0.",
                 {},
                 zero<kX | kY | kZ | kA | kB>});
  out.push_back({"Z6",
                 "Zero all six axes",
                 Z,
                 "The current locations of all axes become 0.",
                 {},
                 zero<kAll>});
  out.push_back({"ZT",
                 "Zero table base coordinates",
                 Z,
                 "The current position becomes table base 0 on every axis; nothing moves, "
                 "working locations keep their values, and the soft limits (table base) move "
                 "with it.",
                 {},
                 zero_table_base,
                 "",
                 {},
                 true,
                 "%(6)-%(10)"});
  out.push_back({"UZ",
                 "Zero working and table base locations",
                 CommandGroup::Utilities,
                 "The current position becomes 0 in working and table base coordinates on "
                 "every axis.",
                 {},
                 zero_everything,
                 "",
                 {},
                 true,
                 "%(1)-%(10)"});
  out.push_back({"ST",
                 "Set working to table base coordinates",
                 CommandGroup::Settings,
                 "Removes the working offsets: locations read in table base coordinates again.",
                 {},
                 to_table_base,
                 "",
                 {},
                 true,
                 "%(1)-%(5)"});
}

}  // namespace gantry
