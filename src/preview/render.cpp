// The toolpath as a picture: one projection and one set of line styles for the PNG and
// the SVG output.
#include "gantry/preview/render.hpp"

#include <fmt/format.h>  // SVG text
#include <stb_image_write.h>

#include <algorithm>  // max, min
#include <array>
#include <cmath>      // sqrt, pow, log10
#include <limits>

#include "canvas.hpp"                 // Canvas
#include "pixel_font.hpp"             // kGlyphAdvance
#include "gantry/core/text_file.hpp"  // write_file_atomically

namespace gantry {
namespace {

// How each segment is drawn.
enum class Style : std::uint8_t { Hidden, Deep, Upper, Jog, Keypad };

Rgb colour(Style s) {
  switch (s) {
    case Style::Deep:
      return palette::cut_deep;
    case Style::Upper:
      return palette::cut_upper;
    case Style::Jog:
      return palette::jog;
    case Style::Keypad:
      return palette::keypad;
    case Style::Hidden:
      break;
  }
  return palette::background;
}

Eigen::Vector3f end_of(const ToolpathSegment& s) {
  return {s.x, s.y, s.z};
}

// A cut is "deep" at the lowest Z its command (source line) cuts to, "upper" above it: a
// tab, a ramp or an upper pass stands out from the finished depth.
std::vector<Style> styles(const Toolpath& path, bool leading_jogs) {
  const std::vector<ToolpathSegment>& seg = path.segments;
  std::vector<float> z_low;  // by source line
  Eigen::Vector3f from = path.start;
  for (const ToolpathSegment& s : seg) {
    if (s.kind == PathKind::Cut) {
      if (s.line >= z_low.size()) z_low.resize(s.line + 1, std::numeric_limits<float>::infinity());
      z_low[s.line] = std::min({z_low[s.line], from.z(), s.z});
    }
    from = end_of(s);
  }
  std::vector<Style> out(seg.size(), Style::Hidden);
  bool cut_yet = leading_jogs;
  from = path.start;
  for (std::size_t i = 0; i < seg.size(); ++i) {
    const ToolpathSegment& s = seg[i];
    cut_yet = cut_yet || s.kind == PathKind::Cut;
    if (cut_yet) switch (s.kind) {
        case PathKind::Cut:
          out[i] = std::max(from.z(), s.z) <= z_low[s.line] + 1e-6f ? Style::Deep : Style::Upper;
          break;
        case PathKind::Jog:
          out[i] = Style::Jog;
          break;
        case PathKind::Keypad:
          out[i] = Style::Keypad;
          break;
      }
    from = end_of(s);
  }
  return out;
}

// The order styles are drawn in: the cuts over the jogs that pass above them.
constexpr Style kDrawOrder[] = {Style::Jog, Style::Upper, Style::Deep, Style::Keypad};

// The table envelope's outline: its XY rectangle at Z 0 (the material surface by the usual
// zeroing), in machine coordinates.
// The soft limits are in the profile's units; the path in the units the file left in force.
std::array<Eigen::Vector3f, 4> table_corners(const Settings& s, Units units) {
  const double k = units_factor(s.units, units);
  const auto x0 = static_cast<float>(k * s.axes[0].min), x1 = static_cast<float>(k * s.axes[0].max);
  const auto y0 = static_cast<float>(k * s.axes[1].min), y1 = static_cast<float>(k * s.axes[1].max);
  return {{{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}};
}

// The stock's top rectangle, counter-clockwise from its front left corner.
std::array<Eigen::Vector3f, 4> stock_corners(const Eigen::AlignedBox3f& b) {
  const float z = b.max().z();
  return {{{b.min().x(), b.min().y(), z},
           {b.max().x(), b.min().y(), z},
           {b.max().x(), b.max().y(), z},
           {b.min().x(), b.max().y(), z}}};
}

float stroke(const Projection& p) {
  return std::max(1.0f, static_cast<float>(std::max(p.width(), p.height())) / 400);
}

Eigen::AlignedBox3f drawn_box(const Toolpath& path, const std::vector<Style>& style,
                              const Settings& settings, const PreviewOptions& opts) {
  Eigen::AlignedBox3f box;
  Eigen::Vector3f from = path.start;
  for (std::size_t i = 0; i < style.size(); ++i) {
    if (style[i] != Style::Hidden) box.extend(from).extend(end_of(path.segments[i]));
    from = end_of(path.segments[i]);
  }
  if (opts.table)
    for (const Eigen::Vector3f& c : table_corners(settings, path.units)) box.extend(c);
  if (opts.stock) box.extend(*opts.stock);
  return box;
}

Projection line_projection(const Toolpath& path, const std::vector<Style>& style,
                           const Settings& settings, const PreviewOptions& opts) {
  return Projection(opts.view, drawn_box(path, style, settings, opts), opts.width,
                    opts.height);
}

// The first and last points drawn; nullopt when nothing is.
std::optional<std::pair<Eigen::Vector3f, Eigen::Vector3f>> drawn_ends(
    const Toolpath& path, const std::vector<Style>& style) {
  std::optional<std::pair<Eigen::Vector3f, Eigen::Vector3f>> ends;
  for (std::size_t i = 0; i < style.size(); ++i)
    if (style[i] != Style::Hidden) {
      const Eigen::Vector3f from = i ? end_of(path.segments[i - 1]) : path.start;
      if (!ends) ends.emplace(from, from);
      ends->second = end_of(path.segments[i]);
    }
  return ends;
}

// The scale bar's length: 1, 2 or 5 times a power of ten, at most a quarter of the picture.
double bar_length(const Projection& p) {
  const double most = 0.25 * p.width() / p.pixels_per_unit();
  double step = std::pow(10.0, std::floor(std::log10(most)));
  for (double k : {5.0, 2.0, 1.0})
    if (k * step <= most) return k * step;
  return step;
}

// The scale bar's label ("2 in") and the path's bounding dimensions, one text per axis
// ("X 0.0000 to 12.0000 (12.0000 in)"), as both pictures write them.
std::string bar_label(double bar, Units units) {
  return fmt::format("{:g} {}", bar, units_name(units));
}
std::array<std::string, 3> dimension_texts(const Toolpath& path) {
  const Eigen::AlignedBox3f& b = path.bounds;
  const Eigen::Vector3f size = b.sizes();
  const char* u = units_name(path.units);
  std::array<std::string, 3> out;
  for (int i = 0; i < 3; ++i)
    out[i] = fmt::format("{} {:.4f} to {:.4f} ({:.4f} {})", "XYZ"[i], b.min()[i], b.max()[i],
                         size[i], u);
  return out;
}

}  // namespace

const char* view_name(View v) {
  switch (v) {
    case View::Top:
      return "top";
    case View::Iso:
      return "iso";
    case View::Front:
      return "front";
    case View::Side:
      return "side";
  }
  return "?";
}

std::optional<View> parse_view(std::string_view name) {
  for (View v : {View::Top, View::Iso, View::Front, View::Side})
    if (name == view_name(v)) return v;
  return std::nullopt;
}

Projection::Projection(View view, const Eigen::AlignedBox3f& box, int width, int height)
    : width_(width), height_(height) {
  const float r2 = std::sqrt(0.5f), r3 = std::sqrt(1.0f / 3), r6 = std::sqrt(1.0f / 6);
  switch (view) {
    case View::Top:
      axes_ << 1, 0, 0, 0, 1, 0, 0, 0, 1;
      break;
    case View::Front:
      axes_ << 1, 0, 0, 0, 0, 1, 0, -1, 0;
      break;
    case View::Side:
      axes_ << 0, 1, 0, 0, 0, 1, 1, 0, 0;
      break;
    // From (1, -1, 1): the front right corner of the table, above it.
    case View::Iso:
      axes_ << r2, r2, 0, -r6, r6, 2 * r6, r3, -r3, r3;
      break;
  }
  // The box's extent across the picture, from its eight corners.
  Eigen::Vector2f lo = Eigen::Vector2f::Constant(std::numeric_limits<float>::infinity());
  Eigen::Vector2f hi = -lo;
  const Eigen::AlignedBox3f b =
      box.isEmpty() ? Eigen::AlignedBox3f(Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()) : box;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector2f uv =
        (axes_ * b.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c))).head<2>();
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
  }
  // A point or a line still gets a picture: at least a hundredth of the larger extent.
  const float big = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-6f});
  const Eigen::Vector2f span = (hi - lo).cwiseMax(Eigen::Vector2f::Constant(big / 100));
  constexpr float kFill = 0.9f;  // 5 % margin on each side
  if (height_ <= 0)
    height_ = std::max(1, static_cast<int>(std::lround(width_ * span.y() / span.x())));
  scale_ = kFill * std::min(width_ / span.x(), height_ / span.y());
  const Eigen::Vector2f mid = (lo + hi) / 2;
  offset_ = Eigen::Vector2f(width_ / 2.0f - scale_ * mid.x(), height_ / 2.0f + scale_ * mid.y());
}

