// The window's look: dark or light colours, the sizes and the fonts at the window's scale,
// and the readout's large digits.
#pragma once

#include <imgui.h>

namespace gantry::ui {

// The colours the windows write text in, readable on the theme's background.
struct Palette {
  ImVec4 red, green, yellow, grey, cyan, magenta, text, off;  // off: a dark light (LEDs)
  ImVec4 background;  // behind the windows (the GL clear colour)
};
const Palette& palette(bool light);
// The palette of the theme in use (apply_style's window background tells which), for the
// parts that draw text in colours (the listing, the file dialog).
const Palette& current_palette();

// Rebuilds the font atlas for `scale` (outside a frame; the renderer's font texture must be
// made again after it): the text font at 13 px times the scale, and the readout's digits,
// large, drawn smaller to fit their window.
void build_fonts(float scale);
ImFont* digits_font();     // null before build_fonts
float digits_font_size();  // the size it was rasterised at, in pixels

// The colours and sizes (padding, rounding, scroll bars) of the theme at `scale`.
void apply_style(bool light, float scale);

// The E-STOP button's colours, the same in both themes: white text on a strong red (6.9:1),
// hovered and held in reds too (the light theme's blue hover under white text would not
// read). Pop them with ImGui::PopStyleColor(kEStopColours).
void push_estop_colours();
inline constexpr int kEStopColours = 4;

}  // namespace gantry::ui
