// The spindle's on, off and direction (M3, M4, M5; SO and C6/C7 on its outputs), with the
// profile's spin-up and spin-down waits and its at-speed input (docs/hardware.md, "Spindle").
#include <fmt/format.h>  // messages

#include "gantry/interp/command_context.hpp"
#include "gantry/interp/value.hpp"  // format_number

namespace gantry {

namespace {

bool on(const ModalState& st, int n) {
  return n >= 1 && ((st.outputs >> (n - 1)) & 1u) != 0;
}

}  // namespace

int CommandContext::spindle_direction() const {
  const SpindleSettings& sp = settings_.spindle;
  const bool run = on(state_, 1), reverse = sp.reverse_output != 0 && on(state_, sp.reverse_output);
  if (sp.reverse_wiring == SpindleSettings::ReverseWiring::Run) return run ? 1 : reverse ? -1 : 0;
  return !run ? 0 : reverse ? -1 : 1;
}

bool CommandContext::spindle_output(int n) const {
  return n == 1 || (settings_.spindle.reverse_output != 0 && n == settings_.spindle.reverse_output);
}

void CommandContext::spindle(int direction, const SourceLoc& loc) {
  const SpindleSettings& sp = settings_.spindle;
  if (direction < 0 && sp.reverse_output == 0)
    fail(loc,
         "M4 (spindle counter-clockwise) is not available: this machine's profile names no "
         "output for it (spindle.reverse_output), so output switch 1 runs the spindle one way "
         "only; use M3");
  const int now = spindle_direction();
  if (now == direction) return;
  // A spindle is never reversed while it turns: it stops (and spins down) first.
  if (now != 0 && direction != 0) spindle(0, loc);
  const bool run_wiring = sp.reverse_wiring == SpindleSettings::ReverseWiring::Run;
  const int rev = sp.reverse_output;
  switch (direction) {
    case 0:  // the output that runs it goes off first (the spin-down wait follows it)
      if (on(state_, 1)) set_output(1, false, loc);
      if (rev && on(state_, rev)) set_output(rev, false, loc);
      break;
    case 1:
      if (rev && on(state_, rev)) set_output(rev, false, loc);  // direction first
      set_output(1, true, loc);
      break;
    default:
      if (run_wiring) {
        if (on(state_, 1)) set_output(1, false, loc);
        set_output(rev, true, loc);
      } else {
        set_output(rev, true, loc);  // the direction is set before the spindle runs
        set_output(1, true, loc);
      }
  }
}

void CommandContext::spindle_settle(int was, const SourceLoc& loc) {
  if (!spindle_settles_) return;  // a run's end: the outputs only go off
  const int now = spindle_direction();
  if (now == was) return;
  const SpindleSettings& sp = settings_.spindle;
  if (now == 0) {
    dwell(sp.spin_down_s, loc);
    return;
  }
  if (was != 0) return;  // a reversal by SO: the operator's own sequence
  dwell(sp.spin_up_s, loc);
  wait_at_speed(loc);
}

// The live machine waits in short dwells, so time passes on the card and a stop ends the
// wait; a check or a preview (no inputs) goes on at once.
void CommandContext::wait_at_speed(const SourceLoc& loc) {
  const SpindleSettings& sp = settings_.spindle;
  if (sp.at_speed_input == 0 || state_.preview) return;
  const auto k = static_cast<size_t>(sp.at_speed_input - 1);
  come_to_rest(loc);
  std::optional<std::array<bool, 12>> in = input_switches();
  constexpr double kStep = 0.01;
  double waited = 0;
  while (in && !(*in)[k]) {
    if (waited >= sp.at_speed_timeout_s - 1e-9)
      fail(loc, fmt::format("the spindle did not reach its speed: input switch {} "
                            "(spindle.at_speed_input) did not close within {} s "
                            "(spindle.at_speed_timeout_s); the job stops here. Check the "
                            "drive (a fault, a speed it cannot reach) and its wiring",
                            sp.at_speed_input, format_number(sp.at_speed_timeout_s)));
    dwell(kStep, loc);
    waited += kStep;
    in = input_switches();
  }
}

}  // namespace gantry
