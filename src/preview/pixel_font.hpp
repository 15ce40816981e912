// A tiny 5x7 bitmap font for the text of the PNG preview (its scale bar and dimensions):
// digits, the signs numbers use, and the letters of axis names and units.
#pragma once

#include <array>
#include <cstdint>

namespace gantry::preview_detail {

// Glyphs are 5 pixels wide and 7 tall, drawn one pixel apart (an advance of 6).
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

// The rows of `c`, top first, bit 4 the leftmost pixel; a character the font lacks is a box
// outline (so it is seen to be missing), space is empty.
std::array<std::uint8_t, kGlyphHeight> glyph_rows(char c);

}  // namespace gantry::preview_detail
