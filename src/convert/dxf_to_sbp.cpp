// DXF (text form): the lines, arcs, circles and polylines of the ENTITIES section become
// the paths of a part file.
#include <fmt/format.h>  // messages

#include <charconv>  // from_chars
#include <cmath>     // atan, cos, sin, hypot
#include <numbers>   // pi
#include <optional>
#include <string>
#include <utility>  // pair

#include "gantry/convert/to_sbp.hpp"
#include "gantry/core/diagnostic.hpp"  // fail, file_loc
#include "gantry/core/text.hpp"        // trim_front, trim_back
#include "part_writer.hpp"

namespace gantry {

using convert::Path;
using convert::Point;
using convert::Segment;

namespace {

// One group: its code, its value (trimmed) and the line of the value, for messages.
struct Group {
  int code = 0;
  std::string value;
  int line = 0;
};

// A value without its blanks, and a line end's '\r' (only at the end: a value never starts with one).
std::string trimmed(std::string_view s) {
  return std::string(ascii::trim_front(ascii::trim_back(s, " \t\r"), " \t"));
}

std::vector<Group> read_groups(std::string_view text, const std::string& source) {
  if (text.starts_with("AutoCAD Binary DXF"))
    fail(file_loc(source, 1),
         "FC: this is a binary DXF; save the drawing as a text (ASCII) DXF and convert that");
  std::vector<std::string> lines;
  for (size_t b = 0; b < text.size();) {
    const size_t e = text.find('\n', b);
    lines.push_back(trimmed(text.substr(b, e == std::string_view::npos ? e : e - b)));
    b = e == std::string_view::npos ? text.size() : e + 1;
  }
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  std::vector<Group> out;
  for (size_t i = 0; i < lines.size(); i += 2) {
    const std::string& c = lines[i];
    Group g;
    const auto r = std::from_chars(c.data(), c.data() + c.size(), g.code);
    if (c.empty() || r.ec != std::errc{} || r.ptr != c.data() + c.size())
      fail(file_loc(source, static_cast<int>(i + 1)),
           fmt::format("FC: expected a DXF group code (a whole number) on this line, found "
                       "'{}'",
                       c));
    if (i + 1 >= lines.size())
      fail(file_loc(source, static_cast<int>(i + 1)),
           fmt::format("FC: group code {} has no value line; the DXF file is cut short", g.code));
    g.value = lines[i + 1];
    g.line = static_cast<int>(i + 2);
    out.push_back(std::move(g));
  }
  return out;
}

// An entity: its type and its groups (up to the next group 0).
struct Entity {
  std::string type;
  int line = 0;
  std::vector<Group> groups;
};

class Reader {
 public:
  Reader(const std::string& source) : source_(source) {}

  double number(const Group& g) const {
    double v = 0;
    const char* b = g.value.data();
    const char* e = b + g.value.size();
    if (b != e && *b == '+') ++b;
    const auto r = std::from_chars(b, e, v);
    if (b == e || r.ec != std::errc{} || r.ptr != e)
      fail(file_loc(source_, g.line),
           fmt::format("FC: group {} should hold a number, not '{}'", g.code, g.value));
    return v;
  }
  // The first group `code` of the entity, as a number; `fallback` when absent (nullopt: it
  // must be there).
  double get(const Entity& en, int code, std::optional<double> fallback = std::nullopt) const {
    for (const Group& g : en.groups)
      if (g.code == code) return number(g);
    if (!fallback)
      fail(file_loc(source_, en.line),
           fmt::format("FC: this {} has no group {}, which it needs", en.type, code));
    return *fallback;
  }
  // Entities in their object coordinate system with the extrusion (0, 0, -1), as mirrored
  // drawings save them: X is reversed, and so is every arc's direction.
  bool mirrored(const Entity& en) const { return get(en, 230, 1.0) < 0; }

