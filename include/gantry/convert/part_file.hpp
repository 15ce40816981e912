// The one part-file writer: the text of a part file as the tools (TD, TF, TU, TT, TC, TI)
// and the converters (FC) write it, one statement a line, numbers by part_number.
#pragma once

#include <fmt/format.h>  // the statements' text

#include <algorithm>  // clamp
#include <cmath>      // ceil, sin, cos, acos
#include <numbers>    // pi
#include <string>
#include <string_view>

#include "gantry/core/part_number.hpp"  // part_number

namespace gantry {

class PartText {
 public:
  void comment(std::string_view text) { line(fmt::format("' {}", text)); }
  void line(std::string_view text) {
    text_ += text;
    text_ += '\n';
  }
  void jog_z(double z) { line(fmt::format("JZ, {}", part_number(z))); }
  void jog_xy(double x, double y) {
    line(fmt::format("J2, {}, {}", part_number(x), part_number(y)));
  }
  void move_z(double z) { line(fmt::format("MZ, {}", part_number(z))); }
  void move_xy(double x, double y) {
    line(fmt::format("M2, {}, {}", part_number(x), part_number(y)));
  }
  // A full circle at the current Z, clockwise from 12 o'clock (where the tool is) and back,
  // as chords no further than `tolerance` from the circle.
  void circle(double cx, double cy, double r, double tolerance) {
    int n = 8;
    if (tolerance < r)
      n = static_cast<int>(std::ceil(std::numbers::pi / std::acos(1 - tolerance / r)));
    n = std::clamp(n, 8, 1000);
    for (int j = 1; j < n; ++j) {
      const double a = 2 * std::numbers::pi * j / n;
      move_xy(cx + r * std::sin(a), cy + r * std::cos(a));
    }
    move_xy(cx, cy + r);
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

}  // namespace gantry
