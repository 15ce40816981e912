// The part file a converted drawing becomes: a jog to each path's start at safe Z, a plunge
// to the cutting Z, then M2 lines and CG arcs; paths that continue one another are cut
// without lifting.
#include "part_writer.hpp"

#include <fmt/format.h>  // the part file's text

#include <cmath>  // hypot

#include "gantry/convert/part_file.hpp"  // PartText, part_number

namespace gantry::convert {

Conversion write_part(const std::vector<Path>& paths, const ConvertOptions& o,
                      std::string_view format, double scale,
                      const std::map<std::string, int>& skipped) {
  Conversion out;
  PartText body;
  auto line = [&](const std::string& l) { body.line(l); };
  auto at = [&](const Point& p) {
    return fmt::format("{}, {}", part_number(p.x * scale), part_number(p.y * scale));
  };
  bool down = false;
  std::string here;  // where the tool is, as written
  Point cur;
  for (const Path& path : paths) {
    bool moves = false;
    for (const Segment& s : path.segments) moves |= s.arc || at(s.end) != at(path.start);
    if (!moves) continue;  // a point, or a pen-up move: nothing to cut
    if (!down || at(path.start) != here) {
      if (down) body.jog_z(o.safe_z);
      line(fmt::format("J2, {}", at(path.start)));
      body.move_z(o.cut_z);
      ++out.paths;
      down = true;
    }
    cur = path.start;
    here = at(cur);
    for (const Segment& s : path.segments) {
      const std::string to = at(s.end);
      const double r = std::hypot(s.centre.x - cur.x, s.centre.y - cur.y) * scale;
      if (s.arc && r > 1e-4) {
        // Parameter 13 (no pull up) keeps the tool down for what follows on the path.
        line(fmt::format("CG, , {}, {}, {}, T, {}, , , , , , 1", to,
                         part_number((s.centre.x - cur.x) * scale),
                         part_number((s.centre.y - cur.y) * scale), s.clockwise ? 1 : -1));
      } else if (to != here) {
        line(fmt::format("M2, {}", to));
      }
      cur = s.end;
      here = to;
    }
  }
  if (down) body.jog_z(o.safe_z);
  for (const auto& [what, n] : skipped) out.notes.push_back(fmt::format("{} {}", n, what));

  const char* u = units_name(o.units);
  out.text = fmt::format("' Part file converted by Gantry FC from {} ({})\n", o.source, format);
  out.text += fmt::format("' {} path{}; 1 drawing unit = {} {}; cut at Z {}, jogs at Z {}\n",
                          out.paths, out.paths == 1 ? "" : "s", fmt::format("{:.6g}", scale), u,
                          part_number(o.cut_z), part_number(o.safe_z));
  for (const std::string& n : out.notes) out.text += fmt::format("' Not converted: {}\n", n);
  out.text += "' For deeper passes, run it with FP's repetitions and plunge.\n";
  out.text += fmt::format("SA\nJZ, {}\n", part_number(o.safe_z));
  out.text += body.text();
  return out;
}

}  // namespace gantry::convert
