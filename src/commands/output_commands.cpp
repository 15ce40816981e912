// Output switches: SO, and MO (M0) which turns them all off.
#include <fmt/format.h>  // messages

#include <cmath>  // trunc

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/interpreter.hpp"

namespace gantry {
namespace {

// SO switch, state: the switch goes on or off with the machine at rest between the moves
// around it; every switch goes off when the job ends.
void set_output_switch(CommandContext& ctx, const CommandCall& call) {
  const double n = *call.number(0);
  const std::vector<int>& wired = ctx.settings().outputs.aux_bits;
  if (n != std::trunc(n) || n < 1 || n > 12)
    fail(call.param_loc(0),
         fmt::format("output switch {} does not exist; switches are 1 to 12", n));
  const double state = call.number(1).value_or(0);  // blank: off, as SB3 says
  if (state < 0 && n == 4)
    fail(call.param_loc(1),
         "switch 4's automatic modes (-1 to -4: on while the tool moves) are not supported; "
         "use SO, 4, 1 and SO, 4, 0 around the moves");
  if (state != 0 && state != 1)
    fail(call.param_loc(1), fmt::format("SO state {} is not 0 (off) or 1 (on)", state));
  const int k = static_cast<int>(n);
  if (k > static_cast<int>(wired.size()) || wired[k - 1] < 0)
    fail(call.param_loc(0),
         fmt::format("output switch {} is not wired in this profile (outputs.aux_bits wires {}); "
                     "nothing was switched",
                     k, wired.size()));
  ctx.set_output(k, state == 1, call.loc);
}

// MO / M0: every output switch off with the machine at rest. Motor power follows the
// charge pump, which stops whenever no pulses flow: the drives are off at rest already.
void motors_off(CommandContext& ctx, const CommandCall& call) {
  ctx.come_to_rest(call.loc);
  for (int n = 1; n <= 12; ++n)
    if (ctx.state().outputs & (1u << (n - 1))) ctx.set_output(n, false, call.loc);
}

}  // namespace

void add_output_commands(std::vector<CommandSpec>& out) {
  out.push_back({"SO",
                 "Set output switch",
                 CommandGroup::Settings,
                 "Turns an output switch on or off. The machine comes to rest first, so the "
                 "switch changes between the moves around it; all switches go off when the "
                 "job ends.",
                 {{"switch", "", true, std::nullopt, "Output switch number, 1 to 12."},
                  {"state", "", false, 0.0, "1 turns it on, 0 (or blank) off."}},
                 set_output_switch,
                 "switch 4's automatic modes (SO, 4, -1 to -4)"});
  for (std::string_view code : {"MO", "M0"})
    out.push_back({code,
                   "Motors off",
                   CommandGroup::Move,
                   "Stops at rest and turns every output switch off. The drives lose their "
                   "enable with the charge pump, which only runs while pulses flow.",
                   {},
                   motors_off,
                   "",
                   {},
                   true});
}

}  // namespace gantry
