// The live feed override's steps and text.
#include "gantry/session/feed_override.hpp"

#include <fmt/format.h>

#include <algorithm>  // clamp
#include <cmath>      // round

#include "gantry/settings/settings.hpp"

namespace gantry::session {

FeedOverrideBounds feed_override_bounds(const Settings& s) {
  return {s.feed_override.min / 100.0, s.feed_override.max / 100.0};
}

double clamped_feed_override(double factor, const FeedOverrideBounds& b) {
  return std::clamp(factor, b.lo, b.hi);
}

double stepped_feed_override(double now, int steps, const FeedOverrideBounds& b) {
  // From between two tens (a bound such as 15 %, a slider's 104 %), the first step goes to
  // the ten on the side it steps to.
  const double tens = steps > 0 ? std::floor(now * 10 + 1e-9) : std::ceil(now * 10 - 1e-9);
  return clamped_feed_override((tens + steps) / 10, b);
}

std::string feed_override_text(double factor) {
  return fmt::format("feed {:.0f} %", factor * 100);
}

}  // namespace gantry::session
