// G-code from canonical moves (docs/gcode.md, "Exporting").
#include "export_gcode.hpp"

#include <fmt/format.h>  // the program's text

#include <cmath>  // abs, ceil

#include "gantry/canon/arc_geometry.hpp"  // plane_axes
#include "gantry/core/part_number.hpp"    // part_number
#include "gantry/motion/path_limits.hpp"  // nominal_path_speed

namespace gantry {
namespace {

// At most 8 decimals (far below any machine's step), no trailing zeros, never "-0".
std::string num(double v) {
  return part_number(v, 8);
}

constexpr std::string_view kAxes = "XYZABC";

}  // namespace

GcodeWriter::GcodeWriter(const Settings& settings, const std::string& source)
    : units_(settings.units) {
  out_ = fmt::format(
      "%\n(Exported by Gantry from {})\n(Coordinates are the machine's own frame: table base "
      "coordinates unless ZT or UZ moved them)\nG90 G94 G91.1 G17 G40 G49 G80\n{}\n",
      source, units_ == Units::Millimetres ? "G21 (millimetres)" : "G20 (inches)");
  plane_ = 0;
}

void GcodeWriter::units(Units u) {
  if (u == units_) return;
  units_ = u;
  out_ += u == Units::Millimetres ? "G21\n" : "G20\n";
}

void GcodeWriter::settings_changed(const Settings& s) {
  units(s.units);
}

// The axis words for `to`: those that differ from the last position written (`all`: X, Y, Z
// always, for the first move).
std::string GcodeWriter::axes(const Vec6& to, bool all) {
  std::string s;
  for (int a = 0; a < kAxisCount; ++a)
    if (num(to[a]) != num(at_[a]) || (all && a < 3))
      s += fmt::format(" {}{}", kAxes[static_cast<size_t>(a)], num(to[a]));
  at_ = to;
  return s;
}

void GcodeWriter::move(const CanonMove& m) {
  auto feed = [&](double units_per_s) {
    const double f = units_per_s * 60;
    if (num(f) == num(feed_)) return std::string();
    feed_ = f;
    return fmt::format(" F{}", num(f));
  };
  const bool first = !started_;
  switch (m.kind) {
    case MoveKind::Line:
      started_ = true;
      if (m.speed_class == SpeedClass::Jog)
        out_ += "G0" + axes(m.to, first) + "\n";
      else
        out_ += "G1" + axes(m.to, first) + feed(nominal_path_speed(m.to - m.from, m.speeds)) + "\n";
      return;
    case MoveKind::Arc: {
      started_ = true;
      const int plane = static_cast<int>(m.plane);
      if (plane != plane_) {
        out_ += plane == 0 ? "G17\n" : plane == 1 ? "G18\n" : "G19\n";
        plane_ = plane;
      }
      const std::array<int, 3> ax = plane_axes(m.plane);
      std::string words = axes(m.to, first);
      for (int i : {ax[0], ax[1]})  // the end point in the plane, always
        if (words.find(kAxes[static_cast<size_t>(i)]) == std::string::npos)
          words += fmt::format(" {}{}", kAxes[static_cast<size_t>(i)], num(m.to[i]));
      const double cu = m.center_x - m.from[ax[0]], cv = m.center_y - m.from[ax[1]];
      words += fmt::format(" {}{} {}{}", "IJK"[ax[0]], num(cu), "IJK"[ax[1]], num(cv));
      const double turns = std::ceil(std::abs(m.sweep) / (2 * M_PI) - 1e-9);
      if (turns > 1) words += fmt::format(" P{}", num(turns));
      out_ += (m.sweep < 0 ? "G2" : "G3") + words + feed(m.speeds.xy) + "\n";
      return;
    }
    case MoveKind::Dwell:
      out_ += fmt::format("G4 P{}\n", num(m.dwell_s));
      return;
    case MoveKind::Stop:
      out_ += "G4 P0\n";
      return;
    case MoveKind::Output:
      out_ += fmt::format("{} P{}\n", m.output_on ? "M64" : "M65", m.output);
      return;
    case MoveKind::SpindleSpeed:
      out_ += fmt::format("S{}\n", num(m.spindle_rpm));
      return;
    case MoveKind::Independent:  // G-code has no axis moving on its own: say so, in place
      out_ += m.independent.running()
                  ? fmt::format("(MI: {} moves on its own here; G-code cannot say so)\n",
                                static_cast<char>(std::toupper(kAxisLetters[m.independent.axis])))
                  : "(MI: it stops here)\n";
      return;
  }
}

std::string GcodeWriter::finish() {
  out_ += "M2\n%\n";
  return std::move(out_);
}

}  // namespace gantry
