// `gui --size` and the layout's scale.
#include "window_size.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace gantry::ui {
namespace {

constexpr int kMin = 320, kMax = 8192;

bool side(std::string_view s, int& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return !s.empty() && r.ec == std::errc{} && r.ptr == s.data() + s.size();
}

}  // namespace

std::optional<WindowSize> parse_window_size(std::string_view text, std::string* why) {
  WindowSize w;
  const std::size_t x = text.find_first_of("xX");
  const bool both = x != std::string_view::npos;
  if (!side(both ? text.substr(0, x) : text, w.width) ||
      (both && !side(text.substr(x + 1), w.height))) {
    if (why)
      *why =
          fmt::format("'{}' is no window size: WIDTH (16:10) or WIDTHxHEIGHT, e.g. 1024x600", text);
    return std::nullopt;
  }
  if (!both) w.height = w.width * 10 / 16;
  for (const int v : {w.width, w.height})
    if (v < kMin || v > kMax) {
      if (why) *why = fmt::format("'{}': each side must be {} to {} pixels", text, kMin, kMax);
      return std::nullopt;
    }
  return w;
}

float window_scale(float width, float height) {
  const float s = std::min(width / 1280.0f, height / 800.0f);
  return std::clamp(std::floor(s * 4) / 4, 1.0f, 3.0f);
}

}  // namespace gantry::ui
