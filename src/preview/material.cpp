// Material removal: the cutter swept along the toolpath through a height map of the stock,
// and the carved stock drawn as a lit, z-buffered mesh.
#include "gantry/preview/material.hpp"

#include <algorithm>  // clamp, max, min
#include <charconv>   // from_chars
#include <cmath>      // ceil, floor, sqrt, tan

#include "canvas.hpp"  // Canvas

namespace gantry {
namespace {

constexpr double kPi = 3.14159265358979323846;

// How far above its tip the cutter's surface is at `rho` from its axis (rho <= radius).
struct Profile {
  CutterShape shape;
  float radius, slope;  // slope: V only, rise per unit out
  float operator()(float rho) const {
    switch (shape) {
      case CutterShape::Flat:
        return 0;
      case CutterShape::Ball:
        return radius - std::sqrt(std::max(0.0f, radius * radius - rho * rho));
      case CutterShape::V:
        return rho * slope;
    }
    return 0;
  }
};

// Lowers the cells within the cutter's radius of the XY segment a-b to the cutter's surface
// with its tip at height `z`.
void sweep(HeightMap& map, const Profile& profile, Eigen::Vector2f a, Eigen::Vector2f b, float z) {
  const float r = profile.radius;
  const Eigen::Vector2f lo = a.cwiseMin(b).array() - r, hi = a.cwiseMax(b).array() + r;
  const int i0 = std::max(0, static_cast<int>(std::ceil((lo.x() - map.x0) / map.cell)));
  const int i1 = std::min(map.nx - 1, static_cast<int>(std::floor((hi.x() - map.x0) / map.cell)));
  const int j0 = std::max(0, static_cast<int>(std::ceil((lo.y() - map.y0) / map.cell)));
  const int j1 = std::min(map.ny - 1, static_cast<int>(std::floor((hi.y() - map.y0) / map.cell)));
  const Eigen::Vector2f d = b - a;
  const float len2 = d.squaredNorm();
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Eigen::Vector2f p(map.x0 + static_cast<float>(i) * map.cell,
                              map.y0 + static_cast<float>(j) * map.cell);
      const float t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0f, 1.0f) : 0.0f;
      const float rho = (a + t * d - p).norm();
      if (rho > r) continue;
      float& h = map.z[static_cast<std::size_t>(j) * map.nx + i];
      h = std::min(h, z + profile(rho));
    }
}

Eigen::Vector3f vertex(const HeightMap& m, int i, int j, float z) {
  return {m.x0 + static_cast<float>(i) * m.cell, m.y0 + static_cast<float>(j) * m.cell, z};
}

Eigen::AlignedBox3f stock_box(const HeightMap& m) {
  return {vertex(m, 0, 0, m.bottom), vertex(m, m.nx - 1, m.ny - 1, m.top)};
}

}  // namespace

std::optional<Cutter> parse_cutter(std::string_view shape, double diameter) {
  Cutter c;
  c.diameter = diameter;
  if (shape == "flat") return c;
  if (shape == "ball") return c.shape = CutterShape::Ball, c;
  if (shape.empty() || shape[0] != 'v') return std::nullopt;
  c.shape = CutterShape::V;
  if (shape.size() == 1) return c;
  const auto [end, ec] = std::from_chars(shape.data() + 1, shape.data() + shape.size(), c.v_angle);
  if (ec != std::errc{} || end != shape.data() + shape.size() || c.v_angle <= 0 || c.v_angle >= 180)
    return std::nullopt;
  return c;
}

std::optional<float> HeightMap::height(float x, float y) const {
  const long i = std::lround((x - x0) / cell), j = std::lround((y - y0) / cell);
  if (i < 0 || j < 0 || i >= nx || j >= ny) return std::nullopt;
  return at(static_cast<int>(i), static_cast<int>(j));
}

