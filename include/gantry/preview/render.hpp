// Pictures of a toolpath without a display: a software-rasterised image (PNG) and an SVG
// drawing, in one of four orthographic views, sharing one projection and one palette.
#pragma once

#include <Eigen/Geometry>  // AlignedBox3f, Matrix

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/preview/toolpath.hpp"   // Toolpath
#include "gantry/settings/settings.hpp"  // Settings (the table envelope)

namespace gantry {

// Top: from above, +X right, +Y up. Front: from the front (-Y), +X right, +Z up. Side:
// from the right (+X), +Y right, +Z up. Iso: from the front right above, +Z up.
enum class View { Top, Iso, Front, Side };
const char* view_name(View v);
std::optional<View> parse_view(std::string_view name);  // "top", "iso", "front", "side"

using Rgb = std::array<std::uint8_t, 3>;

// The palette both pictures use (docs/preview.md).
namespace palette {
inline constexpr Rgb background{255, 255, 255};
inline constexpr Rgb table{110, 110, 110};     // the table envelope's outline
inline constexpr Rgb stock{160, 100, 40};      // the stock's top rectangle
inline constexpr Rgb cut_deep{31, 95, 191};    // a cut at its command's deepest Z
inline constexpr Rgb cut_upper{224, 128, 32};  // a cut above it (tabs, upper passes, ramps)
inline constexpr Rgb jog{150, 150, 150};       // dashed
inline constexpr Rgb keypad{150, 40, 190};     // a keypad jog
inline constexpr Rgb start{34, 170, 34};       // the start and end dots
inline constexpr Rgb end{204, 34, 34};
inline constexpr Rgb text{0, 0, 0};            // the scale bar and the dimensions
}  // namespace palette

// Machine frame to picture: x right and y down in pixels, and a depth that grows toward
// the viewer. Fits `box` into width x height with a margin, keeping the scale equal on both
// axes; a height of 0 is chosen from the box's aspect (for SVG figures).
class Projection {
 public:
  Projection(View view, const Eigen::AlignedBox3f& box, int width, int height);
  Eigen::Vector3f operator()(const Eigen::Vector3f& p) const;
  int width() const { return width_; }
  int height() const { return height_; }
  float pixels_per_unit() const { return scale_; }
  // Unit vectors in the machine frame: picture right, picture up, toward the viewer.
  const Eigen::Matrix3f& axes() const { return axes_; }

 private:
  Eigen::Matrix3f axes_;  // rows: right, up, toward
  float scale_ = 1;
  Eigen::Vector2f offset_;
  int width_, height_;
};

struct PreviewOptions {
  View view = View::Top;
  int width = 800, height = 600;  // pixels; height 0: from the drawing's aspect
  bool table = true;              // draw the table envelope's outline (the view then fits it too)
  // The jogs before the first cut only place the tool; `gantry moves --svg` leaves them out.
  bool leading_jogs = true;
  // The block of stock (machine frame, the file's units): its top rectangle is drawn and
  // the view fits it too; its size and origin are listed (docs/preview.md, "Stock").
  std::optional<Eigen::AlignedBox3f> stock;
  // A scale bar (bottom left) and the path's bounding dimensions (top left), in the file's
  // units; the SVG also lists the cutters. Figures for the docs leave them out.
  bool dimensions = true;
};

// The box the picture fits: the drawn segments and, with `table`, the table envelope's
// XY rectangle at Z 0.
Eigen::AlignedBox3f preview_box(const Toolpath& path, const Settings& settings,
                                const PreviewOptions& opts);

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // rows top to bottom, 3 bytes a pixel
  Rgb at(int x, int y) const;
};

// The toolpath as lines: the table outline first, then jogs (dashed), cuts (coloured by
// depth within their command) and keypad jogs, each group in path order.
Image render_lines(const Toolpath& path, const Settings& settings, const PreviewOptions& opts);

// The same drawing as SVG text: one <path> per run of consecutive segments of one style,
// the table outline a <polygon>, the start and end dots <circle>s.
std::string render_svg(const Toolpath& path, const Settings& settings, const PreviewOptions& opts);

// Writes `image` as a PNG file; false when it cannot be written.
bool write_png(const std::string& path, const Image& image);

}  // namespace gantry
