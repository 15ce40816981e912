// Gantry's own single-stroke font, for engraving text (TT): every printable ASCII character
// drawn as a few polylines the tool follows along their centre lines.
#pragma once

#include <array>
#include <vector>

namespace gantry {

// A glyph in font units: the baseline is y = 0, capitals and digits are kCapHeight tall,
// lower case letters kXHeight, descenders reach kDescent; x runs from 0 to `width`.
// A stroke of one point is a dot (the tool goes down and up there).
struct StrokeGlyph {
  double width = 0;
  std::vector<std::vector<std::array<double, 2>>> strokes;
};

struct StrokeFont {
  static constexpr double kCapHeight = 6;
  static constexpr double kXHeight = 4;
  static constexpr double kDescent = -2;
  static constexpr double kGap = 1;  // between one glyph's width and the next glyph

  // The glyph of `c`, a printable ASCII character (space to '~'); null for any other.
  static const StrokeGlyph* glyph(char c);
  // How far the pen advances after `c`: its width and the gap.
  static double advance(char c) { return glyph(c) ? glyph(c)->width + kGap : 0; }
};

}  // namespace gantry