namespace {

// Sweeps the cutter (and the tool changes of `path`) along every segment below the top.
void carve_into(HeightMap& m, const Toolpath& path, const Cutter& cutter) {
  const float top = m.top;
  const auto slope = static_cast<float>(1 / std::tan(cutter.v_angle / 2 * kPi / 180));
  Profile profile{cutter.shape, static_cast<float>(cutter.diameter / 2), slope};
  // A sloped segment is swept as pieces that each fall at most a cell, at the lower end of
  // each: the depth is exact to a cell, and every piece is a flat sweep.
  Eigen::Vector3f from = path.start;
  auto change = path.cutter_changes.begin();
  for (std::size_t i = 0; i < path.segments.size(); ++i) {
    for (; change != path.cutter_changes.end() && change->first <= i; ++change)
      profile.radius = static_cast<float>(change->diameter / 2);  // a tool change (M6, VC)
    const ToolpathSegment& s = path.segments[i];
    const Eigen::Vector3f to(s.x, s.y, s.z);
    if (std::min(from.z(), to.z()) < top) {
      const float flat = (to - from).head<2>().norm();
      const int pieces =
          flat < m.cell
              ? 1
              : std::max(1, static_cast<int>(std::ceil(std::abs(to.z() - from.z()) / m.cell)));
      for (int k = 0; k < pieces; ++k) {
        const Eigen::Vector3f a = from + (to - from) * (static_cast<float>(k) / pieces);
        const Eigen::Vector3f b = from + (to - from) * (static_cast<float>(k + 1) / pieces);
        sweep(m, profile, a.head<2>(), b.head<2>(), std::min(a.z(), b.z()));
      }
    }
    from = to;
  }
}

}  // namespace

HeightMap carve(const Toolpath& path, const Cutter& cutter, const Eigen::AlignedBox3f& stock,
                int max_cells) {
  HeightMap m;
  m.top = stock.max().z();
  m.bottom = stock.min().z();
  const Eigen::Vector2f size = stock.sizes().head<2>().cwiseMax(Eigen::Vector2f::Constant(1e-6f));
  m.cell = size.maxCoeff() / static_cast<float>(std::max(2, max_cells) - 1);
  m.nx = static_cast<int>(std::lround(size.x() / m.cell)) + 1;
  m.ny = static_cast<int>(std::lround(size.y() / m.cell)) + 1;
  m.x0 = stock.min().x();
  m.y0 = stock.min().y();
  m.z.assign(static_cast<std::size_t>(m.nx) * m.ny, m.top);
  carve_into(m, path, cutter);
  return m;
}

HeightMap carve(const Toolpath& path, const Cutter& cutter, float top, int max_cells) {
  float r = static_cast<float>(cutter.diameter / 2);  // the largest cutter's, for the margin
  for (const Toolpath::CutterChange& c : path.cutter_changes)
    r = std::max(r, static_cast<float>(c.diameter / 2));
  // The stock: the XY extent of what goes below its top.
  Eigen::AlignedBox2f area;
  float lowest = top;
  Eigen::Vector3f from = path.start;
  for (const ToolpathSegment& s : path.segments) {
    const Eigen::Vector3f to(s.x, s.y, s.z);
    if (std::min(from.z(), to.z()) < top) {
      area.extend(from.head<2>()).extend(to.head<2>());
      lowest = std::min({lowest, from.z(), to.z()});
    }
    from = to;
  }
  HeightMap m;
  m.top = top;
  if (area.isEmpty()) area.extend(path.start.head<2>());  // nothing cut: a small block
  const float margin = r + 0.05f * std::max(area.sizes().maxCoeff(), 4 * r);
  area.min().array() -= margin;
  area.max().array() += margin;
  m.cell = area.sizes().maxCoeff() / static_cast<float>(std::max(2, max_cells) - 1);
  m.nx = static_cast<int>(std::ceil(area.sizes().x() / m.cell)) + 1;
  m.ny = static_cast<int>(std::ceil(area.sizes().y() / m.cell)) + 1;
  m.x0 = area.min().x();
  m.y0 = area.min().y();
  m.bottom = lowest - std::max(0.25f * (top - lowest), 2 * m.cell);
  m.z.assign(static_cast<std::size_t>(m.nx) * m.ny, top);
  carve_into(m, path, cutter);
  return m;
}

