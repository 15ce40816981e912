// File commands: FP runs another part file as a subroutine.
#include <fmt/format.h>  // messages

#include <cmath>  // round

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/interpreter.hpp"

namespace gantry {
namespace {

void file_part(CommandContext& ctx, const CommandCall& call) {
  FileCall fc;
  fc.path = *call.text(0);
  fc.proportion[0] = *call.number(1);
  fc.proportion[1] = *call.number(2);
  fc.proportion[2] = *call.number(3);
  for (size_t i = 1; i <= 3; ++i)
    if (!(*call.number(i) > 0))
      fail(call.param_loc(i), "FP proportions must be above 0 (1 keeps the file's size)");
  const double reps = *call.number(4);
  if (reps != std::round(reps) || reps < 1 || reps > 1e6)
    fail(call.param_loc(4), "FP repetitions must be a whole number, 1 or more");
  fc.repetitions = static_cast<int>(reps);
  const double offset = *call.number(5);
  if (offset != 0 && offset != 1 && offset != 2)
    fail(call.param_loc(5), "FP offset is 0 (none), 1 (3D: X, Y, Z from here) or 2 (2D)");
  fc.offset = static_cast<int>(offset);
  fc.plunge = *call.number(6);
  if (*call.number(7) != 0)
    fail(call.param_loc(7),
         "FP's tab feature needs tabbing (VB), which Gantry does not offer "
         "yet; leave parameter 8 blank");
  if (*call.number(8) != 0)
    fail(call.param_loc(8),
         "FP's plunge from Z 0 (parameter 9) is not offered yet; move Z to 0 "
         "before FP instead");
  ctx.call_file(fc, call.loc);
}

}  // namespace

void add_file_commands(std::vector<CommandSpec>& out) {
  const auto F = CommandGroup::File;
  out.push_back(
      {"FP",
       "File: run a part file",
       F,
       "Runs another part file, then continues on the next line. Variables are shared; the file "
       "may be scaled, repeated, and placed relative to the current position.",
       {{"file name", "", true, std::nullopt,
         "The part file; a relative name is found in the parts folder (the top-level file's).",
         ParamKind::Text},
        {"proportion X", "", false, 1.0, "Scale of X."},
        {"proportion Y", "", false, 1.0, "Scale of Y."},
        {"proportion Z", "", false, 1.0, "Scale of Z."},
        {"repetitions", "", false, 1.0, "How many times the file runs."},
        {"offset", "", false, 0.0, "0 none; 1 3D: X, Y, Z start from here; 2 2D: X, Y from here."},
        {"plunge", "units", false, 0.0, "Z added at each repetition (negative goes down)."},
        {"tab feature", "", false, 0.0, "1 adds tabs on the last pass (not offered yet)."},
        {"plunge from Z 0", "", false, 0.0, "1 plunges from Z 0 (not offered yet)."}},
       file_part,
       "tabs (parameter 8) and plunge from Z 0 (parameter 9)"});
}

}  // namespace gantry
