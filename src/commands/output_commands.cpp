// Output switches: SO, and MO (M0) which turns them all off; TR, the spindle's speed.
#include <fmt/format.h>  // messages

#include <cmath>  // trunc

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

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
  if (n == 4 && (state == -1 || state == -2 || state == -3 || state == -4)) {
    // Kept for good, like SW: it says what switch 4 is wired to.
    ctx.change_values(ValueScope::Permanent).machine.switch4_mode = static_cast<int>(state);
    return;
  }
  if (state != 0 && state != 1)
    fail(call.param_loc(1),
         n == 4 ? fmt::format("SO state {} is not 0 (off), 1 (on) or an automatic mode -1 to -4",
                              state)
                : fmt::format("SO state {} is not 0 (off) or 1 (on); only switch 4 has "
                              "automatic modes (-1 to -4)",
                              state));
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

// TR rpm: the speed the spindle (output switch 1, which C6 and C7 switch) runs at. CAM posts
// write it before C6 at every tool.
void spindle_speed(CommandContext& ctx, const CommandCall& call) {
  const double rpm = *call.number(0);
  const SpindleSettings& spindle = ctx.settings().spindle;
  if (spindle.speed_output() && rpm > spindle.max_rpm)
    fail(call.param_loc(0),
         fmt::format("TR {} RPM is faster than this spindle runs ({} RPM, spindle.max_rpm); "
                     "nothing was changed",
                     format_number(rpm), format_number(spindle.max_rpm)));
  ctx.set_spindle_speed(rpm, call.loc);
}

}  // namespace

void add_output_commands(std::vector<CommandSpec>& out) {
  out.push_back({"SO",
                 "Set output switch",
                 CommandGroup::Settings,
                 "Turns an output switch on or off. The machine comes to rest first, so the "
                 "switch changes between the moves around it; all switches go off when the "
                 "job ends. Switch 4 also comes on by itself while a run moves the tool "
                 "(from SW's warning to the run's end) unless SO, 4, -4 makes it an "
                 "ordinary switch; SO, 4, -1 turns that back on.",
                 {{"switch", "", true, std::nullopt, "Output switch number, 1 to 12."},
                  {"state", "", false, 0.0,
                   "1 turns it on, 0 (or blank) off. Switch 4 only: -1, -2 or -3 on while the "
                   "tool moves (the default), -4 not."}},
                 set_output_switch});
  out.push_back(
      {"TR",
       "Tools: spindle speed (RPM)",
       CommandGroup::Tools,
       "Sets the spindle's speed in RPM; output switch 1 (C6, C7) switches the spindle on and "
       "off. Where the profile has a speed output, it carries rpm / max_rpm between the moves "
       "around TR: as a PWM duty on [spindle] pwm_bit (or, with speed_mode \"frequency\", a "
       "pulse rate rpm / max_rpm x max_hz), or as a D/A word on dac_bits; otherwise the speed "
       "is recorded and the run "
       "warns once that the spindle keeps the speed set on it. A change while the spindle "
       "runs waits for the profile's at-speed input, where it has one. %(161) reads the speed "
       "while the spindle runs.",
       {ParamSpec{"speed", "RPM", true, std::nullopt,
                  "Spindle speed, at most spindle.max_rpm where a speed output is wired."}
            .at_least(0),
        ParamSpec{"spindle", "", false, 1.0, "FabMo's spindle number; Gantry drives one (1)."}
            .integer(1, 1)},
       spindle_speed,
       "one spindle; its speed as a PWM duty or a pulse rate on an output bit, not over a VFD's "
       "serial link",
       {},
       false,
       "%(161)"});
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