Eigen::Vector3f Projection::operator()(const Eigen::Vector3f& p) const {
  const Eigen::Vector3f q = axes_ * p;
  return {offset_.x() + scale_ * q.x(), offset_.y() - scale_ * q.y(), q.z()};
}

Eigen::AlignedBox3f preview_box(const Toolpath& path, const Settings& settings,
                                const PreviewOptions& opts) {
  return drawn_box(path, styles(path, opts.leading_jogs), settings, opts);
}

Rgb Image::at(int x, int y) const {
  const std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  return {p[0], p[1], p[2]};
}

// The SVG's scale bar (bottom left) and bounding dimensions (top left), in the pixel font:
// its pixels twice as big from 1000 pixels up.
void preview_detail::draw_dimensions(Canvas& canvas, const Projection& proj, const Toolpath& path) {
  constexpr Rgb black = palette::text;
  const int k = std::max(1, std::min(proj.width(), proj.height()) / 500);
  const double bar = bar_length(proj);
  const int bar_px = static_cast<int>(std::lround(bar * proj.pixels_per_unit()));
  const int y = proj.height() - 8;
  const Eigen::Vector2f p0(8, static_cast<float>(y - 6)), p1(8, static_cast<float>(y)),
      p2(static_cast<float>(8 + bar_px), static_cast<float>(y)),
      p3(static_cast<float>(8 + bar_px), static_cast<float>(y - 6));
  canvas.line(p0, p1, black, 1);
  canvas.line(p1, p2, black, 1);
  canvas.line(p2, p3, black, 1);
  canvas.text(12 + bar_px, y - 7 * k, bar_label(bar, path.units), black, k);
  if (!path.bounds.isEmpty()) {
    const std::array<std::string, 3> dims = dimension_texts(path);
    const std::string one = dims[0] + ", " + dims[1] + ", " + dims[2];
    const int advance = kGlyphAdvance * k;
    if (8 + static_cast<int>(one.size()) * advance <= proj.width())
      canvas.text(8, 8, one, black, k);
    else
      for (int i = 0; i < 3; ++i) canvas.text(8, 8 + i * 10 * k, dims[i], black, k);
  }

}