 private:
  const std::string& source_;
};

Point mirror(Point p, bool m) {
  return m ? Point{-p.x, p.y} : p;
}

// A polyline's segment from `a` to `b` with a DXF bulge (the tangent of a quarter of the
// included angle; positive counter-clockwise).
Segment bulge_segment(Point a, Point b, double bulge, bool m) {
  Segment s = convert::line_to(mirror(b, m));
  if (std::abs(bulge) < 1e-12) return s;
  const double dx = b.x - a.x, dy = b.y - a.y, chord = std::hypot(dx, dy);
  if (chord == 0) return s;
  // The centre is off the chord's middle along its left normal.
  const double off = chord * (1 - bulge * bulge) / (4 * bulge);
  const Point centre{(a.x + b.x) / 2 - dy / chord * off, (a.y + b.y) / 2 + dx / chord * off};
  s.arc = true;
  s.centre = mirror(centre, m);
  s.clockwise = (bulge < 0) != m;
  return s;
}

// A polyline through `vertices` (each with the bulge to the next), closed or not.
Path polyline(const std::vector<std::pair<Point, double>>& vertices, bool closed, bool m) {
  Path p{mirror(vertices.front().first, m), {}};
  for (size_t k = 0; k + 1 < vertices.size(); ++k)
    p.segments.push_back(
        bulge_segment(vertices[k].first, vertices[k + 1].first, vertices[k].second, m));
  if (closed && vertices.size() > 1)
    p.segments.push_back(
        bulge_segment(vertices.back().first, vertices.front().first, vertices.back().second, m));
  return p;
}

// Millimetres per drawing unit for $INSUNITS; 0 when the drawing says none.
double insunits_mm(int code) {
  switch (code) {
    case 1:
      return 25.4;
    case 2:
      return 304.8;
    case 4:
      return 1;
    case 5:
      return 10;
    case 6:
      return 1000;
    case 8:
      return 25.4e-6;
    case 9:
      return 0.0254;
    case 10:
      return 914.4;
    default:
      return 0;
  }
}

}  // namespace

Conversion dxf_to_sbp(std::string_view text, const ConvertOptions& o) {
  const std::vector<Group> groups = read_groups(text, o.source);
  const Reader rd(o.source);
  std::vector<Path> paths;
  std::map<std::string, int> skipped;
  double unit_mm = 0;
  // A POLYLINE's vertices are the VERTEX entities that follow it, up to SEQEND.
  std::optional<Entity> poly;
  std::vector<std::pair<Point, double>> vertices;

  auto finish_polyline = [&] {
    if (!poly) return;
    const int flags = static_cast<int>(rd.get(*poly, 70, 0.0));
    if (flags & (16 | 64))
      ++skipped["POLYLINE mesh(es)"];
    else if (!vertices.empty())
      paths.push_back(polyline(vertices, flags & 1, rd.mirrored(*poly)));
    poly.reset();
    vertices.clear();
  };

  auto entity = [&](const Entity& en) {
    const std::string& t = en.type;
    if (t == "VERTEX" && poly) {
      if (!(static_cast<int>(rd.get(en, 70, 0.0)) & 16))  // not a spline's control point
        vertices.push_back({{rd.get(en, 10), rd.get(en, 20)}, rd.get(en, 42, 0.0)});
      return;
    }
    finish_polyline();
    const bool m = rd.mirrored(en);
    if (t == "LINE") {
      paths.push_back(
          {{rd.get(en, 10), rd.get(en, 20)}, {convert::line_to({rd.get(en, 11), rd.get(en, 21)})}});
    } else if (t == "ARC" || t == "CIRCLE") {
      const Point c{rd.get(en, 10), rd.get(en, 20)};
      const double r = rd.get(en, 40);
      const double rad = std::numbers::pi / 180;
      const double a0 = t == "ARC" ? rd.get(en, 50) : 0, a1 = t == "ARC" ? rd.get(en, 51) : 0;
      const Point s{c.x + r * std::cos(a0 * rad), c.y + r * std::sin(a0 * rad)};
      const Point e{c.x + r * std::cos(a1 * rad), c.y + r * std::sin(a1 * rad)};
      Segment seg{mirror(e, m), true, mirror(c, m), m};
      if (t == "CIRCLE") seg.end = mirror(s, m);  // all the way round
      paths.push_back({mirror(s, m), {seg}});
    } else if (t == "LWPOLYLINE") {
      std::vector<std::pair<Point, double>> v;
      for (const Group& g : en.groups) {
        if (g.code == 10) v.push_back({{rd.number(g), 0}, 0});
        if (g.code == 20 && !v.empty()) v.back().first.y = rd.number(g);
        if (g.code == 42 && !v.empty()) v.back().second = rd.number(g);
      }
      if (!v.empty()) paths.push_back(polyline(v, static_cast<int>(rd.get(en, 70, 0.0)) & 1, m));
    } else if (t == "POLYLINE") {
      poly = en;
    } else if (t != "SEQEND") {
      ++skipped[t + " entity(ies)"];
    }
  };

  std::string section;
  std::optional<Entity> current;
  for (size_t i = 0; i < groups.size(); ++i) {
    const Group& g = groups[i];
    if (g.code == 0) {
      if (current) entity(*current);
      current.reset();
      if (g.value == "SECTION") {
        section = i + 1 < groups.size() && groups[i + 1].code == 2 ? groups[i + 1].value : "";
        continue;
      }
      if (g.value == "ENDSEC") {
        finish_polyline();
        section.clear();
        continue;
      }
      if (section == "ENTITIES") current = Entity{g.value, g.line, {}};
      continue;
    }
    if (current) {
      current->groups.push_back(g);
    } else if (section == "HEADER" && g.code == 9 && g.value == "$INSUNITS" &&
               i + 1 < groups.size() && groups[i + 1].code == 70) {
      unit_mm = insunits_mm(static_cast<int>(rd.number(groups[i + 1])));
    }
  }
  if (current) entity(*current);
  finish_polyline();
  double scale = o.scale;
  if (!(scale > 0)) scale = unit_mm == 0 ? 1 : unit_mm / (o.units == Units::Millimetres ? 1 : 25.4);
  return convert::write_part(paths, o, "DXF", scale, skipped);
}

}  // namespace gantry
