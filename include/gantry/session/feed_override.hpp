// The operator's live feed override, as every front end steps and shows it: 10 % to 200 %
// of the programmed speeds (docs/controller.md, set_feed_override), in steps of 10 %.
#pragma once

#include <string>

namespace gantry::session {

inline constexpr double kMinFeedOverride = 0.1, kMaxFeedOverride = 2.0;

// `now` moved by `steps` tens of percent, rounded to a whole ten, within the limits.
double stepped_feed_override(double now, int steps);
// Within the limits (a slider's value, a typed one).
double clamped_feed_override(double factor);
// "feed 120 %"
std::string feed_override_text(double factor);

}  // namespace gantry::session