Image render_lines(const Toolpath& path, const Settings& settings, const PreviewOptions& opts) {
  const std::vector<Style> style = styles(path, opts.leading_jogs);
  const Projection proj = line_projection(path, style, settings, opts);
  preview_detail::Canvas canvas(proj.width(), proj.height(), palette::background);
  const float w = stroke(proj);
  const int px = static_cast<int>(std::lround(w));
  auto at = [&](const Eigen::Vector3f& p) -> Eigen::Vector2f { return proj(p).head<2>(); };
  if (opts.table) {
    const auto c = table_corners(settings, path.units);
    for (int i = 0; i < 4; ++i) canvas.line(at(c[i]), at(c[(i + 1) % 4]), palette::table, 1);
  }
  if (opts.stock) {
    const auto c = stock_corners(*opts.stock);
    for (int i = 0; i < 4; ++i) canvas.line(at(c[i]), at(c[(i + 1) % 4]), palette::stock, px);
  }
  for (Style pass : kDrawOrder) {
    Eigen::Vector2f from = at(path.start);
    for (std::size_t i = 0; i < style.size(); ++i) {
      const Eigen::Vector2f to = at(end_of(path.segments[i]));
      if (style[i] == pass)
        canvas.line(from, to, colour(pass), px, pass == Style::Jog ? 3 * px : 0);
      from = to;
    }
  }
  if (const auto ends = drawn_ends(path, style)) {
    canvas.dot(at(ends->first), 3 * w, palette::start);
    canvas.dot(at(ends->second), 2 * w, palette::end);
  }
  if (opts.dimensions) preview_detail::draw_dimensions(canvas, proj, path);
  return canvas.take();
}

