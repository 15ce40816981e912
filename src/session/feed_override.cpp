// The live feed override's steps and text.
#include "gantry/session/feed_override.hpp"

#include <fmt/format.h>

#include <algorithm>  // clamp
#include <cmath>      // round

namespace gantry::session {

double clamped_feed_override(double factor) {
  return std::clamp(factor, kMinFeedOverride, kMaxFeedOverride);
}

double stepped_feed_override(double now, int steps) {
  return clamped_feed_override((std::round(now * 10) + steps) / 10);
}

std::string feed_override_text(double factor) {
  return fmt::format("feed {:.0f} %", factor * 100);
}

}  // namespace gantry::session