Projection material_projection(const HeightMap& map, const PreviewOptions& opts) {
  return Projection(opts.view, stock_box(map), opts.width, opts.height);
}

Image render_material(const HeightMap& map, const PreviewOptions& opts, const Toolpath* path) {
  const Projection proj = material_projection(map, opts);
  preview_detail::Canvas canvas(proj.width(), proj.height(), palette::background);
  // Light from the viewer's upper left; the colour goes from light wood at the top to dark
  // at the deepest cut, so depth reads in the top view as well.
  const Eigen::Vector3f light =
      (proj.axes().transpose() * Eigen::Vector3f(-0.5f, 0.6f, 1.0f)).normalized();
  const float depth_range = std::max(map.top - map.bottom, 1e-6f);
  auto shade = [&](const Eigen::Vector3f& normal, float z) {
    const Eigen::Vector3f kTop(222, 184, 135), kDeep(110, 72, 40);
    const float deep = std::clamp((map.top - z) / depth_range, 0.0f, 1.0f);
    const float lit = 0.35f + 0.65f * std::max(0.0f, normal.normalized().dot(light));
    const Eigen::Vector3f c = (kTop + (kDeep - kTop) * deep) * lit;
    return Rgb{static_cast<std::uint8_t>(c.x()), static_cast<std::uint8_t>(c.y()),
               static_cast<std::uint8_t>(c.z())};
  };
  auto quad = [&](const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                  const Eigen::Vector3f& d) {
    // Normals point out of the stock: the corners go counter-clockwise seen from outside.
    Eigen::Vector3f n = (c - a).cross(d - b);
    if (n.dot(proj.axes().row(2).transpose()) < 0) return;  // faces away: hidden
    const Rgb colour = shade(n, std::min({a.z(), b.z(), c.z(), d.z()}));
    canvas.triangle(proj(a), proj(b), proj(c), colour);
    canvas.triangle(proj(a), proj(c), proj(d), colour);
  };
  for (int j = 0; j + 1 < map.ny; ++j)
    for (int i = 0; i + 1 < map.nx; ++i)
      quad(vertex(map, i, j, map.at(i, j)), vertex(map, i + 1, j, map.at(i + 1, j)),
           vertex(map, i + 1, j + 1, map.at(i + 1, j + 1)),
           vertex(map, i, j + 1, map.at(i, j + 1)));
  // The four sides, from the surface's edge down to the bottom.
  for (int i = 0; i + 1 < map.nx; ++i) {
    const int j = map.ny - 1;
    quad(vertex(map, i, 0, map.bottom), vertex(map, i + 1, 0, map.bottom),
         vertex(map, i + 1, 0, map.at(i + 1, 0)), vertex(map, i, 0, map.at(i, 0)));
    quad(vertex(map, i + 1, j, map.bottom), vertex(map, i, j, map.bottom),
         vertex(map, i, j, map.at(i, j)), vertex(map, i + 1, j, map.at(i + 1, j)));
  }
  for (int j = 0; j + 1 < map.ny; ++j) {
    const int i = map.nx - 1;
    quad(vertex(map, 0, j + 1, map.bottom), vertex(map, 0, j, map.bottom),
         vertex(map, 0, j, map.at(0, j)), vertex(map, 0, j + 1, map.at(0, j + 1)));
    quad(vertex(map, i, j, map.bottom), vertex(map, i, j + 1, map.bottom),
         vertex(map, i, j + 1, map.at(i, j + 1)), vertex(map, i, j, map.at(i, j)));
  }
  if (opts.dimensions && path) preview_detail::draw_dimensions(canvas, proj, *path);
  return canvas.take();
}

}  // namespace gantry