std::string render_svg(const Toolpath& path, const Settings& settings, const PreviewOptions& opts) {
  const std::vector<Style> style = styles(path, opts.leading_jogs);
  const Projection proj = line_projection(path, style, settings, opts);
  const float w = stroke(proj);
  auto hex = [](Rgb c) { return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]); };
  auto at = [&](const Eigen::Vector3f& p) -> Eigen::Vector2f { return proj(p).head<2>(); };
  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"{2}\"/>\n"
      "<g fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\" "
      "stroke-width=\"{3:.3g}\">\n",
      proj.width(), proj.height(), hex(palette::background), w);
  if (opts.table) {
    std::string points;
    for (const Eigen::Vector3f& c : table_corners(settings, path.units))
      points += fmt::format("{}{:.2f},{:.2f}", points.empty() ? "" : " ", at(c).x(), at(c).y());
    out += fmt::format("<polygon stroke=\"{}\" stroke-width=\"1\" points=\"{}\"/>\n",
                       hex(palette::table), points);
  }
  if (opts.stock) {
    std::string points;
    for (const Eigen::Vector3f& c : stock_corners(*opts.stock))
      points += fmt::format("{}{:.2f},{:.2f}", points.empty() ? "" : " ", at(c).x(), at(c).y());
    out += fmt::format("<polygon class=\"stock\" stroke=\"{}\" points=\"{}\"/>\n",
                       hex(palette::stock), points);
  }
  // One path per run of one style; the runs of each style drawn in kDrawOrder's order.
  for (Style pass : kDrawOrder) {
    const std::string look = pass == Style::Jog
                                 ? fmt::format("stroke=\"{}\" stroke-dasharray=\"{:.3g} {:.3g}\"",
                                               hex(colour(pass)), 3 * w, 3 * w)
                                 : fmt::format("stroke=\"{}\"", hex(colour(pass)));
    Eigen::Vector2f from = at(path.start);
    std::string d;
    for (std::size_t i = 0; i <= style.size(); ++i) {
      if (i == style.size() || style[i] != pass) {  // a run ends
        if (!d.empty()) out += fmt::format("<path {} d=\"{}\"/>\n", look, d);
        d.clear();
      }
      if (i == style.size()) break;
      const Eigen::Vector2f to = at(end_of(path.segments[i]));
      if (style[i] == pass) {
        if (d.empty()) d = fmt::format("M{:.2f} {:.2f}", from.x(), from.y());
        d += fmt::format(" L{:.2f} {:.2f}", to.x(), to.y());
      }
      from = to;
    }
  }
  if (const auto ends = drawn_ends(path, style)) {
    out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.3g}\" fill=\"{}\"/>\n",
                       at(ends->first).x(), at(ends->first).y(), 3 * w, hex(palette::start));
    out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.3g}\" fill=\"{}\"/>\n",
                       at(ends->second).x(), at(ends->second).y(), 2 * w, hex(palette::end));
  }
  out += "</g>\n";
  if (!opts.dimensions) return out + "</svg>\n";
  // The scale bar (lengths in the picture's plane) and the path's bounding dimensions, in
  // the units the file left in force.
  const char* units = units_name(path.units);
  const double bar = bar_length(proj);
  const std::string label = bar_label(bar, path.units);
  const float bar_px = static_cast<float>(bar) * proj.pixels_per_unit();
  const float y = static_cast<float>(proj.height()) - 8;
  out += fmt::format(
      "<g class=\"scale\" stroke=\"#000000\" stroke-width=\"1\">"
      "<polyline fill=\"none\" points=\"8,{2:.2f} 8,{0:.2f} {1:.2f},{0:.2f} {1:.2f},{2:.2f}\"/>"
      "<text x=\"{3:.2f}\" y=\"{0:.2f}\" font-family=\"sans-serif\" font-size=\"11\" "
      "stroke=\"none\" fill=\"#000000\">{4}</text></g>\n",
      y, 8 + bar_px, y - 6, 12 + bar_px, label);
  if (!path.bounds.isEmpty()) {
    const std::array<std::string, 3> dims = dimension_texts(path);
    out += fmt::format(
        "<text class=\"dimensions\" x=\"8\" y=\"16\" font-family=\"sans-serif\" "
        "font-size=\"11\" fill=\"#000000\">{}, {}, {}</text>\n",
        dims[0], dims[1], dims[2]);
  }
  // The cutters: VC's at the start, then each tool change with the line it came at.
  // A named tool (&Tool + C9, M6) is given as T<n> before its diameter.
  auto named = [](int tool) { return tool ? fmt::format("T{} ", tool) : std::string(); };
  std::string cutters = fmt::format("{}{:g} {}", named(path.tool), path.cutter_diameter, units);
  for (const Toolpath::CutterChange& c : path.cutter_changes)
    cutters += fmt::format(", {}{:g} {} from line {}", named(c.tool), c.diameter, units, c.line);
  out += fmt::format(
      "<text class=\"tools\" x=\"8\" y=\"30\" font-family=\"sans-serif\" font-size=\"11\" "
      "fill=\"#000000\">cutter{} {}</text>\n",
      path.cutter_changes.empty() ? "" : "s", cutters);
  out += "</svg>\n";
  return out;
}

bool write_png(const std::string& path, const Image& image) {
  std::string bytes;
  const int ok = stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
      },
      &bytes, image.width, image.height, 3, image.rgb.data(), image.width * 3);
  return ok && write_file_atomically(path, bytes);
}

}  // namespace gantry
