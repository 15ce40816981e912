// The software rasteriser behind the preview images: lines, dots and depth-tested
// triangles on an RGB image.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <string_view>
#include <utility>  // move
#include <vector>

#include "gantry/preview/render.hpp"    // Image, Rgb, Projection
#include "gantry/preview/toolpath.hpp"  // Toolpath

namespace gantry::preview_detail {

class Canvas {
 public:
  Canvas(int width, int height, Rgb background);

  // A line `width` pixels wide; `dash` > 0: drawn `dash` pixels, skipped `dash` pixels.
  void line(Eigen::Vector2f a, Eigen::Vector2f b, Rgb colour, int width, int dash = 0);
  void dot(Eigen::Vector2f centre, float radius, Rgb colour);
  // `text` in the 5x7 pixel font (pixel_font.hpp), each font pixel `scale` pixels square,
  // its top left corner at (x, y).
  void text(int x, int y, std::string_view text, Rgb colour, int scale = 1);
  // A triangle in picture coordinates with depth (larger: nearer), one colour.
  void triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                Rgb colour);

  Image take() { return std::move(image_); }

 private:
  void plot(int x, int y, Rgb colour) {
    if (x < 0 || y < 0 || x >= image_.width || y >= image_.height) return;
    std::uint8_t* p = &image_.rgb[(static_cast<std::size_t>(y) * image_.width + x) * 3];
    p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
  }

  Image image_;
  std::vector<float> depth_;  // for triangles only: the nearest drawn so far per pixel
};

// A scale bar (bottom left) and the path's bounding dimensions (top left), in its units.
void draw_dimensions(Canvas& canvas, const Projection& proj, const Toolpath& path);

}  // namespace gantry::preview_detail
