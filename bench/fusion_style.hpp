// A G-code job shaped as Fusion 360's Mach3/LinuxCNC posts write an adaptive clearing pass.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace gantry::bench {

// About `lines` lines: the post's header, a helical ramp (G3 with Z), then trochoidal loops
// across the table at two depths: each loop a run of short G1 chords (0.01-0.03 in, modal:
// only the coordinates that change), a G2 arc back onto the path, and a feed change between
// the cutting and the linking feed, as adaptive clearing posts them. Inches, inside the
// default profile's 24 x 18 in table.
inline std::string fusion_style_gcode(int lines) {
  std::string out =
      "%\n(1001)\n(T1  D=0.25 CR=0. - ZMIN=-0.25 - flat end mill)\nG90 G94 G91.1 G40 G49 G17\n"
      "G20\nG28 G91 Z0.\nG90\n\n(Adaptive1)\nT1 M6\nS16000 M3\nG54\nM8\n"
      "G0 X2.1 Y2.\nG43 Z0.6 H1\nG0 Z0.2\nG1 Z0.04 F40.\n";
  int n = 18;
  // A helical ramp down to the first depth.
  for (int k = 0; k < 4; ++k, n += 2)
    out += fmt::format("G3 X1.9 Y2. Z{:.4f} I-0.1 J0.\nG3 X2.1 Y2. Z{:.4f} I0.1 J0.\n",
                       0.03 - 0.03 * k, 0.015 - 0.03 * k);
  const double r = 0.12;     // the loop's radius
  const double step = 0.06;  // the path advances this much per loop
  double x = 2.1, y = 2.0, depth = -0.125;
  int row = 0;
  bool cutting_feed = false;
  const int chords = 18;
  while (n + chords + 5 < lines - 9) {  // room for a whole loop and a change of row
    // A loop: chords around a circle centred r to the left of (x, y), starting at angle 0.
    cutting_feed = !cutting_feed;
    out += fmt::format("G1 X{:.4f} F{}\n", x, cutting_feed ? "80." : "120.");
    ++n;
    for (int i = 1; i <= chords; ++i, ++n) {
      const double a = 2 * M_PI * 0.75 * i / chords;  // three quarters of the loop in chords
      out += fmt::format("X{:.4f} Y{:.4f}\n", x - r + r * std::cos(a), y + r * std::sin(a));
    }
    // The last quarter as a counterclockwise arc (radius 0.13) onto the next loop's start,
    // `step` further on; I and J from the arc's start, as G91.1 has them.
    const double sx = x - r, sy = y - r;  // where the chords ended (angle 270 degrees)
    x += step;
    const double dx = x - sx, dy = y - sy, half = std::hypot(dx, dy) / 2;
    const double h = std::sqrt(0.13 * 0.13 - half * half);
    const double cx = sx + dx / 2 - dy / (2 * half) * h, cy = sy + dy / 2 + dx / (2 * half) * h;
    out += fmt::format("G3 X{:.4f} Y{:.4f} I{:.4f} J{:.4f}\n", x, y, cx - sx, cy - sy);
    ++n;
    if (x > 22.0) {  // the next row, and after a pass over the table the next depth
      x = 2.1;
      y += 0.5;
      if (++row == 30) {
        row = 0;
        y = 2.0;
        depth = depth < -0.2 ? -0.125 : -0.25;
      }
      out += fmt::format("G0 Z0.2\nG0 X{:.4f} Y{:.4f}\nG1 Z{:.4f} F40.\n", x, y, depth);
      n += 3;
    }
  }
  out += "G0 Z0.6\nM9\nG28 G91 Z0.\nG90\nG28 G91 X0. Y0.\nG90\nM5\nM30\n%\n";
  return out;
}

}  // namespace gantry::bench
