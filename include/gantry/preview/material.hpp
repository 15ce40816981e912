// A material-removal simulation: the stock as a height map, carved by the cutter along the
// toolpath, and a shaded picture of it.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "gantry/preview/render.hpp"    // Image, PreviewOptions, Projection
#include "gantry/preview/toolpath.hpp"  // Toolpath

namespace gantry {

enum class CutterShape { Flat, Ball, V };

struct Cutter {
  CutterShape shape = CutterShape::Flat;
  double diameter = 0.25;  // VC's cutter diameter, profile units
  double v_angle = 90;     // V: the included angle, degrees
};
// "flat", "ball", or "v" with an optional included angle ("v", "v60"); nullopt otherwise.
std::optional<Cutter> parse_cutter(std::string_view shape, double diameter);

// The stock's top surface on a square grid of cells (row-major, +Y rows): each cell's Z
// is the lowest the cutter's surface reached over the cell's centre, at most `top`.
struct HeightMap {
  float x0 = 0, y0 = 0, cell = 1;  // centre of cell (0, 0), the cell size
  int nx = 0, ny = 0;
  float top = 0, bottom = 0;  // the stock's top (uncut) and bottom (drawn as its sides)
  std::vector<float> z;
  float at(int i, int j) const { return z[static_cast<std::size_t>(j) * nx + i]; }
  // The height at a point of the machine frame (the nearest cell); nullopt off the stock.
  std::optional<float> height(float x, float y) const;
};

// The stock covers every segment below `top` in XY, plus the cutter's radius and a
// margin, in at most `max_cells` cells along its longer side. Every segment below the top
// removes material, jogs too: a jog through the stock is a crash the picture must show.
HeightMap carve(const Toolpath& path, const Cutter& cutter, float top, int max_cells);
// The same cut into a given block of stock (--stock, or the profile's VP table size): its
// XY rectangle, its top (max Z) and bottom (min Z); cuts outside it remove nothing.
HeightMap carve(const Toolpath& path, const Cutter& cutter, const Eigen::AlignedBox3f& stock,
                int max_cells);

// The carved stock, lit from the viewer's upper left, darker where deeper; the view fits
// the stock block.
// With `path`, the scale bar and its dimensions as the line picture has them
// (opts.dimensions).
Image render_material(const HeightMap& map, const PreviewOptions& opts,
                      const Toolpath* path = nullptr);
Projection material_projection(const HeightMap& map, const PreviewOptions& opts);

}  // namespace gantry
