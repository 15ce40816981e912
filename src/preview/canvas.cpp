// The preview's rasteriser: Bresenham lines, filled dots and z-buffered triangles.
#include "canvas.hpp"

#include "pixel_font.hpp"  // glyph_rows

#include <algorithm>  // min, max
#include <cmath>      // lround, floor, ceil
#include <cstdlib>    // abs

namespace gantry::preview_detail {

Canvas::Canvas(int width, int height, Rgb background)
    : depth_(static_cast<std::size_t>(width) * height, -std::numeric_limits<float>::infinity()) {
  image_.width = width;
  image_.height = height;
  image_.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0; i < image_.rgb.size(); i += 3)
    image_.rgb[i] = background[0], image_.rgb[i + 1] = background[1],
    image_.rgb[i + 2] = background[2];
}

void Canvas::line(Eigen::Vector2f a, Eigen::Vector2f b, Rgb colour, int width, int dash) {
  // Far outside the picture a line cannot be drawn pixel by pixel; none is, since every view
  // fits what it draws, but a non-finite point is skipped rather than looped over.
  if (!a.allFinite() || !b.allFinite()) return;
  long x0 = std::lround(std::floor(a.x())), y0 = std::lround(std::floor(a.y()));
  const long x1 = std::lround(std::floor(b.x())), y1 = std::lround(std::floor(b.y()));
  const long dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  const int lo = -(width - 1) / 2, hi = width / 2;
  long err = dx + dy;
  for (long step = 0;; ++step) {
    if (dash <= 0 || (step / dash) % 2 == 0)
      for (int oy = lo; oy <= hi; ++oy)
        for (int ox = lo; ox <= hi; ++ox)
          plot(static_cast<int>(x0) + ox, static_cast<int>(y0) + oy, colour);
    if (x0 == x1 && y0 == y1) break;
    const long e2 = 2 * err;
    if (e2 >= dy) err += dy, x0 += sx;
    if (e2 <= dx) err += dx, y0 += sy;
  }
}

void Canvas::dot(Eigen::Vector2f c, float radius, Rgb colour) {
  for (int y = static_cast<int>(std::floor(c.y() - radius));
       y <= static_cast<int>(std::ceil(c.y() + radius)); ++y)
    for (int x = static_cast<int>(std::floor(c.x() - radius));
         x <= static_cast<int>(std::ceil(c.x() + radius)); ++x)
      if ((Eigen::Vector2f(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f) - c)
              .squaredNorm() <= radius * radius)
        plot(x, y, colour);
}

void Canvas::text(int x, int y, std::string_view text, Rgb colour, int scale) {
  for (char c : text) {
    const auto rows = glyph_rows(c);
    for (int r = 0; r < kGlyphHeight; ++r)
      for (int k = 0; k < kGlyphWidth; ++k)
        if (rows[r] >> (kGlyphWidth - 1 - k) & 1)
          for (int dy = 0; dy < scale; ++dy)
            for (int dx = 0; dx < scale; ++dx) plot(x + k * scale + dx, y + r * scale + dy, colour);
    x += kGlyphAdvance * scale;
  }
}

void Canvas::triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                      Rgb colour) {
  // Edge functions over the bounding box, sampled at pixel centres; depth interpolated by
  // the barycentric weights.
  const float area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  if (area == 0 || !std::isfinite(area)) return;
  const int x_lo = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
  const int x_hi =
      std::min(image_.width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
  const int y_lo = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
  const int y_hi =
      std::min(image_.height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
  auto edge = [](const Eigen::Vector3f& p, const Eigen::Vector3f& q, float x, float y) {
    return (q.x() - p.x()) * (y - p.y()) - (q.y() - p.y()) * (x - p.x());
  };
  for (int y = y_lo; y <= y_hi; ++y)
    for (int x = x_lo; x <= x_hi; ++x) {
      const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
      const float wa = edge(b, c, px, py) / area, wb = edge(c, a, px, py) / area,
                  wc = edge(a, b, px, py) / area;
      // A small tolerance closes the hairline gaps between neighbouring triangles.
      if (wa < -1e-4f || wb < -1e-4f || wc < -1e-4f) continue;
      const float d = wa * a.z() + wb * b.z() + wc * c.z();
      float& nearest = depth_[static_cast<std::size_t>(y) * image_.width + x];
      if (d < nearest) continue;
      nearest = d;
      plot(x, y, colour);
    }
}

}  // namespace gantry::preview_detail
