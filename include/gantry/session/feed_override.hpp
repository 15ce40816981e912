// The operator's live feed override, as every front end steps and shows it: within the
// profile's [feed_override] bounds (10 % to 200 % unless it says otherwise; docs/controller.md,
// set_feed_override), in steps of 10 %.
#pragma once

#include <string>

namespace gantry {
struct Settings;
}

namespace gantry::session {

// The profile's bounds as factors (feed_override.min / 100, max / 100).
struct FeedOverrideBounds {
  double lo = 0.1, hi = 2.0;
};
FeedOverrideBounds feed_override_bounds(const Settings& s);

// `now` moved by `steps` tens of percent, to whole tens, within the bounds (a bound that is
// not a whole ten is a step of its own: 15 % steps up to 20 %, 20 % down to 15 %).
double stepped_feed_override(double now, int steps, const FeedOverrideBounds& b);
// Within the bounds (a slider's value, a typed one).
double clamped_feed_override(double factor, const FeedOverrideBounds& b);
// "feed 120 %"
std::string feed_override_text(double factor);

}  // namespace gantry::session
