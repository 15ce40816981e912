// SVG top view of canonical moves.
#include "svg.hpp"

#include <fmt/format.h>  // the SVG text

#include <algorithm>  // min, max
#include <cmath>      // abs, cos, sin
#include <limits>
#include <map>

#include "gantry/cuts/path.hpp"  // arc_extremes

namespace gantry {

std::string moves_svg(const std::vector<CanonMove>& moves) {
  // The jogs to the first cut only place the tool: they are left out.
  std::vector<const CanonMove*> drawn;
  for (const CanonMove& m : moves)
    if ((m.kind == MoveKind::Line || m.kind == MoveKind::Arc) &&
        (!drawn.empty() || m.speed_class == SpeedClass::Move))
      drawn.push_back(&m);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  std::map<int, double> z_low;  // per source line: the deepest a command cuts
  auto take = [&](double x, double y) {
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  };
  for (const CanonMove* m : drawn) {
    take(m->from[0], m->from[1]);
    take(m->to[0], m->to[1]);
    if (m->kind == MoveKind::Arc)
      for (const cuts::V2& p : cuts::arc_extremes(cuts::V2(m->from[0], m->from[1]),
                                                  cuts::V2(m->center_x, m->center_y), m->sweep))
        take(p.x(), p.y());
    if (m->speed_class == SpeedClass::Move) {
      const auto it = z_low.try_emplace(m->loc.line, kInf).first;
      it->second = std::min({it->second, m->from[2], m->to[2]});
    }
  }
  if (drawn.empty()) x0 = y0 = x1 = y1 = 0;
  const double span = std::max({x1 - x0, y1 - y0, 1e-6});
  const double pad = span * 0.05, stroke = span / 250;
  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" "
      "viewBox=\"{:.6g} {:.6g} {:.6g} {:.6g}\">\n"
      "<rect x=\"{:.6g}\" y=\"{:.6g}\" width=\"{:.6g}\" height=\"{:.6g}\" fill=\"white\"/>\n"
      "<g transform=\"scale(1,-1)\" fill=\"none\" stroke-linecap=\"round\" "
      "stroke-width=\"{:.4g}\">\n",
      400 * (x1 - x0 + 2 * pad) / span, 400 * (y1 - y0 + 2 * pad) / span, x0 - pad, -y1 - pad,
      x1 - x0 + 2 * pad, y1 - y0 + 2 * pad, x0 - pad, -y1 - pad, x1 - x0 + 2 * pad,
      y1 - y0 + 2 * pad, stroke);
  for (const CanonMove* m : drawn) {
    if (m->from[0] == m->to[0] && m->from[1] == m->to[1] && m->kind == MoveKind::Line) continue;
    const bool jog = m->speed_class == SpeedClass::Jog;
    const bool deep = std::max(m->from[2], m->to[2]) <= z_low[m->loc.line] + 1e-9;
    const std::string style =
        jog    ? fmt::format("stroke=\"#999\" stroke-dasharray=\"{:.4g} {:.4g}\"", 4 * stroke,
                             4 * stroke)
        : deep ? "stroke=\"#1f5fbf\""
               : "stroke=\"#e08020\"";
    std::string d = fmt::format("M {:.6f} {:.6f}", m->from[0], m->from[1]);
    if (m->kind == MoveKind::Line) {
      d += fmt::format(" L {:.6f} {:.6f}", m->to[0], m->to[1]);
    } else {
      // SVG cannot draw an arc whose ends meet: at most half a turn per piece.
      const double r = std::hypot(m->from[0] - m->center_x, m->from[1] - m->center_y);
      const double a0 = std::atan2(m->from[1] - m->center_y, m->from[0] - m->center_x);
      const int pieces = static_cast<int>(std::ceil(std::abs(m->sweep) / M_PI - 1e-9));
      for (int i = 1; i <= std::max(1, pieces); ++i) {
        const double a = a0 + m->sweep * i / std::max(1, pieces);
        const double x = i == pieces ? m->to[0] : m->center_x + r * std::cos(a);
        const double y = i == pieces ? m->to[1] : m->center_y + r * std::sin(a);
        d += fmt::format(" A {:.6f} {:.6f} 0 0 {} {:.6f} {:.6f}", r, r, m->sweep > 0 ? 1 : 0, x, y);
      }
    }
    out += fmt::format("<path {} d=\"{}\"/>\n", style, d);
  }
  if (!drawn.empty()) {
    const Vec6& s = drawn.front()->from;
    const Vec6& e = drawn.back()->to;
    out += fmt::format(
        "<circle cx=\"{:.6f}\" cy=\"{:.6f}\" r=\"{:.4g}\" fill=\"#2a2\" stroke=\"none\"/>\n", s[0],
        s[1], 3 * stroke);
    out += fmt::format(
        "<circle cx=\"{:.6f}\" cy=\"{:.6f}\" r=\"{:.4g}\" fill=\"#c22\" stroke=\"none\"/>\n", e[0],
        e[1], 2 * stroke);
  }
  out += "</g>\n</svg>\n";
  return out;
}

}  // namespace gantry
