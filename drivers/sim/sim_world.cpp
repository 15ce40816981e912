// The simulated machine's switches from the profile, and what can change an input unattended.
#include "sim/sim_world.hpp"

namespace gantry {

SimWorld simulated_world(const Settings& s) {
  SimWorld w;
  for (int i = 0; i < kAxisCount; ++i) {
    w.home_switch[i] = s.simulator.home[i];
    // Switch i is channel i's (its motor's): it homes the way its axis homes.
    w.home_above[i] = s.homing.direction[s.drivers.channel_axis[i]] > 0;
  }
  w.probe_z = s.simulator.plate_z;
  return w;
}

// As SimCard::update_switches sets them, a shared bit active while any of its switches is.
std::optional<bool> SimWorld::level_at(int bit, const Vec6& at, const InputSettings& bits) const {
  bool driven = false, active = false, low = false;
  auto drive = [&](bool on, bool active_low) {
    driven = true;
    active = active || on;
    low = active_low;
  };
  for (int i = 0; i < kAxisCount; ++i) {
    if (bits.min_bit[i] == bit && min_switch[i])
      drive(at[i] <= *min_switch[i], bits.limits_active_low);
    if (bits.max_bit[i] == bit && max_switch[i])
      drive(at[i] >= *max_switch[i], bits.limits_active_low);
    if (bits.home_bit[i] == bit && home_switch[i])
      drive(home_above[i] ? at[i] >= *home_switch[i] : at[i] <= *home_switch[i], false);
  }
  if (bits.probe_bit == bit && probe_z) drive(at[2] <= *probe_z, false);
  if (bits.probe_bit == bit && probe_surface) drive(at[2] <= probe_surface(at[0], at[1]), false);
  std::optional<bool> level;
  if (driven) level = active != low;
  for (const SimPositionInput& p : position_inputs)
    if (p.bit == bit) level = (p.above ? at[p.axis] >= p.at : at[p.axis] <= p.at) == p.high;
  return level;
}

bool SimWorld::can_set(int bit, bool high, const InputSettings& bits, double from_s,
                       const std::optional<Vec6>& at) const {
  if (bit < 0) return false;
  for (const SimInputEvent& e : input_events)
    if (e.bit == bit && e.high == high && e.at_s >= from_s) return true;
  return at && level_at(bit, *at, bits) == high;
}

}  // namespace gantry
