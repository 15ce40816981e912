// What both converters share: the paths a drawing holds and the part file written from them.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/convert/to_sbp.hpp"

namespace gantry::convert {

struct Point {
  double x = 0, y = 0;
};

// From the end of the previous segment (or the path's start) to `end`: a line, or an arc
// about `centre`.
struct Segment {
  Point end;
  bool arc = false;
  Point centre;
  bool clockwise = false;
};

inline Segment line_to(Point end) {
  Segment s;
  s.end = end;
  return s;
}

struct Path {
  Point start;
  std::vector<Segment> segments;
};

// The part file cutting `paths` (in drawing units; `scale` part-file units per drawing
// unit). `format` names the drawing's kind in the header; `skipped` counts what was left
// out, by name, for the notes.
Conversion write_part(const std::vector<Path>& paths, const ConvertOptions& options,
                      std::string_view format, double scale,
                      const std::map<std::string, int>& skipped);

}  // namespace gantry::convert
