// The window's size as `gui --size` takes it (WIDTH or WIDTHxHEIGHT) and the scale of its
// layout and fonts for a size. Nothing here draws.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace gantry::ui {

struct WindowSize {
  int width = 1280, height = 800;
};

// "1280" (the height follows at 16:10) or "1024x600"; each side 320 to 8192. nullopt with
// `why` when the text is neither.
std::optional<WindowSize> parse_window_size(std::string_view text, std::string* why);

// The scale of the layout and the fonts: 1 up to 1280 x 800 (smaller windows keep the text
// readable and lay the windows out tighter), then the smaller of the two ratios, to 3 (4K is
// 2.7), in quarters so that a resize by a few pixels does not rebuild the fonts.
float window_scale(float width, float height);

}  // namespace gantry::ui
