// The input word's roles, from the profile's [inputs] wiring and VN (docs/controller.md).
#include "gantry/hal/input_roles.hpp"

#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

void add(InputTrip& t, int bit, bool active_high) {
  if (bit < 0 || bit > 31) return;  // not wired
  t.mask |= 1u << bit;
  if (active_high) t.active_high |= 1u << bit;
}

}  // namespace

// A bit has one role; the profile's wiring comes first. A VN mode on an input that is the
// E-stop or a limit switch already leaves it as it is (the profile says how it is wired).
InputRoles input_roles(const Settings& s) {
  const InputSettings& in = s.inputs;
  InputRoles r;
  add(r.estop, in.estop_bit, !in.estop_active_low);
  if (s.switches.limits)
    for (int i = 0; i < kAxisCount; ++i)
      for (int bit : {in.min_bit[i], in.max_bit[i]}) add(r.limits, bit, !in.limits_active_low);
  auto taken = [&](int bit) { return bit < 0 || ((r.estop.mask | r.limits.mask) >> bit & 1u); };
  for (int n = 1; n <= 12; ++n) {
    const int bit = in.switch_bits[n - 1];
    // A normally-open switch closes when it acts (reads 1), a normally-closed one opens.
    const int mode = s.switches.input_modes[n - 1];
    if (n == 4) {  // the stop switch, unless it is the E-stop chain
      if (!taken(bit)) add(r.stops, bit, s.switches.stop_normally_open);
    } else if ((mode == 1 || mode == 2) && s.switches.limits && !taken(bit)) {
      add(r.limits, bit, mode == 1);
    } else if ((mode == 3 || mode == 4) && !taken(bit)) {
      add(r.stops, bit, mode == 3);
    }
  }
  return r;
}

}  // namespace gantry
