// Ellipse arcs with an exact cutter offset, and rectangles, as contours.
#include "gantry/cuts/shapes.hpp"

#include <algorithm>  // max, min
#include <cmath>      // sin, cos, ceil, abs

namespace gantry::cuts {

double side_offset(Side side, double cutter_diameter) {
  return side == Side::Out ? cutter_diameter / 2 : side == Side::In ? -cutter_diameter / 2 : 0;
}

bool Curve::full() const {
  return std::abs(sweep) >= 2 * M_PI - 1e-9;
}

// The nominal point is (a sin t, b cos t); its tangent is (a cos t, -b sin t), so the outward
// normal is (b sin t, a cos t), normalised. On a circle it is the radius direction, and the
// offset point is written as (a + offset)(sin t, cos t) so that it stays exactly on the circle.
V2 Curve::relative(double t) const {
  const double s = std::sin(t), c = std::cos(t);
  if (circular()) return (a + offset) * V2(s, c);
  const V2 n(b * s, a * c);
  return V2(a * s, b * c) + offset * n / n.norm();
}

Curve Curve::scaled(double k) const {
  Curve c = *this;
  c.a *= k;
  c.b *= k;
  c.offset *= k;
  return c;
}

double Curve::tightest_radius() const {
  return std::min(a, b) * std::min(a, b) / std::max(a, b);
}

namespace {

double distance_to_segment(const V2& p, const V2& a, const V2& b) {
  const V2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double f = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + f * ab - p).norm();
}

// Splits [t0, t1] until the curve strays from each chord by less than `tolerance`, judged
// at the quarter points (the pieces start small, so the curve bends little within one).
void subdivide(const Curve& c, double t0, double t1, const V2& p0, const V2& p1, double tolerance,
               int depth, Contour& out) {
  double worst = 0;
  for (double f : {0.25, 0.5, 0.75})
    worst = std::max(worst, distance_to_segment(c.point(t0 + (t1 - t0) * f), p0, p1));
  if (worst > 0.8 * tolerance && depth < 40) {
    const double tm = (t0 + t1) / 2;
    const V2 pm = c.point(tm);
    subdivide(c, t0, tm, p0, pm, tolerance, depth + 1, out);
    subdivide(c, tm, t1, pm, p1, tolerance, depth + 1, out);
    return;
  }
  Piece line;
  line.from = p0;
  line.to = p1;
  out.push_back(line);
}

}  // namespace

Contour contour(const Curve& c, double tolerance) {
  const V2 from = c.point(c.begin);
  const V2 to = c.full() ? from : c.point(c.begin + c.sweep);
  Contour out;
  if (c.circular()) {
    Piece arc;
    arc.arc = true;
    arc.from = from;
    arc.to = to;
    arc.centre = c.centre;
    arc.sweep = -c.sweep;  // clockwise positive in ShopBot's angles, negative in CanonMove's
    out.push_back(arc);
    return out;
  }
  const int n = std::max(8, static_cast<int>(std::ceil(std::abs(c.sweep) / (M_PI / 16))));
  V2 p0 = from;
  for (int i = 1; i <= n; ++i) {
    const double t0 = c.begin + c.sweep * (i - 1) / n, t1 = c.begin + c.sweep * i / n;
    const V2 p1 = i == n ? to : c.point(t1);
    subdivide(c, t0, t1, p0, p1, tolerance, 0, out);
    p0 = p1;
  }
  return out;
}

V2 Rect::corner_point(int code) const {
  switch (code) {
    case 1:
      return lower_left + V2(0, h);
    case 2:
      return lower_left + V2(w, h);
    case 3:
      return lower_left + V2(w, 0);
    default:
      return lower_left;
  }
}

Rect Rect::inset(double d) const {
  Rect r = *this;
  r.lower_left += V2(d, d);
  r.w -= 2 * d;
  r.h -= 2 * d;
  return r;
}

Contour contour(const Rect& r) {
  // The corners clockwise from the lower left: lower left, upper left, upper right, lower right.
  constexpr int kClockwise[4] = {4, 1, 2, 3};
  int k = 0;
  while (k < 3 && kClockwise[k] != r.corner) ++k;
  Contour out;
  for (int i = 0; i < 4; ++i) {
    const int next = (k + (r.direction > 0 ? 1 : 3)) % 4;
    Piece line;
    line.from = r.corner_point(kClockwise[k]);
    line.to = r.corner_point(kClockwise[next]);
    out.push_back(line);
    k = next;
  }
  return out;
}

}  // namespace gantry::cuts
